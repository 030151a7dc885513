// backend/graph_plot.h: loops are drawn above the odometry chain in colours told apart with
// the common colour-vision deficiencies, and the plot's grid places every pose.
#include "backend/graph_plot.h"

#include <gtest/gtest.h>

#include <cmath>

namespace uwbsar {
namespace {

PoseGraphEdge Edge(int from, int to, EdgeKind kind) {
  PoseGraphEdge e;
  e.from_id = from;
  e.to_id = to;
  e.kind = kind;
  return e;
}

TEST(GraphPlotTest, LoopsAreDrawnAboveTheChainAndTheGridPlacesThePoses) {
  // A chain along y = 0 and a loop from (2, 1) down to (2, -1) crossing it at (2, 0).
  const std::map<int, Pose2> poses = {
      {0, {0, 0, 0}}, {1, {4, 0, 0}}, {2, {2, 1, 0}}, {3, {2, -1, 0}}};
  const std::vector<PoseGraphEdge> edges = {Edge(0, 1, EdgeKind::kOdometry),
                                            Edge(2, 3, EdgeKind::kLoop)};
  ImageGrid grid;
  const cv::Mat plot = PlotPoseGraph(poses, edges, {}, 200, &grid);
  ASSERT_EQ(grid.rows, plot.rows);
  ASSERT_EQ(grid.cols, plot.cols);
  auto at = [&](double x, double y) {
    return plot.at<cv::Vec3b>(static_cast<int>(grid.YToRow(y)), static_cast<int>(grid.XToCol(x)));
  };
  auto near = [](const cv::Vec3b& a, const cv::Scalar& b) {
    return cv::norm(cv::Scalar(a[0], a[1], a[2]) - b) < 60.0;
  };
  EXPECT_TRUE(near(at(2, 0), kGraphLoopBgr)) << at(2, 0);  // the loop over the chain
  EXPECT_TRUE(near(at(1, 0), kGraphOdometryBgr)) << at(1, 0);
  EXPECT_TRUE(near(at(2, 0.5), kGraphLoopBgr)) << at(2, 0.5);
  EXPECT_EQ(at(1, 0.5), cv::Vec3b(255, 255, 255));
  // Blue and vermillion differ in lightness and hue, not only red against green.
  EXPECT_GT(cv::norm(kGraphLoopBgr - kGraphRejectedLoopBgr), 150.0);
}

}  // namespace
}  // namespace uwbsar
