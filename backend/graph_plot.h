// A picture of a pose graph for reports: trajectory (odometry chain) in black,
// accepted loops in green, rejected loops in red, scaled to fit the image.
#pragma once

#include <map>
#include <opencv2/core.hpp>
#include <vector>

#include "backend/pose_graph.h"

namespace uwbsar {

/// BGR image of at most size_px x size_px; `reports` may be empty (no loop colouring).
cv::Mat PlotPoseGraph(const std::map<int, Pose2>& poses, const std::vector<PoseGraphEdge>& edges,
                      const std::vector<EdgeReport>& reports, int size_px = 1000);

}  // namespace uwbsar
