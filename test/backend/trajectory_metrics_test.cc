#include "backend/trajectory_metrics.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/errors.h"

namespace uwbsar {
namespace {

TEST(TrajectoryMetricsTest, AteIsZeroForARigidlyMovedCopy) {
  std::vector<Pose2> ref, est;
  const Pose2 T{3.0, -2.0, 0.7};
  for (int k = 0; k < 20; ++k) {
    const Pose2 p{0.3 * k, std::sin(0.4 * k), 0.1 * k};
    ref.push_back(p);
    est.push_back(T * p);
  }
  const AteResult r = ComputeAte(est, ref);
  EXPECT_NEAR(r.rmse_m, 0.0, 1e-9);
  EXPECT_NEAR(r.yaw_rmse_rad, 0.0, 1e-9);
  const Pose2 back = r.T_reference_estimate * T;
  EXPECT_NEAR(back.x_m, 0.0, 1e-9);
  EXPECT_NEAR(back.yaw_rad, 0.0, 1e-9);
}

TEST(TrajectoryMetricsTest, AteMeasuresAnOffsetPose) {
  std::vector<Pose2> ref{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  std::vector<Pose2> est = ref;
  est[3].y_m = 1.0;
  const AteResult r = ComputeAte(est, ref);
  EXPECT_GT(r.rmse_m, 0.2);
  EXPECT_LT(r.rmse_m, 0.5);
  EXPECT_THROW(ComputeAte({ref[0]}, {ref[0]}), std::invalid_argument);
}

TEST(TrajectoryMetricsTest, GroundTruthChainComposesConsecutiveEdgesOnly) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "uwbsar_gt_chain.txt").string();
  {
    std::ofstream out(path);
    out << "EDGE2 0 1 1 0 0 50 0 0 50 0 100\n"
           "EDGE2 1 2 0 1 1.5707963267948966 50 0 0 50 0 100\n"
           "EDGE2 0 2 9 9 9 50 0 0 50 0 100\n";
  }
  const std::vector<Pose2> chain = ReadGroundTruthChain(path);
  ASSERT_EQ(chain.size(), 3u);
  EXPECT_NEAR(chain[2].x_m, 1.0, 1e-12);
  EXPECT_NEAR(chain[2].y_m, 1.0, 1e-12);
  EXPECT_NEAR(chain[2].yaw_rad, M_PI / 2, 1e-12);
  {
    std::ofstream out(path);
    out << "EDGE2 0 1 1 0 0\nEDGE2 1 2 x 0 0\n";
  }
  try {
    ReadGroundTruthChain(path);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(":2:"), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
}

}  // namespace
}  // namespace uwbsar
