#include "eval/tour/localization_eval.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "drivers/sim/route.h"
#include "eval/tour/tour_eval.h"
#include "slam/slam_system.h"

namespace uwbsar::eval {

LocalizationEvaluation EvaluateLocalization(const slam::LocalizeRun& run, double false_fix_m) {
  LocalizationEvaluation e;
  e.keyframes = static_cast<int>(run.keyframes.size());
  if (run.first_fix < 0) return e;
  e.placed = true;
  e.first_fix_path_m = run.first_fix_path_m;
  const std::vector<std::pair<TimestampNs, Pose2>> trajectory = run.Trajectory(false);
  std::vector<std::pair<TimestampNs, Pose2>> from_fix;
  for (const auto& p : trajectory) {
    if (p.first >= run.first_fix_stamp_ns) from_fix.push_back(p);
  }
  const AteResult error = slam::TrajectoryError(from_fix, run.ground_truth, 0.01, /*align=*/false);
  e.rmse_m = error.rmse_m;
  e.max_m = error.max_m;
  for (std::size_t i = 0; i < run.keyframes.size(); ++i) {
    const LocalizedKeyframe& k = run.keyframes[i];
    if (k.status == LocalizeStatus::kRelocalised) {
      ++e.relocalisations;
      // Where the fix put the robot: the trajectory's first sample from the keyframe's stamp on.
      const auto at = std::lower_bound(
          trajectory.begin(), trajectory.end(), k.stamp_ns,
          [](const std::pair<TimestampNs, Pose2>& p, TimestampNs t) { return p.first < t; });
      if (at != trajectory.end() &&
          Distance(at->second, TruePoseAt(run.ground_truth, at->first)) > false_fix_m) {
        ++e.false_fixes;
      }
    }
    if (static_cast<int>(i) <= run.first_fix) continue;
    ++e.after_fix;
    e.lost_after_fix += k.status == LocalizeStatus::kLost;
    e.registered += k.registrations > 0;
    e.with_loops += k.loops > 0;
  }
  return e;
}

std::string FormatLocalizationEvaluation(const LocalizationEvaluation& e) {
  if (!e.placed) return "never placed (" + std::to_string(e.keyframes) + " keyframes)";
  char buf[320];
  std::snprintf(buf, sizeof(buf),
                "first fix after %.1f m; after it %d keyframes, %d lost, %d registered, %d with "
                "loops; %d relocalisations (%d false); map-frame error rms %.2f cm, worst %.2f cm",
                e.first_fix_path_m, e.after_fix, e.lost_after_fix, e.registered, e.with_loops,
                e.relocalisations, e.false_fixes, e.rmse_m * 100, e.max_m * 100);
  return buf;
}

double OdometryPathAtTruePath(const slam::LocalizeRun& run, double true_path_m) {
  if (run.odometry.empty()) return 0.0;
  double path_m = 0.0;
  TimestampNs when = run.ground_truth.empty() ? 0 : run.ground_truth.back().stamp_ns;
  for (std::size_t i = 1; i < run.ground_truth.size(); ++i) {
    path_m += Distance(run.ground_truth[i - 1].T_world_robot, run.ground_truth[i].T_world_robot);
    if (path_m >= true_path_m) {
      when = run.ground_truth[i].stamp_ns;
      break;
    }
  }
  for (const OdometryEntry& o : run.odometry) {
    if (o.stamp_ns >= when) return o.path_m;
  }
  return run.odometry.back().path_m;
}

double PathToRelocalisation(const slam::LocalizeRun& run, double from_path_m) {
  for (const LocalizedKeyframe& k : run.keyframes) {
    if (k.path_end_m > from_path_m && k.status == LocalizeStatus::kRelocalised) {
      return k.path_end_m - from_path_m;
    }
  }
  return -1.0;
}

void WriteRouteTail(const std::string& route_file, double from_fraction,
                    const std::string& out_file) {
  const std::vector<Point2> w = sim::ReadWaypointsFile(route_file).waypoints;
  auto leg = [&](std::size_t i) {
    return std::hypot(w[i].x_m - w[i - 1].x_m, w[i].y_m - w[i - 1].y_m);
  };
  double length_m = 0.0;
  for (std::size_t i = 1; i < w.size(); ++i) length_m += leg(i);
  double to_go_m = from_fraction * length_m;
  std::ofstream out(out_file);
  out << "# " << route_file << " from " << from_fraction << " of its length on\n";
  for (std::size_t i = 1; i < w.size(); ++i) {
    const double leg_m = leg(i);
    if (to_go_m >= leg_m && i + 1 < w.size()) {
      to_go_m -= leg_m;
      continue;
    }
    const double f = std::min(1.0, to_go_m / leg_m);
    out << w[i - 1].x_m + f * (w[i].x_m - w[i - 1].x_m) << " "
        << w[i - 1].y_m + f * (w[i].y_m - w[i - 1].y_m) << "\n";
    for (std::size_t j = i; j < w.size(); ++j) out << w[j].x_m << " " << w[j].y_m << "\n";
    break;
  }
  if (!out.flush()) throw std::runtime_error("cannot write " + out_file);
}

AteResult MapFrameError(const slam::MapRun& run) {
  return slam::TrajectoryError(run.slam->CorrectedTrajectory(), run.ground_truth, 0.01,
                               /*align=*/false);
}

}  // namespace uwbsar::eval
