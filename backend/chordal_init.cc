#include "backend/chordal_init.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cmath>
#include <unordered_map>

namespace uwbsar {
namespace {

/// Solves min sum_k w_k |x_j - M_k x_i - b_k|^2 over 2-vectors x per node, with x_anchor
/// given and a weak pull of every x towards its guess (keeps the system regular for nodes
/// that no edge reaches).
class LinearProblem {
 public:
  LinearProblem(int num_nodes, int anchor, const Eigen::Vector2d& anchor_value)
      : n_(num_nodes),
        anchor_(anchor),
        anchor_value_(anchor_value),
        rhs_(Eigen::VectorXd::Zero(2 * num_nodes)) {}

  void AddPrior(int i, const Eigen::Vector2d& value, double weight) {
    AddBlock(i, i, weight * Eigen::Matrix2d::Identity());
    rhs_.segment<2>(2 * i) += weight * value;
  }

  /// Residual x_j - M x_i - b with weight w.
  void AddRelative(int i, int j, const Eigen::Matrix2d& M, const Eigen::Vector2d& b, double w) {
    AddBlock(j, j, w * Eigen::Matrix2d::Identity());
    AddBlock(i, i, w * M.transpose() * M);
    AddBlock(j, i, -w * M);
    AddBlock(i, j, -w * M.transpose());
    rhs_.segment<2>(2 * j) += w * b;
    rhs_.segment<2>(2 * i) -= w * M.transpose() * b;
  }

  /// The solution (anchor included); empty when the factorisation fails.
  Eigen::VectorXd Solve() {
    // Fix the anchor: replace its rows by the identity and move its columns to the right side.
    Eigen::VectorXd rhs = rhs_;
    std::vector<Eigen::Triplet<double>> kept;
    kept.reserve(triplets_.size());
    for (const auto& t : triplets_) {
      const bool row_anchor = t.row() / 2 == anchor_, col_anchor = t.col() / 2 == anchor_;
      if (row_anchor) continue;
      if (col_anchor) {
        rhs(t.row()) -= t.value() * anchor_value_(t.col() % 2);
        continue;
      }
      kept.push_back(t);
    }
    kept.emplace_back(2 * anchor_, 2 * anchor_, 1.0);
    kept.emplace_back(2 * anchor_ + 1, 2 * anchor_ + 1, 1.0);
    rhs.segment<2>(2 * anchor_) = anchor_value_;
    Eigen::SparseMatrix<double> H(2 * n_, 2 * n_);
    H.setFromTriplets(kept.begin(), kept.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(H);
    if (solver.info() != Eigen::Success) return {};
    Eigen::VectorXd x = solver.solve(rhs);
    if (solver.info() != Eigen::Success || !x.allFinite()) return {};
    return x;
  }

 private:
  void AddBlock(int bi, int bj, const Eigen::Matrix2d& m) {
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 2; ++c) triplets_.emplace_back(2 * bi + r, 2 * bj + c, m(r, c));
    }
  }

  int n_;
  int anchor_;
  Eigen::Vector2d anchor_value_;
  Eigen::VectorXd rhs_;
  std::vector<Eigen::Triplet<double>> triplets_;
};

Eigen::Matrix2d Rotation(double yaw) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return (Eigen::Matrix2d() << c, -s, s, c).finished();
}

constexpr double kGuessWeight = 1e-9;  // relative to the edges' weights

}  // namespace

std::map<int, Pose2> ChordalInitialization(const std::map<int, Pose2>& guess,
                                           const std::vector<PoseGraphEdge>& edges, int anchor_id) {
  std::unordered_map<int, int> index;
  std::vector<int> ids;
  for (const auto& [id, pose] : guess) {
    index[id] = static_cast<int>(ids.size());
    ids.push_back(id);
  }
  const int n = static_cast<int>(ids.size());
  const int anchor = index.at(anchor_id);
  const Pose2& anchor_pose = guess.at(anchor_id);

  // Rotations: r = (cos, sin) of each node; R_j = R_i R_ij reads r_j = Rot(yaw_ij) r_i.
  LinearProblem rotations(n, anchor,
                          {std::cos(anchor_pose.yaw_rad), std::sin(anchor_pose.yaw_rad)});
  for (int k = 0; k < n; ++k) {
    const double yaw = guess.at(ids[static_cast<std::size_t>(k)]).yaw_rad;
    rotations.AddPrior(k, {std::cos(yaw), std::sin(yaw)}, kGuessWeight);
  }
  for (const PoseGraphEdge& e : edges) {
    rotations.AddRelative(index.at(e.from_id), index.at(e.to_id), Rotation(e.T_from_to.yaw_rad),
                          Eigen::Vector2d::Zero(), e.information(2, 2));
  }
  const Eigen::VectorXd r = rotations.Solve();
  if (r.size() == 0) return guess;
  std::vector<double> yaw(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) yaw[static_cast<std::size_t>(k)] = std::atan2(r(2 * k + 1), r(2 * k));

  // Positions: t_j = t_i + R_i t_ij with the rotations fixed.
  LinearProblem positions(n, anchor, {anchor_pose.x_m, anchor_pose.y_m});
  for (int k = 0; k < n; ++k) {
    const Pose2& p = guess.at(ids[static_cast<std::size_t>(k)]);
    positions.AddPrior(k, {p.x_m, p.y_m}, kGuessWeight);
  }
  for (const PoseGraphEdge& e : edges) {
    const int i = index.at(e.from_id), j = index.at(e.to_id);
    const Eigen::Vector2d b = Rotation(yaw[static_cast<std::size_t>(i)]) *
                              Eigen::Vector2d(e.T_from_to.x_m, e.T_from_to.y_m);
    positions.AddRelative(i, j, Eigen::Matrix2d::Identity(), b,
                          0.5 * (e.information(0, 0) + e.information(1, 1)));
  }
  const Eigen::VectorXd t = positions.Solve();
  if (t.size() == 0) return guess;
  std::map<int, Pose2> out;
  for (int k = 0; k < n; ++k) {
    const std::size_t s = static_cast<std::size_t>(k);
    out[ids[s]] = {t(2 * k), t(2 * k + 1), yaw[s]};
  }
  out[anchor_id] = anchor_pose;
  return out;
}

}  // namespace uwbsar
