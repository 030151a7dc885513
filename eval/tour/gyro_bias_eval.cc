#include "eval/tour/gyro_bias_eval.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "core/types.h"
#include "drivers/sim/sim_stream.h"

namespace uwbsar::eval {

GyroBiasEvaluation EvaluateGyroBias(const slam::MapRun& run, const Config& config,
                                    std::uint64_t seed) {
  GyroBiasEvaluation e;
  const auto biases = run.slam->graph().GyroBiases();
  const auto it = biases.find(0);
  if (it == biases.end() || it->second.empty()) return e;
  const std::vector<std::pair<double, double>>& segments = it->second;
  // Segments are in absolute time (the stamps' seconds); the truth is in seconds from the start.
  const double start_s = NsToSeconds(run.first_stamp_ns);
  const double end_s = NsToSeconds(run.last_stamp_ns);
  const double segment_s = config.backend.gyro_bias_segment_s;
  std::vector<double> middles, lengths;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const double to =
        i + 1 < segments.size() ? segments[i + 1].first : segments[i].first + segment_s;
    const double a = std::clamp(segments[i].first, start_s, end_s);
    const double b = std::clamp(to, start_s, end_s);
    middles.push_back(0.5 * (a + b) - start_s);
    lengths.push_back(b - a);
  }
  std::vector<double> times = {0.0};
  times.insert(times.end(), middles.begin(), middles.end());
  const std::vector<double> truth = sim::TrueGyroBiasRadps(config.simulator.odometry, seed, times);
  if (truth.size() != times.size()) return e;  // no gyro in the simulated base
  e.segments = static_cast<int>(segments.size());
  e.true_turn_on_radps = truth[0];
  e.first_estimate_radps = segments[0].second;
  double weight = 0.0, sum_sq = 0.0;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    if (segments[i].first <= start_s) e.first_estimate_radps = segments[i].second;
    e.true_mean_radps += lengths[i] * truth[i + 1];
    e.estimated_mean_radps += lengths[i] * segments[i].second;
    weight += lengths[i];
    sum_sq += std::pow(segments[i].second - truth[i + 1], 2);
  }
  if (weight > 0) {
    e.true_mean_radps /= weight;
    e.estimated_mean_radps /= weight;
  }
  e.rms_error_radps = std::sqrt(sum_sq / static_cast<double>(segments.size()));
  return e;
}

std::string FormatGyroBiasEvaluation(const GyroBiasEvaluation& e) {
  if (e.segments == 0) return "no gyro bias estimated";
  constexpr double kDeg = 180.0 / M_PI;
  char line[300];
  std::snprintf(line, sizeof(line),
                "gyro bias: turn-on %+.4f dps (estimated %+.4f), mean over the run %+.4f dps "
                "(estimated %+.4f), %d segments' error rms %.4f dps",
                e.true_turn_on_radps * kDeg, e.first_estimate_radps * kDeg,
                e.true_mean_radps * kDeg, e.estimated_mean_radps * kDeg, e.segments,
                e.rms_error_radps * kDeg);
  return line;
}

}  // namespace uwbsar::eval
