#include "backend/odometry_calibration_fit.h"

#include <ceres/ceres.h>
#include <ceres/manifold.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <memory>
#include <sstream>

#include "backend/gyro_stillness.h"
#include "backend/odometry_calibration_segments.h"
#include "core/errors.h"

namespace uwbsar {
namespace {

using calibration_fit::CutSegments;
using calibration_fit::Segment;
using calibration_fit::SegmentCost;
using calibration_fit::SegmentErrors;
using calibration_fit::SegmentSqrtInformation;

/// Throws when the stamps of `samples` go back.
void RequireStampOrder(const std::vector<OdometrySample>& samples, const std::string& source) {
  for (std::size_t i = 1; i < samples.size(); ++i) {
    if (samples[i].stamp_ns >= samples[i - 1].stamp_ns) continue;
    std::ostringstream what;
    what << std::fixed << std::setprecision(6) << source << ": stamps go back at sample " << i
         << " (t=" << NsToSeconds(samples[i].stamp_ns)
         << " s after t=" << NsToSeconds(samples[i - 1].stamp_ns)
         << " s): interleaved or merged recordings; calibrate needs one run in time order";
    throw InputError(what.str());
  }
}

/// Throws at the first step of `samples` (`what`: odometry or ground truth) that is a jump
/// (options.max_step_m, max_speed_mps, max_turn_rate_radps): a reset or two runs in one
/// recording would fit nonsense. Steps longer than `max_gap_ns` are not checked: the fit does
/// not interpolate across them. `lines` (optional) names each sample's line of `source`.
void RequireNoJump(const std::vector<OdometrySample>& samples, const char* what,
                   const std::string& source, const std::vector<int>& lines, TimestampNs max_gap_ns,
                   const CalibrationFitOptions& options) {
  for (std::size_t i = 1; i < samples.size(); ++i) {
    if (samples[i].stamp_ns - samples[i - 1].stamp_ns > max_gap_ns) continue;
    const Pose2 step = Between(samples[i - 1].T_world_robot, samples[i].T_world_robot);
    const double d = std::hypot(step.x_m, step.y_m), turn = std::abs(step.yaw_rad);
    const double dt = NsToSeconds(samples[i].stamp_ns - samples[i - 1].stamp_ns);
    const bool too_fast =
        dt > 0.0 ? d / dt > options.max_speed_mps || turn / dt > options.max_turn_rate_radps
                 : d > 0.0 || turn > 0.0;
    if (d <= options.max_step_m && !(too_fast && (d > 0.05 || turn > 0.5))) continue;
    std::ostringstream msg;
    msg << source;
    if (i < lines.size()) msg << ":" << lines[i];
    msg << std::fixed << std::setprecision(3) << ": " << what << " jumps " << d << " m and " << turn
        << " rad in " << dt << " s at t=" << std::setprecision(6)
        << NsToSeconds(samples[i].stamp_ns) << " s (sample " << i
        << "): a reset or two runs in one recording; calibrate needs one continuous run";
    throw InputError(msg.str());
  }
}

/// Throws when the truth does not move over the segments, or when its path and the odometry's
/// differ by more than options.max_path_ratio (each summed over the segments' straight steps).
void RequirePlausiblePaths(const std::vector<Segment>& segments,
                           const CalibrationFitOptions& options) {
  double odometry_m = 0.0, truth_m = 0.0;
  for (const Segment& s : segments) {
    Pose2 composed;
    for (const Pose2& step : s.increments) composed = composed * step;
    odometry_m += std::hypot(composed.x_m, composed.y_m);
    truth_m += std::hypot(s.truth.x_m, s.truth.y_m);
  }
  std::ostringstream what;
  what << std::fixed << std::setprecision(3);
  if (!(truth_m >= options.min_truth_path_m)) {
    what << options.truth_source << ": the ground truth does not move: " << truth_m
         << " m over the " << segments.size() << " segments where the odometry travels "
         << odometry_m << " m (at least " << options.min_truth_path_m << " m needed)";
    throw InputError(what.str());
  }
  const double ratio = odometry_m / truth_m;
  if (ratio <= options.max_path_ratio && ratio >= 1.0 / options.max_path_ratio) return;
  what << options.odometry_source << ": the odometry travels " << odometry_m
       << " m where the ground truth (" << options.truth_source << ") travels " << truth_m
       << " m, a ratio of " << ratio << " (a base's scale error is a few percent, at most "
       << options.max_path_ratio << "x is plausible): not the same run, or another unit";
  throw InputError(what.str());
}

/// Throws when a fitted value lies outside what backend.calibration_*_mean accept.
void RequireLoadable(const CalibrationFit& fit, const CalibrationFitOptions& options) {
  const char* keys[3] = {"backend.calibration_scale_mean",
                         "backend.calibration_heading_drift_mean_rad_per_m",
                         "backend.calibration_rotation_mean"};
  const double limits[3] = {kMaxCalibrationScale, kMaxCalibrationHeadingDriftRadPerM,
                            kMaxCalibrationRotation};
  for (int i = 0; i < 3; ++i) {
    if (std::abs(fit.calibration[i]) <= limits[i]) continue;
    std::ostringstream what;
    what << options.odometry_source << ": the fitted " << keys[i] << " is " << std::fixed
         << std::setprecision(6) << fit.calibration[i] << ", outside [" << -limits[i] << ", "
         << limits[i] << "] that the configuration accepts: the odometry and the ground truth "
         << "do not describe the same motion (another run, frame or unit); nothing written";
    throw InputError(what.str());
  }
}

/// J^T J of every residual of `problem` at its current parameters, over the parameter blocks
/// `columns` (each of its size, at its offset: the blocks' ambient coordinates).
Eigen::MatrixXd InformationOf(const ceres::Problem& problem,
                              const std::vector<std::pair<double*, int>>& columns) {
  int size = 0;
  std::map<const double*, int> offset;
  for (const auto& [block, n] : columns) {
    offset[block] = size;
    size += n;
  }
  Eigen::MatrixXd information = Eigen::MatrixXd::Zero(size, size);
  std::vector<ceres::ResidualBlockId> residuals;
  problem.GetResidualBlocks(&residuals);
  for (const ceres::ResidualBlockId id : residuals) {
    std::vector<double*> blocks;
    problem.GetParameterBlocksForResidualBlock(id, &blocks);
    const ceres::CostFunction* cost = problem.GetCostFunctionForResidualBlock(id);
    const int m = cost->num_residuals();
    std::vector<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> jacobians;
    std::vector<double*> jacobian_ptrs;
    for (const int n : cost->parameter_block_sizes()) jacobians.emplace_back(m, n);
    for (auto& j : jacobians) jacobian_ptrs.push_back(j.data());
    Eigen::VectorXd r(m);
    cost->Evaluate(blocks.data(), r.data(), jacobian_ptrs.data());
    Eigen::MatrixXd row = Eigen::MatrixXd::Zero(m, size);
    for (std::size_t k = 0; k < blocks.size(); ++k) {
      row.middleCols(offset.at(blocks[k]), jacobians[k].cols()) = jacobians[k];
    }
    information += row.transpose() * row;
  }
  return information;
}

double Solve(ceres::Problem* problem) {
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = 50;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, problem, &summary);
  if (!summary.IsSolutionUsable()) {
    throw InputError("odometry calibration: the fit failed: " + summary.message);
  }
  return summary.final_cost;
}

/// One model's least-squares fit of the segments: the calibration (a gyro's drift per metre
/// held at 0) and, for a gyro, a bias per `bias_segment_s` of time; `cost` is its final cost.
struct ModelFit {
  CalibrationFit fit;
  std::vector<double> segment_bias;  ///< the bias each segment was corrected with (rad/s)
  double cost = 0.0;
  int unknowns = 0;
};

ModelFit FitModel(const std::vector<Segment>& segments, const BackendConfig& priors,
                  OdometryModel model, double bias_segment_s) {
  const bool gyro = model == OdometryModel::kGyro;
  ModelFit result;
  CalibrationFit& fit = result.fit;
  fit.model = model;
  OdometryCalibration mean = priors.CalibrationMean();
  if (gyro) mean[kCalibHeadingDrift] = 0.0;
  fit.calibration = mean;
  double* x = fit.calibration.data();
  // The gyro's bias blocks, by segment of time (std::map: stable addresses, in time order).
  std::map<long long, double> bias;
  const auto bias_segment_of = [bias_segment_s](const Segment& s) {
    return static_cast<long long>(std::floor(s.middle_s / bias_segment_s));
  };
  ceres::Problem problem;
  for (const Segment& s : segments) {
    auto* cost = new SegmentCost(&s, SegmentSqrtInformation(s, priors));
    if (gyro) {
      double* b = &bias[bias_segment_of(s)];
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<SegmentCost, 3, 3, 1>(cost), nullptr,
                               x, b);
    } else {
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<SegmentCost, 3, 3>(cost), nullptr,
                               x);
    }
    fit.path_m += s.path_m;
    fit.abs_turn_rad += std::abs(s.turn_rad);
  }
  if (gyro) problem.SetManifold(x, new ceres::SubsetManifold(3, {kCalibHeadingDrift}));
  Solve(&problem);
  // Observed: with the backend's priors (the calibration's, and a gyro bias's turn-on spread),
  // the run leaves it under half the prior's sigma (the data hold at least 3x the prior's
  // information on it). A straight run cannot tell the heading drift from the turns' scale
  // (its only turning is the drift); at the backend's prior the turns' scale barely moves, so
  // the drift counts as observed and the rotation not. A gyro's drift is held: not observed.
  const Eigen::Vector3d prior_sigma(priors.calibration_scale_sigma,
                                    priors.calibration_heading_drift_sigma_rad_per_m,
                                    priors.calibration_rotation_sigma);
  std::vector<std::pair<double*, int>> columns = {{x, 3}};
  for (auto& [k, b] : bias) columns.emplace_back(&b, 1);
  Eigen::MatrixXd information = InformationOf(problem, columns);
  information.diagonal().head<3>() += prior_sigma.cwiseInverse().cwiseAbs2();
  const double bias_sigma = priors.gyro_bias_sigma_dps * M_PI / 180.0;
  information.diagonal().tail(bias.size()).array() += 1.0 / (bias_sigma * bias_sigma);
  if (gyro) {  // held: out of the inverse
    information.row(kCalibHeadingDrift).setZero();
    information.col(kCalibHeadingDrift).setZero();
    information(kCalibHeadingDrift, kCalibHeadingDrift) = 1.0;
  }
  const Eigen::VectorXd sigma_m = information.inverse().diagonal().cwiseSqrt();
  std::vector<int> unobserved;
  for (int i = 0; i < 3; ++i) {
    fit.observed[i] = !(gyro && i == kCalibHeadingDrift) && std::isfinite(sigma_m[i]) &&
                      sigma_m[i] < 0.5 * prior_sigma[i];
    if (!fit.observed[i]) unobserved.push_back(i);
  }
  // The unobserved ones are the base's given calibration (the prior's mean), and the others
  // are fitted with them held there: the least squares alone, no prior pulling them.
  for (const int i : unobserved) fit.calibration[i] = mean[i];
  if (unobserved.size() == 3) {
    problem.SetParameterBlockConstant(x);
  } else if (!unobserved.empty()) {
    problem.SetManifold(x, new ceres::SubsetManifold(3, unobserved));
  }
  result.cost = Solve(&problem);
  result.unknowns = static_cast<int>(3 - unobserved.size() + bias.size());
  // The standard error, scaled by the residuals' chi2 per degree of freedom: the base's actual
  // noise, not the configured bound.
  const double dof = std::max(1.0, 3.0 * static_cast<double>(segments.size()) - result.unknowns);
  const double noise = std::sqrt(2.0 * result.cost / dof);
  for (int i = 0; i < 3; ++i) {
    fit.sigma[i] = fit.observed[i] ? sigma_m[i] * noise
                                   : (gyro && i == kCalibHeadingDrift ? 0.0 : prior_sigma[i]);
  }
  fit.segments = static_cast<int>(segments.size());
  // Each segment of the bias, weighted by the time the fitted segments spend in it.
  std::map<long long, double> seconds;
  for (const Segment& s : segments) {
    if (!gyro) {
      result.segment_bias.push_back(0.0);
      continue;
    }
    const long long k = bias_segment_of(s);
    result.segment_bias.push_back(bias[k]);
    seconds[k] += s.duration_s;
  }
  double total_s = 0.0, weighted = 0.0, weighted2 = 0.0;
  for (const auto& [k, b] : bias) {
    fit.gyro_bias_segments.emplace_back(static_cast<double>(k) * bias_segment_s, b);
    total_s += seconds[k];
    weighted += seconds[k] * b;
    weighted2 += seconds[k] * b * b;
  }
  if (total_s > 0.0) {
    fit.gyro_bias_mean_radps = weighted / total_s;
    fit.gyro_bias_spread_radps = std::sqrt(
        std::max(0.0, weighted2 / total_s - fit.gyro_bias_mean_radps * fit.gyro_bias_mean_radps));
  }
  return result;
}

