#include "backend/trajectory_metrics.h"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "core/bounded_file.h"
#include "core/errors.h"
#include "core/limits_config.h"

namespace uwbsar {

AteResult ComputeAte(const std::vector<Pose2>& estimate, const std::vector<Pose2>& reference,
                     bool align) {
  if (estimate.size() != reference.size() || estimate.size() < 2) {
    throw std::invalid_argument("ComputeAte: trajectories must have the same length >= 2");
  }
  // Closed-form 2-D Umeyama without scale: centre both point sets, the rotation angle
  // is atan2(sum of cross products, sum of dot products). (Eigen::umeyama trips a
  // -Wmaybe-uninitialized false positive of GCC 12 with AVX-512.)
  const double n = static_cast<double>(estimate.size());
  double ex = 0, ey = 0, rx = 0, ry = 0;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    ex += estimate[i].x_m / n;
    ey += estimate[i].y_m / n;
    rx += reference[i].x_m / n;
    ry += reference[i].y_m / n;
  }
  double dot = 0, cross = 0;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    const double ax = estimate[i].x_m - ex, ay = estimate[i].y_m - ey;
    const double bx = reference[i].x_m - rx, by = reference[i].y_m - ry;
    dot += ax * bx + ay * by;
    cross += ax * by - ay * bx;
  }
  const double theta = std::atan2(cross, dot);
  const double c = std::cos(theta), s = std::sin(theta);
  AteResult r;
  r.num_poses = static_cast<int>(estimate.size());
  if (align) r.T_reference_estimate = {rx - (c * ex - s * ey), ry - (s * ex + c * ey), theta};
  double sum_sq = 0.0, sum = 0.0, yaw_sq = 0.0;
  for (std::size_t i = 0; i < estimate.size(); ++i) {
    const Pose2 aligned = r.T_reference_estimate * estimate[i];
    const double d = Distance(aligned, reference[i]);
    sum_sq += d * d;
    sum += d;
    r.max_m = std::max(r.max_m, d);
    const double dyaw = NormalizeAngle(aligned.yaw_rad - reference[i].yaw_rad);
    yaw_sq += dyaw * dyaw;
  }
  r.rmse_m = std::sqrt(sum_sq / n);
  r.mean_m = sum / n;
  r.yaw_rmse_rad = std::sqrt(yaw_sq / n);
  return r;
}

std::vector<Pose2> ComposeChain(const std::vector<Pose2>& steps) {
  std::vector<Pose2> poses{Pose2{}};
  poses.reserve(steps.size() + 1);
  for (const Pose2& step : steps) poses.push_back(poses.back() * step);
  return poses;
}

std::vector<Pose2> ReadGroundTruthChain(const std::string& path) {
  std::ifstream in = OpenTextInput(path, "ground-truth", LimitsConfig{}.max_input_file_mb);
  std::map<int, Pose2> steps;  // from id -> motion to id + 1
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream fields(line);
    std::string tag;
    if (!(fields >> tag) || tag[0] == '#') continue;
    const std::string where = path + ":" + std::to_string(line_no) + ": ";
    if (tag != "EDGE2" && tag != "EDGE_SE2") continue;  // vertices etc. are not needed
    int i = 0, j = 0;
    Pose2 step;
    if (!(fields >> i >> j >> step.x_m >> step.y_m >> step.yaw_rad) || !std::isfinite(step.x_m) ||
        !std::isfinite(step.y_m) || !std::isfinite(step.yaw_rad)) {
      throw InputError(where + "expected 'EDGE2 i j dx dy dtheta' with finite numbers");
    }
    if (j == i + 1) steps[i] = step;
  }
  std::vector<Pose2> chain;
  for (int k = 0; k < static_cast<int>(steps.size()); ++k) {
    const auto it = steps.find(k);
    if (it == steps.end()) {
      throw InputError(path + ": no edge " + std::to_string(k) + " -> " + std::to_string(k + 1));
    }
    chain.push_back(it->second);
  }
  return ComposeChain(chain);
}

}  // namespace uwbsar
