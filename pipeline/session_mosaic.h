// The mosaic of a session with several runs (pipeline/session_outputs.h), on the world
// lattice of GlobalMap (backend/global_map.h).
#pragma once

#include <opencv2/core.hpp>

#include "imaging/image_grid.h"
#include "pipeline/app_config.h"
#include "session/session_data.h"

namespace uwbsar::pipeline {

/// The mosaic (CV_32FC1, 0 = unobserved), its grid and the observed mask (CV_8UC1).
/// `reference_percentile`: kNormalizedMax's per-run reference level (that percentile of the
/// run's observed pixels, as the occupancy rule takes it).
cv::Mat RenderSessionMosaic(const SessionData& session, double resolution_m, JoinedMosaic mode,
                            ImageGrid* grid, cv::Mat* observed, double reference_percentile);

/// The mosaic `config` asks for (session.joined_mosaic, slam.map_resolution_m,
/// slam.occupancy_reference_percentile).
cv::Mat RenderSessionMosaic(const SessionData& session, const Config& config, ImageGrid* grid,
                            cv::Mat* observed);

}  // namespace uwbsar::pipeline
