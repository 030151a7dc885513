#include "frontend/place_recognition/loop_validator.h"

#include <Eigen/LU>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <vector>

namespace uwbsar {
namespace {

Point2 ToMetric(const ImageGrid& g, const cv::Point2d& p) { return g.PixelToMetric(p.x, p.y); }

/// The smaller principal standard deviation of both detectors' inliers in image b, in pixels:
/// small when the inliers lie nearly on a line, which leaves the pose unfixed along it.
double InlierSpreadPx(const MatchResult& first, const MatchResult& second) {
  Eigen::Vector2d mean_px = Eigen::Vector2d::Zero();
  double n = 0.0;
  for (const MatchResult* m : {&first, &second}) {
    for (const cv::Point2d& p : m->inliers_b) mean_px += Eigen::Vector2d(p.x, p.y);
    n += static_cast<double>(m->inliers_b.size());
  }
  mean_px /= n;
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const MatchResult* m : {&first, &second}) {
    for (const cv::Point2d& p : m->inliers_b) {
      const Eigen::Vector2d d = Eigen::Vector2d(p.x, p.y) - mean_px;
      scatter += d * d.transpose();
    }
  }
  // Smaller eigenvalue of the 2x2 covariance, in closed form.
  const Eigen::Matrix2d cov_px = scatter / n;
  const double half_trace = 0.5 * (cov_px(0, 0) + cov_px(1, 1));
  const double half_diff = 0.5 * (cov_px(0, 0) - cov_px(1, 1));
  const double min_eig = half_trace - std::hypot(half_diff, cov_px(0, 1));
  return std::sqrt(std::max(0.0, min_eig));
}

/// Least-squares translation of q_i = R(yaw) q_j + t for a given rotation, with the sum of
/// squared residuals and J^T J of (tx, ty, yaw) at the solution.
struct RigidFit {
  Eigen::Vector2d t = Eigen::Vector2d::Zero();
  double sum_sq = 0.0;
  Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
};

/// With `fixed_t` the translation is that one (a refined pair's), not the least-squares one.
RigidFit FitForRotation(const std::vector<Point2>& qi, const std::vector<Point2>& qj, double yaw,
                        const Eigen::Vector2d* fixed_t = nullptr) {
  const double n = static_cast<double>(qi.size());
  const double c = std::cos(yaw), s = std::sin(yaw);
  Eigen::Vector2d ci = Eigen::Vector2d::Zero(), rj = Eigen::Vector2d::Zero();
  std::vector<Eigen::Vector2d> rotated(qi.size());
  for (std::size_t k = 0; k < qi.size(); ++k) {
    rotated[k] = Eigen::Vector2d(c * qj[k].x_m - s * qj[k].y_m, s * qj[k].x_m + c * qj[k].y_m);
    ci += Eigen::Vector2d(qi[k].x_m, qi[k].y_m);
    rj += rotated[k];
  }
  RigidFit fit;
  fit.t = fixed_t ? *fixed_t : Eigen::Vector2d((ci - rj) / n);
  for (std::size_t k = 0; k < qi.size(); ++k) {
    fit.sum_sq += (Eigen::Vector2d(qi[k].x_m, qi[k].y_m) - rotated[k] - fit.t).squaredNorm();
    // d(R q + t) / d(tx, ty, yaw) = [I, perp(R q)].
    Eigen::Matrix<double, 2, 3> jac;
    jac << 1, 0, -rotated[k].y(), 0, 1, rotated[k].x();
    fit.jtj += jac.transpose() * jac;
  }
  return fit;
}

/// The loop's information: the fit's residual scatter (floored at min_residual_px) through
/// J^T J, plus the configured floors of the standard deviations. False when the inlier
/// geometry does not fix the pose (J^T J singular relative to its scale).
bool LoopInformation(const RigidFit& fit, double n, double resolution_m,
                     const LoopValidationConfig& config, Eigen::Matrix3d* information) {
  const double dof = std::max(1.0, 2.0 * n - 3.0);
  const double floor_m = config.min_residual_px * resolution_m;
  const double sigma2 = std::max(fit.sum_sq / dof, floor_m * floor_m);
  Eigen::Matrix3d floors = Eigen::Matrix3d::Zero();
  const double yaw_floor = config.min_yaw_sigma_deg * M_PI / 180.0;
  floors.diagonal() << config.min_xy_sigma_m * config.min_xy_sigma_m,
      config.min_xy_sigma_m * config.min_xy_sigma_m, yaw_floor * yaw_floor;
  // J^T J is 3x3 and well scaled in metres: the closed-form inverse is enough, and
  // its determinant (relative to the scale of the entries) tells a singular geometry.
  const Eigen::Matrix3d fisher = fit.jtj / sigma2;
  const double det = fisher.determinant();
  const double scale3 = std::pow(fisher.diagonal().cwiseAbs().maxCoeff(), 3.0);
  if (!(std::abs(det) > 1e-12 * scale3)) return false;
  const Eigen::Matrix3d covariance = fisher.inverse() + floors;
  *information = covariance.inverse();
  return true;
}

/// Empty when both detectors lie within the rule's agreement limits of the refined transform
/// and its peak is distinct; otherwise why not.
std::string JudgeRefinement(const DetectorStats& first, const DetectorStats& second,
                            const DenseRefinement& r, const LoopValidationConfig& c) {
  const std::string peak = JudgePeak(r, c.refinement.min_peak_ncc, c.refinement.min_peak_ratio);
  if (!peak.empty()) return peak;
  char buf[200];
  for (int k = 0; k < 2; ++k) {
    const DetectorStats& s = k == 0 ? first : second;
    const double dtx = std::abs(s.tx_px - r.transform.tx_px);
    const double dty = std::abs(s.ty_px - r.transform.ty_px);
    const double drot = std::abs(WrapDegrees(s.rotation_deg - r.transform.rotation_deg));
    if (dtx > c.max_tx_difference_px || dty > c.max_ty_difference_px ||
        drot > c.max_rotation_difference_deg) {
      std::snprintf(buf, sizeof(buf), "%s off the correlation peak (%.1f px, %.1f px, %.1f deg)",
                    DetectorName(c.detectors[k]), dtx, dty, drot);
      return buf;
    }
  }
  return "";
}

/// The rule with the agreement limits widened to near_agreement_factor times their size: it
/// accepts, with the fused transform as the seed, the pairs that nearly agree.
LoopDecision NearAgreement(const DetectorStats& first, const DetectorStats& second,
                           const LoopValidationConfig& config) {
  LoopValidationConfig near = config;
  const double f = config.refinement.near_agreement_factor;
  near.max_tx_difference_px *= f;
  near.max_ty_difference_px *= f;
  near.max_rotation_difference_deg *= f;
  return ApplyLoopRule(first, second, near);
}

/// A pair the rule rejected although its detectors nearly agree: correlates the images around
/// the fused transform and accepts it at the correlation peak when JudgeRefinement finds
/// nothing against it.
void RefineNearAgreement(const DetectorStats& first, const DetectorStats& second,
                         double resolution_m, const LoopImages& images,
                         const LoopValidationConfig& config, LoopValidation* v) {
  const DenseRefinementConfig& rc = config.refinement;
  if (!rc.enabled || !images.i || !images.j || images.i->gray.empty() || images.j->gray.empty()) {
    return;
  }
  const LoopDecision seed = NearAgreement(first, second, config);
  if (!seed.accepted) return;  // a detector failed on its own, or they are far apart
  v->refinement_tried = true;
  v->refinement = RefineByCorrelation(
      *images.i, *images.j, {seed.tx_px, seed.ty_px, seed.rotation_deg}, resolution_m, rc);
  const std::string why = JudgeRefinement(first, second, v->refinement, config);
  if (!why.empty()) {
    v->decision.reason += "; refinement: " + why;
    return;
  }
  v->refined = true;
  v->decision.accepted = true;
  v->decision.reason.clear();
  v->decision.tx_px = v->refinement.transform.tx_px;
  v->decision.ty_px = v->refinement.transform.ty_px;
  v->decision.rotation_deg = v->refinement.transform.rotation_deg;
}

}  // namespace

