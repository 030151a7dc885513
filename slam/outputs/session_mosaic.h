// The mosaic of a session with several runs (slam/outputs/session_outputs.h), on the world
// lattice of GlobalMap (backend/global_map.h).
#pragma once

#include <limits>
#include <opencv2/core.hpp>

#include "imaging/image_grid.h"
#include "slam/app_config.h"
#include "slam/session/session_data.h"

namespace uwbsar::slam {

/// Throws InputError naming session.source (the session file; else the runs' inputs) and the
/// extent when the mosaic of `session` at `resolution_m` (GlobalMap's block-aligned lattice)
/// would hold more than `max_pixels` pixels: checked from the keyframes' tiles and poses before
/// anything is allocated (one keyframe moved 2 km would otherwise make a map of gigabytes).
void CheckSessionMosaicExtent(const SessionData& session, double resolution_m, double max_pixels);

/// The mosaic (CV_32FC1, 0 = unobserved), its grid and the observed mask (CV_8UC1).
/// `reference_percentile`: kNormalizedMax's per-run reference level (that percentile of the
/// run's observed pixels, as the occupancy rule takes it). `max_pixels`: see
/// CheckSessionMosaicExtent, checked first.
cv::Mat RenderSessionMosaic(const SessionData& session, double resolution_m, JoinedMosaic mode,
                            ImageGrid* grid, cv::Mat* observed, double reference_percentile,
                            double max_pixels = std::numeric_limits<double>::infinity());

/// The mosaic `config` asks for (session.joined_mosaic, slam.map_resolution_m,
/// slam.occupancy_reference_percentile), within limits.max_image_pixels.
cv::Mat RenderSessionMosaic(const SessionData& session, const Config& config, ImageGrid* grid,
                            cv::Mat* observed);

}  // namespace uwbsar::slam
