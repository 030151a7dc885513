#include "eval/tour/tour_eval.h"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

namespace uwbsar::eval {

// The SLAM system's run, as the scoring reads it.
using slam::KeyframeRecord;
using slam::LoopRecord;
using slam::MapRun;
using slam::RetiredKeyframe;
using slam::SlamSystem;
using slam::TrajectoryError;

namespace {

constexpr double kFalseLoopM = 0.2;
constexpr double kFalseLoopDeg = 5.0;

void EvaluateWallEdges(const SlamSystem& slam, const std::map<int, Pose2>& true_anchor,
                       TourEvaluation* e) {
  const std::vector<PoseGraphEdge> edges = slam.graph().Edges();
  const std::vector<EdgeReport> reports = slam.graph().EdgeReports();
  double sum_sq = 0.0;
  int accepted = 0;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (edges[i].kind != EdgeKind::kWall) continue;
    ++e->wall_edges;
    if (i < reports.size() && reports[i].rejected) {
      ++e->wall_rejected;
      continue;
    }
    // The direction the edge measures: its information's strongest direction in (x, y).
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(edges[i].information.topLeftCorner<2, 2>());
    const Eigen::Vector2d n = eig.eigenvectors().col(1);
    const Pose2 truth = Between(true_anchor.at(edges[i].from_id), true_anchor.at(edges[i].to_id));
    const double error = n.dot(
        Eigen::Vector2d(edges[i].T_from_to.x_m - truth.x_m, edges[i].T_from_to.y_m - truth.y_m));
    sum_sq += error * error;
    ++accepted;
    e->wall_error_max_m = std::max(e->wall_error_max_m, std::abs(error));
  }
  if (accepted > 0) e->wall_error_rms_m = std::sqrt(sum_sq / accepted);
}

/// Each accepted landmark observation placed in the world by its keyframe's true anchor: its
/// point nearest the reference point. Per landmark, a line through those points (total least
/// squares) stands for the true wall; an observation's error is its point's distance from it.
void EvaluateLandmarks(const SlamSystem& slam, const std::map<int, Pose2>& true_anchor,
                       TourEvaluation* e) {
  const std::vector<LineObservation> observations = slam.graph().LineObservations();
  const std::vector<LineObservationReport> reports = slam.graph().LineObservationReports();
  std::map<int, std::vector<Eigen::Vector2d>> points;
  for (std::size_t i = 0; i < observations.size(); ++i) {
    ++e->landmark_observations;
    const LineObservation& o = observations[i];
    if (i < reports.size() && reports[i].rejected) {
      ++e->landmark_rejected;
      continue;
    }
    const auto anchor = true_anchor.find(o.node_id);
    if (anchor == true_anchor.end()) continue;
    const Eigen::Vector2d n(std::cos(o.line_node.normal_rad), std::sin(o.line_node.normal_rad));
    const Eigen::Vector2d q(o.reference_node.x_m, o.reference_node.y_m);
    const Eigen::Vector2d on_line = q + (o.line_node.offset_m - n.dot(q)) * n;
    const Point2 w = anchor->second * Point2{on_line.x(), on_line.y()};
    points[o.landmark_id].emplace_back(w.x_m, w.y_m);
  }
  e->landmarks = static_cast<int>(slam.graph().GetLandmarks().size());
  double sum_sq = 0.0;
  int count = 0;
  for (const auto& [id, p] : points) {
    if (p.size() < 3) continue;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& x : p) mean += x;
    mean /= static_cast<double>(p.size());
    Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
    for (const Eigen::Vector2d& x : p) scatter += (x - mean) * (x - mean).transpose();
    const Eigen::Vector2d normal =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(scatter).eigenvectors().col(
            0);  // smallest eigenvalue: across the line
    for (const Eigen::Vector2d& x : p) {
      const double error = normal.dot(x - mean);
      sum_sq += error * error;
      ++count;
      e->landmark_error_max_m = std::max(e->landmark_error_max_m, std::abs(error));
    }
  }
  if (count > 0) e->landmark_error_rms_m = std::sqrt(sum_sq / count);
}

/// Adds one accepted loop's error against `truth` and its claimed sigmas to the sums.
struct LoopAccuracySums {
  double error_sq_m2 = 0.0, error_sq_rad2 = 0.0, sigma_m = 0.0, sigma_rad = 0.0;
  int count = 0;

  void Add(const LoopConstraint& c, const Pose2& truth) {
    const Pose2& T = c.T_ij;
    error_sq_m2 += std::pow(T.x_m - truth.x_m, 2) + std::pow(T.y_m - truth.y_m, 2);
    error_sq_rad2 += std::pow(NormalizeAngle(T.yaw_rad - truth.yaw_rad), 2);
    const Eigen::Matrix3d covariance = c.information.inverse();
    sigma_m += 0.5 * (std::sqrt(covariance(0, 0)) + std::sqrt(covariance(1, 1)));
    sigma_rad += std::sqrt(covariance(2, 2));
    ++count;
  }
  void Finish(TourEvaluation* e) const {
    if (count == 0) return;
    e->loop_error_rms_m = std::sqrt(error_sq_m2 / count);
    e->loop_error_rms_yaw_rad = std::sqrt(error_sq_rad2 / count);
    e->loop_sigma_mean_m = sigma_m / count;
    e->loop_sigma_mean_yaw_rad = sigma_rad / count;
  }
};

}  // namespace

