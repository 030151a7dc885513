#include "backend/gyro_bias_track.h"

#include <ceres/sized_cost_function.h>

#include <algorithm>
#include <cmath>
#include <iterator>
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
      walk_radps_per_sqrt_s_(config.gyro_bias_walk_dps_per_sqrt_s * kRadPerDeg),
      turn_on_sigma_radps_(config.gyro_bias_sigma_dps * kRadPerDeg) {}

long long GyroBiasTrack::SegmentOf(double t_s) const {
  // Without a walk the bias is one constant: one segment for the whole run.
  if (!(walk_radps_per_sqrt_s_ > 0.0) || !std::isfinite(t_s)) return 0;
  constexpr double kMaxSegment = 1e15;  // far beyond any stamp (core/stamp_range.h)
  return static_cast<long long>(
      std::clamp(std::floor(t_s / segment_s_), -kMaxSegment, kMaxSegment));
}

void GyroBiasTrack::Tie(long long from, long long to) {
  Walk w;
  w.a = segments_.at(from).get();
  w.b = segments_.at(to).get();
  w.sigma = walk_radps_per_sqrt_s_ * std::sqrt(static_cast<double>(to - from) * segment_s_);
  w.residual = problem_->AddResidualBlock(new BiasWalk(w.sigma), nullptr, w.a, w.b);
  walks_[from] = w;
}

double* GyroBiasTrack::BlockAt(double t_s) {
  const long long k = SegmentOf(t_s);
  auto it = segments_.find(k);
  if (it != segments_.end()) return it->second.get();
  auto value = std::make_unique<double>(Latest());  // the newest estimate: the walk's mean
  double* x = value.get();
  problem_->AddParameterBlock(x, 1);
  const bool first = segments_.empty();
  segments_.emplace(k, std::move(value));
  if (first) {
    problem_->AddResidualBlock(new BiasPrior(0.0, turn_on_sigma_radps_), nullptr, x);
    priors_.push_back({x, 0.0, turn_on_sigma_radps_});
    return x;
  }
  auto self = segments_.find(k);
  const bool has_prev = self != segments_.begin();
  const auto next = std::next(self);
  if (has_prev) {
    const long long prev = std::prev(self)->first;
    if (next != segments_.end()) {  // between two tied segments: the walk now passes through k
      problem_->RemoveResidualBlock(walks_.at(prev).residual);
      walks_.erase(prev);
    }
    Tie(prev, k);
  }
  if (next != segments_.end()) Tie(k, next->first);
  return x;
}

void GyroBiasTrack::AddMeasurement(double t_s, double bias_radps, double sigma_radps) {
  double* x = BlockAt(t_s);
  problem_->AddResidualBlock(new BiasPrior(bias_radps, sigma_radps), nullptr, x);
  priors_.push_back({x, bias_radps, sigma_radps});
}

double GyroBiasTrack::Chi2() const {
  double sum = 0.0;
  for (const Prior& p : priors_) sum += std::pow((*p.x - p.mean) / p.sigma, 2);
  for (const auto& [k, w] : walks_) sum += std::pow((*w.b - *w.a) / w.sigma, 2);
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
