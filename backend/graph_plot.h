// A picture of a pose graph (`uwbsar optimize --png`): the odometry chain in black, accepted
// loops in blue above it and rejected loops in vermillion above both (Okabe-Ito colours),
// scaled to fit the image; slam/jobs/optimize_job frames it with axes and a legend.
#pragma once

#include <map>
#include <opencv2/core.hpp>
#include <vector>

#include "backend/pose_graph.h"
#include "imaging/image_grid.h"

namespace uwbsar {

inline const cv::Scalar kGraphOdometryBgr(0, 0, 0);
inline const cv::Scalar kGraphLoopBgr(178, 114, 0);         ///< blue #0072B2
inline const cv::Scalar kGraphRejectedLoopBgr(0, 94, 213);  ///< vermillion #D55E00

/// BGR image of at most size_px x size_px, white background; `reports` may be empty (no loop
/// colouring). `grid` (optional) gets the plot's metric geometry (x right, y up, equal scales).
cv::Mat PlotPoseGraph(const std::map<int, Pose2>& poses, const std::vector<PoseGraphEdge>& edges,
                      const std::vector<EdgeReport>& reports, int size_px = 1000,
                      ImageGrid* grid = nullptr);

}  // namespace uwbsar