/// The standstills of `odometry` (backend/gyro_stillness.h): their time and the heading's
/// turn over them.
void Standstills(const std::vector<OdometrySample>& odometry, const BackendConfig& priors,
                 CalibrationModelEvidence* evidence) {
  GyroStillness stillness(priors);
  const auto count = [evidence](const std::optional<GyroStandstill>& s) {
    if (!s) return;
    evidence->still_s += s->end_s - s->begin_s;
    evidence->still_turn_rad += std::abs(s->bias_radps) * (s->end_s - s->begin_s);
  };
  for (const OdometrySample& o : odometry) {
    count(stillness.Add(NsToSeconds(o.stamp_ns), o.T_world_robot));
  }
  count(stillness.Flush());
}

/// Which model explains the run (the header's rule): both fitted with one constant each.
OdometryModel DetectModel(const std::vector<Segment>& segments,
                          const std::vector<OdometrySample>& odometry, const BackendConfig& priors,
                          const ModelFit& wheel, CalibrationModelEvidence* evidence) {
  const ModelFit gyro =
      FitModel(segments, priors, OdometryModel::kGyro, std::numeric_limits<double>::infinity());
  const double dof = std::max(1.0, 3.0 * static_cast<double>(segments.size()) - wheel.unknowns);
  // The better model's noise per degree of freedom (a floor: noiseless odometry fits exactly).
  const double noise2 = std::max(2.0 * std::min(wheel.cost, gyro.cost) / dof, 1e-12);
  evidence->wheel_chi2 = 2.0 * wheel.cost / noise2;
  evidence->gyro_chi2 = 2.0 * gyro.cost / noise2;
  Standstills(odometry, priors, evidence);
  // 25: five standard deviations of a chi2 difference of one degree of freedom.
  if (std::abs(evidence->wheel_chi2 - evidence->gyro_chi2) >= 25.0) {
    evidence->decided_by = "residuals";
    return evidence->gyro_chi2 < evidence->wheel_chi2 ? OdometryModel::kGyro
                                                      : OdometryModel::kWheel;
  }
  if (evidence->still_s > 0.0) {
    evidence->decided_by = "standstills";
    return evidence->still_turn_rad > 0.0 ? OdometryModel::kGyro : OdometryModel::kWheel;
  }
  evidence->decided_by = "configuration";
  return priors.odometry_model;
}

}  // namespace