Pose2 PixelToMetricTransform(const ImageGrid& grid_a, const ImageGrid& grid_b, double tx_px,
                             double ty_px, double rotation_deg) {
  // Rows grow towards -y, so a rotation by +rot in pixels is -rot in metres. Map the
  // metric origin of b through the pixel transform to find the translation.
  const double rot = rotation_deg * M_PI / 180.0;
  const double c = std::cos(rot), s = std::sin(rot);
  auto map = [&](double x_m, double y_m) {
    const double col = grid_b.XToCol(x_m), row = grid_b.YToRow(y_m);
    return grid_a.PixelToMetric(c * col - s * row + tx_px, s * col + c * row + ty_px);
  };
  const Point2 origin = map(0.0, 0.0);
  return {origin.x_m, origin.y_m, NormalizeAngle(-rot)};
}

bool MayRefine(const DetectorMap<MatchResult>& matches, const LoopValidationConfig& config) {
  assert(config.detectors.size() == 2);
  if (!config.refinement.enabled) return false;
  static const MatchResult kNotMatched;
  const DetectorStats first = StatsOf(Of(matches, config.detectors[0], kNotMatched));
  const DetectorStats second = StatsOf(Of(matches, config.detectors[1], kNotMatched));
  return !ApplyLoopRule(first, second, config).accepted &&
         NearAgreement(first, second, config).accepted;
}

