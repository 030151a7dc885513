// The mosaic of a session with several runs (pipeline/session_outputs.h), on the world
// lattice of GlobalMap (backend/global_map.h).
#pragma once

#include <opencv2/core.hpp>

#include "imaging/image_grid.h"
#include "session/session_data.h"
#include "slam/config.h"

namespace uwbsar::pipeline {

/// session.joined_mosaic (slam/session_config.h).
enum class SessionMosaic {
  kMean,          ///< every tile of every run averaged per pixel (as one run's map)
  kNormalizedMax  ///< each run's mean mosaic divided by its own reference level, then max
};

/// The mosaic (CV_32FC1, 0 = unobserved), its grid and the observed mask (CV_8UC1).
/// `reference_percentile`: kNormalizedMax's per-run reference level (that percentile of the
/// run's observed pixels, as the occupancy rule takes it).
cv::Mat RenderSessionMosaic(const SessionData& session, double resolution_m, SessionMosaic mode,
                            ImageGrid* grid, cv::Mat* observed, double reference_percentile);

/// The mosaic `config` asks for (session.joined_mosaic, slam.map_resolution_m,
/// slam.occupancy_reference_percentile).
cv::Mat RenderSessionMosaic(const SessionData& session, const Config& config, ImageGrid* grid,
                            cv::Mat* observed);

}  // namespace uwbsar::pipeline