TourEvaluation EvaluateTour(const MapRun& run, double overlap_m) {
  TourEvaluation e;
  const SlamSystem& slam = *run.slam;
  for (std::size_t i = 1; i < run.ground_truth.size(); ++i) {
    const Pose2& a = run.ground_truth[i - 1].T_world_robot;
    const Pose2& b = run.ground_truth[i].T_world_robot;
    e.travel_m += std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
  }
  std::vector<std::pair<TimestampNs, Pose2>> odometry;
  for (const OdometryEntry& o : slam.odometry()) odometry.push_back({o.stamp_ns, o.T_world_robot});
  e.ate_m = TrajectoryError(slam.CorrectedTrajectory(), run.ground_truth).rmse_m;
  e.odometry_ate_m = TrajectoryError(odometry, run.ground_truth).rmse_m;
  e.ring_closed = e.ate_m * 3.0 <= e.odometry_ate_m;

  std::map<int, Pose2> true_anchor;
  std::map<int, double> path_m;
  for (const KeyframeRecord& k : slam.keyframes()) {
    const Pose2 T_robot_anchor = k.keyframe.T_world_robot.Inverse() * k.keyframe.T_world_anchor;
    true_anchor[k.keyframe.id] = TruePoseAt(run.ground_truth, k.keyframe.stamp_ns) * T_robot_anchor;
    path_m[k.keyframe.id] = k.keyframe.path_begin_m;
  }
  for (const RetiredKeyframe& k : slam.retired()) {  // revisits retire old views
    const Pose2 T_robot_anchor = k.T_odom_robot.Inverse() * k.T_odom_anchor;
    true_anchor[k.id] = TruePoseAt(run.ground_truth, k.stamp_ns) * T_robot_anchor;
    path_m[k.id] = k.path_begin_m;
  }
  e.keyframes = static_cast<int>(slam.keyframes().size());

  std::map<int, bool> query_overlap, query_recalled;  // per query keyframe with true overlap
  LoopAccuracySums accuracy;
  for (const LoopRecord& l : slam.loops()) {
    ++e.candidates;
    const Pose2 truth = Between(true_anchor[l.match_id], true_anchor[l.query_id]);
    const bool overlap = std::hypot(truth.x_m, truth.y_m) <= overlap_m;
    if (overlap) {
      ++e.overlap_candidates;
      e.overlap_accepted += l.accepted();
      query_overlap[l.query_id] = true;
      query_recalled[l.query_id] = query_recalled[l.query_id] || l.accepted();
    }
    if (!l.validation.accepted) continue;
    ++e.validated;
    e.accepted += l.accepted();
    const Pose2& T = l.validation.constraint.T_ij;
    const bool is_false =
        std::hypot(T.x_m - truth.x_m, T.y_m - truth.y_m) > kFalseLoopM ||
        std::abs(NormalizeAngle(T.yaw_rad - truth.yaw_rad)) * 180.0 / M_PI > kFalseLoopDeg;
    e.false_validated += is_false;
    if (l.accepted()) {
      e.false_accepted += is_false;
      if (!is_false) accuracy.Add(l.validation.constraint, truth);
      e.longest_loop_path_m =
          std::max(e.longest_loop_path_m, std::abs(path_m[l.query_id] - path_m[l.match_id]));
    }
  }
  accuracy.Finish(&e);
  EvaluateWallEdges(slam, true_anchor, &e);
  EvaluateLandmarks(slam, true_anchor, &e);
  int previous = -10;
  bool recalled = false;
  for (const auto& [id, overlap] : query_overlap) {
    if (id != previous + 1) {  // a new revisit begins
      e.revisits_recalled += recalled;
      ++e.revisits;
      recalled = false;
    }
    recalled = recalled || query_recalled[id];
    previous = id;
  }
  e.revisits_recalled += recalled;
  return e;
}

std::string FormatTourEvaluation(const TourEvaluation& e) {
  char line[1000];
  std::snprintf(
      line, sizeof(line),
      "travel %.1f m, ATE %.2f cm, odometry %.2f cm (%.1fx)%s, loops %d accepted / %d "
      "validated / %d candidates, false %d accepted (%d validated), longest %.0f m, "
      "recall %d/%d candidates (%.2f), %d/%d revisits (%.2f), wall edges %d (%d "
      "rejected, error rms %.1f max %.1f cm), wall landmarks %d (%d observations, %d "
      "rejected, error rms %.1f max %.1f cm), true loops' error rms %.2f cm %.2f deg "
      "(claimed sigma %.2f cm %.2f deg)",
      e.travel_m, e.ate_m * 100, e.odometry_ate_m * 100,
      e.ate_m > 0 ? e.odometry_ate_m / e.ate_m : 0.0, e.ring_closed ? " ring closed" : " RING OPEN",
      e.accepted, e.validated, e.candidates, e.false_accepted, e.false_validated,
      e.longest_loop_path_m, e.overlap_accepted, e.overlap_candidates, e.candidate_recall(),
      e.revisits_recalled, e.revisits, e.revisit_recall(), e.wall_edges, e.wall_rejected,
      e.wall_error_rms_m * 100, e.wall_error_max_m * 100, e.landmarks, e.landmark_observations,
      e.landmark_rejected, e.landmark_error_rms_m * 100, e.landmark_error_max_m * 100,
      e.loop_error_rms_m * 100, e.loop_error_rms_yaw_rad * 180 / M_PI, e.loop_sigma_mean_m * 100,
      e.loop_sigma_mean_yaw_rad * 180 / M_PI);
  return line;
}

Pose2 TruePoseAt(const std::vector<OdometrySample>& truth, TimestampNs t) {
  auto it = std::lower_bound(
      truth.begin(), truth.end(), t,
      [](const OdometrySample& s, TimestampNs stamp) { return s.stamp_ns < stamp; });
  if (it == truth.end()) --it;
  if (it != truth.begin() && std::llabs((it - 1)->stamp_ns - t) < std::llabs(it->stamp_ns - t)) {
    --it;
  }
  return it->T_world_robot;
}

}  // namespace uwbsar::eval