int MinGoodMatches(const LoopConstraint& loop) {
  if (loop.good_matches.empty()) return 0;
  int n = loop.good_matches.begin()->second;
  for (const auto& [kind, good] : loop.good_matches) n = std::min(n, good);
  return n;
}

LoopValidation ValidateLoop(int id_i, const ImageGrid& grid_i, int id_j, const ImageGrid& grid_j,
                            const DetectorMap<MatchResult>& matches,
                            const LoopValidationConfig& config, const LoopImages& images) {
  assert(config.detectors.size() == 2);
  static const MatchResult kNotMatched;
  const MatchResult& first = Of(matches, config.detectors[0], kNotMatched);
  const MatchResult& second = Of(matches, config.detectors[1], kNotMatched);
  LoopValidation v;
  v.decision = ApplyLoopRule(StatsOf(first), StatsOf(second), config);
  if (!v.decision.accepted) {
    RefineNearAgreement(StatsOf(first), StatsOf(second), grid_i.resolution_m, images, config, &v);
  }
  if (!v.decision.accepted) {
    v.reason = v.decision.reason;
    return v;
  }
  v.inlier_spread_px = InlierSpreadPx(first, second);
  if (!(v.inlier_spread_px >= config.min_inlier_spread_px)) {
    char buf[128];
    std::snprintf(buf, sizeof(buf), "degenerate: inliers nearly collinear (spread %.1f px < %.1f)",
                  v.inlier_spread_px, config.min_inlier_spread_px);
    v.reason = buf;
    return v;
  }
  // All inliers of both detectors, in metres in the two anchor frames.
  std::vector<Point2> qi, qj;
  for (const MatchResult* m : {&first, &second}) {
    for (std::size_t k = 0; k < m->inliers_a.size(); ++k) {
      qi.push_back(ToMetric(grid_i, m->inliers_a[k]));
      qj.push_back(ToMetric(grid_j, m->inliers_b[k]));
    }
  }
  // Fused rotation (paper), metric; translation = least squares for that rotation over
  // all inliers (equals the paper's weighted mean when scale is 1, and unlike the pixel
  // translation it does not pick up a lever-arm error from a scale slightly off 1).
  // A refined pair's translation is the correlation peak's, exactly converted.
  const double yaw = NormalizeAngle(-v.decision.rotation_deg * M_PI / 180.0);
  const Pose2 peak = PixelToMetricTransform(grid_i, grid_j, v.decision.tx_px, v.decision.ty_px,
                                            v.decision.rotation_deg);
  const Eigen::Vector2d peak_t(peak.x_m, peak.y_m);
  const RigidFit fit = FitForRotation(qi, qj, yaw, v.refined ? &peak_t : nullptr);
  const double n = static_cast<double>(qi.size());
  Eigen::Matrix3d information;
  if (!LoopInformation(fit, n, grid_i.resolution_m, config, &information)) {
    v.reason = "degenerate: inlier geometry does not fix the pose";
    return v;
  }
  LoopConstraint& lc = v.constraint;
  lc.i = id_i;
  lc.j = id_j;
  lc.T_ij = {fit.t.x(), fit.t.y(), yaw};
  lc.information = 0.5 * (information + information.transpose());
  lc.good_matches = {{config.detectors[0], first.good_matches},
                     {config.detectors[1], second.good_matches}};
  lc.residual_rms_m = std::sqrt(fit.sum_sq / n);
  if (!lc.information.allFinite() || !std::isfinite(lc.T_ij.x_m) || !std::isfinite(lc.T_ij.y_m) ||
      !std::isfinite(lc.T_ij.yaw_rad)) {
    v.reason = "degenerate: non-finite constraint";
    return v;
  }
  v.accepted = true;
  return v;
}

LoopValidation ValidateLoop(int id_i, const ImageGrid& grid_i, int id_j, const ImageGrid& grid_j,
                            const MatchResult& first, const MatchResult& second,
                            const LoopValidationConfig& config, const LoopImages& images) {
  assert(config.detectors.size() == 2);
  const DetectorMap<MatchResult> matches = {{config.detectors[0], first},
                                            {config.detectors[1], second}};
  return ValidateLoop(id_i, grid_i, id_j, grid_j, matches, config, images);
}

}  // namespace uwbsar
