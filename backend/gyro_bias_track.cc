#include "backend/gyro_bias_track.h"

#include <ceres/sized_cost_function.h>

#include <cmath>
#include <utility>

namespace uwbsar {
namespace {

constexpr double kRadPerDeg = M_PI / 180.0;

/// r = (b - mean) / sigma.
class BiasPrior final : public ceres::SizedCostFunction<1, 1> {
 public:
  BiasPrior(double mean, double sigma) : mean_(mean), sigma_(sigma) {}
  bool Evaluate(double const* const* p, double* r, double** j) const override {
    r[0] = (p[0][0] - mean_) / sigma_;
    if (j != nullptr && j[0] != nullptr) j[0][0] = 1.0 / sigma_;
    return true;
  }

 private:
  double mean_, sigma_;
};

/// r = (b_next - b) / sigma.
class BiasWalk final : public ceres::SizedCostFunction<1, 1, 1> {
 public:
  explicit BiasWalk(double sigma) : sigma_(sigma) {}
  bool Evaluate(double const* const* p, double* r, double** j) const override {
    r[0] = (p[1][0] - p[0][0]) / sigma_;
    if (j != nullptr) {
      if (j[0] != nullptr) j[0][0] = -1.0 / sigma_;
      if (j[1] != nullptr) j[1][0] = 1.0 / sigma_;
    }
    return true;
  }

 private:
  double sigma_;
};

}  // namespace

GyroBiasTrack::GyroBiasTrack(ceres::Problem* problem, const BackendConfig& config)
    : problem_(problem),
      segment_s_(config.gyro_bias_segment_s),
      walk_sigma_radps_(config.gyro_bias_walk_dps_per_sqrt_s * kRadPerDeg *
                        std::sqrt(config.gyro_bias_segment_s)),
      turn_on_sigma_radps_(config.gyro_bias_sigma_dps * kRadPerDeg) {}

long long GyroBiasTrack::SegmentOf(double t_s) const {
  // Without a walk the bias is one constant: one segment for the whole run.
  if (!(walk_sigma_radps_ > 0.0) || !std::isfinite(t_s)) return 0;
  return static_cast<long long>(std::floor(t_s / segment_s_));
}

double* GyroBiasTrack::MakeSegment(long long k) {
  auto value = std::make_unique<double>(Latest());  // the newest estimate: the walk's mean
  double* x = value.get();
  problem_->AddParameterBlock(x, 1);
  if (segments_.empty()) {
    problem_->AddResidualBlock(new BiasPrior(0.0, turn_on_sigma_radps_), nullptr, x);
    terms_.push_back({x, nullptr, 0.0, turn_on_sigma_radps_});
  }
  segments_.emplace(k, std::move(value));
  return x;
}

double* GyroBiasTrack::BlockAt(double t_s) {
  const long long k = SegmentOf(t_s);
  auto it = segments_.find(k);
  if (it != segments_.end()) return it->second.get();
  if (segments_.empty()) return MakeSegment(k);
  // Contiguous: every segment between the track's nearer end and k, each tied to its neighbour.
  if (k > segments_.rbegin()->first) {
    for (long long i = segments_.rbegin()->first + 1; i <= k; ++i) {
      double* prev = segments_.rbegin()->second.get();
      double* x = MakeSegment(i);
      problem_->AddResidualBlock(new BiasWalk(walk_sigma_radps_), nullptr, prev, x);
      terms_.push_back({prev, x, 0.0, walk_sigma_radps_});
    }
  } else {
    for (long long i = segments_.begin()->first - 1; i >= k; --i) {
      double* next = segments_.begin()->second.get();
      double* x = MakeSegment(i);
      problem_->AddResidualBlock(new BiasWalk(walk_sigma_radps_), nullptr, x, next);
      terms_.push_back({x, next, 0.0, walk_sigma_radps_});
    }
  }
  return segments_.at(k).get();
}

void GyroBiasTrack::AddMeasurement(double t_s, double bias_radps, double sigma_radps) {
  double* x = BlockAt(t_s);
  problem_->AddResidualBlock(new BiasPrior(bias_radps, sigma_radps), nullptr, x);
  terms_.push_back({x, nullptr, bias_radps, sigma_radps});
}

double GyroBiasTrack::Chi2() const {
  double sum = 0.0;
  for (const Term& t : terms_) {
    const double r = (t.b != nullptr ? *t.b - *t.a : *t.a - t.mean) / t.sigma;
    sum += r * r;
  }
  return sum;
}

std::vector<double> GyroBiasTrack::State() const {
  std::vector<double> state;
  state.reserve(segments_.size());
  for (const auto& [k, x] : segments_) state.push_back(*x);
  return state;
}

void GyroBiasTrack::Restore(const std::vector<double>& state) {
  std::size_t i = 0;
  for (auto& [k, x] : segments_) {
    if (i < state.size()) *x = state[i++];
  }
}

double GyroBiasTrack::Latest() const {
  return segments_.empty() ? 0.0 : *segments_.rbegin()->second;
}

std::vector<std::pair<double, double>> GyroBiasTrack::Segments() const {
  std::vector<std::pair<double, double>> out;
  for (const auto& [k, x] : segments_) out.push_back({static_cast<double>(k) * segment_s_, *x});
  return out;
}

}  // namespace uwbsar
