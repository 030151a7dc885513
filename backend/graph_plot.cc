#include "backend/graph_plot.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

namespace uwbsar {

cv::Mat PlotPoseGraph(const std::map<int, Pose2>& poses, const std::vector<PoseGraphEdge>& edges,
                      const std::vector<EdgeReport>& reports, int size_px, ImageGrid* grid) {
  double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
  for (const auto& [id, p] : poses) {
    lo_x = std::min(lo_x, p.x_m);
    hi_x = std::max(hi_x, p.x_m);
    lo_y = std::min(lo_y, p.y_m);
    hi_y = std::max(hi_y, p.y_m);
  }
  if (poses.empty()) {
    if (grid != nullptr) *grid = ImageGrid{0.0, 0.0, 1.0, size_px, size_px};
    return cv::Mat(size_px, size_px, CV_8UC3, cv::Scalar(255, 255, 255));
  }
  const int margin = 10;
  const double span = std::max({hi_x - lo_x, hi_y - lo_y, 1e-6});
  const double scale = (size_px - 2 * margin) / span;
  const int cols = static_cast<int>((hi_x - lo_x) * scale) + 2 * margin + 1;
  const int rows = static_cast<int>((hi_y - lo_y) * scale) + 2 * margin + 1;
  cv::Mat image(rows, cols, CV_8UC3, cv::Scalar(255, 255, 255));
  auto pixel = [&](const Pose2& p) {  // row 0 at the top: +y up
    return cv::Point(static_cast<int>(margin + (p.x_m - lo_x) * scale),
                     static_cast<int>(margin + (hi_y - p.y_m) * scale));
  };
  // The odometry chain first, loops above it (a loop is the thing to see), rejected loops
  // last. Okabe-Ito blue and vermillion: told apart with the common colour-vision deficiencies.
  for (int pass = 0; pass < 3; ++pass) {
    for (std::size_t i = 0; i < edges.size(); ++i) {
      const PoseGraphEdge& e = edges[i];
      const bool rejected = i < reports.size() && reports[i].rejected;
      if (e.kind == EdgeKind::kWall) continue;  // short sideways ties along the path
      // A marginal edge stands for the odometry and loops of a removed keyframe: drawn thin.
      const bool chain = e.kind == EdgeKind::kOdometry || e.kind == EdgeKind::kMarginal;
      const int wanted = chain ? 0 : (rejected ? 2 : 1);
      if (wanted != pass) continue;
      const auto a = poses.find(e.from_id), b = poses.find(e.to_id);
      if (a == poses.end() || b == poses.end()) continue;
      const cv::Scalar colour = pass == 0   ? kGraphOdometryBgr
                                : pass == 1 ? kGraphLoopBgr
                                            : kGraphRejectedLoopBgr;
      cv::line(image, pixel(a->second), pixel(b->second), colour, pass == 0 ? 1 : 2, cv::LINE_AA);
    }
  }
  if (grid != nullptr) {
    grid->resolution_m = 1.0 / scale;
    grid->x0_m = lo_x - margin / scale;
    grid->y0_m = hi_y + margin / scale;
    grid->rows = rows;
    grid->cols = cols;
  }
  return image;
}

}  // namespace uwbsar
