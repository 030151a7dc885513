#include "backend/chordal_init.h"

#include <gtest/gtest.h>

namespace uwbsar {
namespace {

TEST(ChordalInitTest, RecoversAConsistentGraphFromAGarbageGuess) {
  std::vector<Pose2> truth;
  Pose2 p;
  for (int k = 0; k < 12; ++k) {
    truth.push_back(p);
    p = p * Pose2{1.0, 0.0, M_PI / 6};  // a 12-gon
  }
  std::vector<PoseGraphEdge> edges;
  for (int k = 0; k < 12; ++k) {
    PoseGraphEdge e;
    e.from_id = k;
    e.to_id = (k + 1) % 12;
    e.T_from_to = Between(truth[static_cast<std::size_t>(e.from_id)],
                          truth[static_cast<std::size_t>(e.to_id)]);
    edges.push_back(e);
  }
  std::map<int, Pose2> guess;
  for (int k = 0; k < 12; ++k) guess[k] = {k * 7.0, -3.0 * k, 2.5 * k};
  guess[0] = truth[0];
  const std::map<int, Pose2> init = ChordalInitialization(guess, edges, 0);
  for (int k = 0; k < 12; ++k) {
    EXPECT_NEAR(init.at(k).x_m, truth[static_cast<std::size_t>(k)].x_m, 1e-6) << k;
    EXPECT_NEAR(init.at(k).y_m, truth[static_cast<std::size_t>(k)].y_m, 1e-6) << k;
    EXPECT_NEAR(NormalizeAngle(init.at(k).yaw_rad - truth[static_cast<std::size_t>(k)].yaw_rad),
                0.0, 1e-6);
  }
}

}  // namespace
}  // namespace uwbsar
