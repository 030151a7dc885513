#include "backend/se2_edge_cost.h"

#include <gtest/gtest.h>

namespace uwbsar {
namespace {

TEST(Se2EdgeCostTest, AnalyticJacobiansMatchCentralDifferences) {
  // (ceres::GradientChecker's result struct holds Eigen members whose layout differs
  // between this -march=native build and the packaged Ceres, so differences are taken here.)
  Eigen::Matrix3d info;
  info << 40, 3, 1, 3, 20, 2, 1, 2, 90;
  const Se2EdgeCost cost({0.7, -0.3, 0.4}, *SqrtInformation(info));
  double a[3] = {1.0, 2.0, 2.9}, b[3] = {1.5, 2.5, -2.8};  // yaw difference wraps
  double* blocks[2] = {a, b};
  const double* params[2] = {a, b};
  double r[3], j0[9], j1[9];
  double* jacobians[2] = {j0, j1};
  ASSERT_TRUE(cost.Evaluate(params, r, jacobians));
  const double h = 1e-6;
  for (int block = 0; block < 2; ++block) {
    for (int col = 0; col < 3; ++col) {
      double rp[3], rm[3];
      blocks[block][col] += h;
      cost.Evaluate(params, rp, nullptr);
      blocks[block][col] -= 2 * h;
      cost.Evaluate(params, rm, nullptr);
      blocks[block][col] += h;
      for (int row = 0; row < 3; ++row) {
        const double numeric = (rp[row] - rm[row]) / (2 * h);
        EXPECT_NEAR(jacobians[block][row * 3 + col], numeric, 1e-5)
            << "block " << block << " row " << row << " col " << col;
      }
    }
  }
}

TEST(Se2EdgeCostTest, ResidualIsZeroAtTheMeasurementAndChi2IsWeighted) {
  const Pose2 T_a_b{1.0, 0.5, 0.3};
  const Pose2 T_w_a{2.0, -1.0, 2.0};
  const Pose2 T_w_b = T_w_a * T_a_b;
  double a[3] = {T_w_a.x_m, T_w_a.y_m, T_w_a.yaw_rad + 2 * M_PI};  // unwrapped yaw is fine
  double b[3] = {T_w_b.x_m, T_w_b.y_m, T_w_b.yaw_rad};
  const Eigen::Matrix3d U = *SqrtInformation(Eigen::Vector3d(4, 4, 100).asDiagonal());
  EXPECT_NEAR(Se2Chi2(a, b, T_a_b, U), 0.0, 1e-18);
  b[2] += 0.1;  // 0.1 rad off with yaw information 100 -> chi2 = 1
  EXPECT_NEAR(Se2Chi2(a, b, T_a_b, U), 1.0, 1e-9);
}

TEST(Se2EdgeCostTest, SqrtInformationRejectsMatricesThatAreNotPositiveDefinite) {
  EXPECT_TRUE(SqrtInformation(Eigen::Matrix3d::Identity()).has_value());
  EXPECT_FALSE(SqrtInformation(Eigen::Matrix3d::Zero()).has_value());
  EXPECT_FALSE(SqrtInformation(Eigen::Vector3d(1, -1, 1).asDiagonal()).has_value());
  EXPECT_FALSE(SqrtInformation(Eigen::Vector3d(1, 0, 1).asDiagonal()).has_value());
  Eigen::Matrix3d asym = Eigen::Matrix3d::Identity();
  asym(0, 1) = 0.5;
  EXPECT_FALSE(SqrtInformation(asym).has_value());
  Eigen::Matrix3d nan = Eigen::Matrix3d::Identity();
  nan(2, 2) = std::nan("");
  EXPECT_FALSE(SqrtInformation(nan).has_value());
  const Eigen::Matrix3d info = (Eigen::Matrix3d() << 5, 1, 0, 1, 3, 0.5, 0, 0.5, 2).finished();
  const Eigen::Matrix3d U = *SqrtInformation(info);
  EXPECT_TRUE((U.transpose() * U).isApprox(info, 1e-12));
  EXPECT_TRUE(U.isUpperTriangular());
}

}  // namespace
}  // namespace uwbsar