CalibrationFit FitOdometryCalibration(const std::vector<OdometrySample>& odometry,
                                      const std::vector<OdometrySample>& ground_truth,
                                      const BackendConfig& priors,
                                      const CalibrationFitOptions& options) {
  RequireStampOrder(odometry, options.odometry_source);
  RequireStampOrder(ground_truth, options.truth_source);
  RequireNoJump(odometry, "odometry", options.odometry_source, {},
                std::numeric_limits<TimestampNs>::max(), options);
  // TruthAt interpolates between samples up to twice max_truth_gap_s apart.
  RequireNoJump(ground_truth, "ground truth", options.truth_source, options.truth_lines,
                2 * static_cast<TimestampNs>(options.max_truth_gap_s * 1e9), options);
  const std::vector<Segment> segments = CutSegments(odometry, ground_truth, options);
  if (segments.size() < 10) {
    std::ostringstream what;
    what << options.odometry_source << ": odometry calibration: " << segments.size()
         << " segments of " << options.segment_m
         << " m overlap the ground truth, at least 10 are needed (" << odometry.size()
         << " odometry and " << ground_truth.size() << " ground-truth samples)";
    throw InputError(what.str());
  }
  RequirePlausiblePaths(segments, options);
  const ModelFit wheel = FitModel(segments, priors, OdometryModel::kWheel, 0.0);
  CalibrationModelEvidence evidence;
  OdometryModel model;
  if (options.model) {
    model = *options.model;
    evidence.told = true;
    evidence.decided_by = "told";
    Standstills(odometry, priors, &evidence);
  } else {
    model = DetectModel(segments, odometry, priors, wheel, &evidence);
  }
  const ModelFit chosen = model == OdometryModel::kWheel
                              ? wheel
                              : FitModel(segments, priors, model, priors.gyro_bias_segment_s);
  CalibrationFit fit = chosen.fit;
  fit.evidence = evidence;
  SegmentErrors(segments, {0.0, 0.0, 0.0}, std::vector<double>(segments.size(), 0.0),
                &fit.xy_rms_before_m, &fit.yaw_rms_before_rad);
  SegmentErrors(segments, fit.calibration, chosen.segment_bias, &fit.xy_rms_after_m,
                &fit.yaw_rms_after_rad);
  RequireLoadable(fit, options);
  return fit;
}

}  // namespace uwbsar
