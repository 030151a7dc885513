#include "imaging/factorized_back_projection.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "imaging/pulse.h"

namespace uwbsar {
PolarSampling PolarSamplingFor(const FfbpConfig& ffbp, const PulseConfig& pulse, bool coherent) {
  PolarSampling s;
  s.coherent = coherent;
  s.carrier_wavenumber_rad_per_m = 4.0 * M_PI * pulse.center_frequency_hz / kSpeedOfLightMps;
  // The -6 dB band is fc +- B/2; the spectrum reaches about fc + B before it is negligible.
  s.min_wavelength_m = kSpeedOfLightMps / (pulse.center_frequency_hz + pulse.bandwidth_hz);
  // The shortest two-way fringe along range of the baseband the polar images hold, whose band
  // reaches about B.
  s.range_step_m = kSpeedOfLightMps / (2.0 * pulse.bandwidth_hz) / ffbp.range_oversampling;
  s.angular_oversampling = ffbp.angular_oversampling;
  return s;
}

FactorizedBackProjector::FactorizedBackProjector(const FfbpConfig& config,
                                                 const PolarSampling& sampling, int threads)
    : config_(config),
      sampling_(sampling),
      threads_(std::max(1, threads)),
      levels_(static_cast<std::size_t>(config.levels)),
      direct_(std::max(1, threads)) {}

void FactorizedBackProjector::Footprint::Add(const std::vector<RowSpan>& spans, int rows) {
  if (lo.empty()) {
    lo.assign(static_cast<std::size_t>(rows), INT_MAX);
    hi.assign(static_cast<std::size_t>(rows), INT_MIN);
  }
  for (const RowSpan& sp : spans) {
    lo[sp.row] = std::min(lo[sp.row], sp.col_begin);
    hi[sp.row] = std::max(hi[sp.row], sp.col_end);
  }
}

void FactorizedBackProjector::Footprint::Add(const Footprint& other) {
  if (lo.empty()) {
    *this = other;
    return;
  }
  for (std::size_t r = 0; r < other.lo.size() && r < lo.size(); ++r) {
    lo[r] = std::min(lo[r], other.lo[r]);
    hi[r] = std::max(hi[r], other.hi[r]);
  }
}

std::vector<RowSpan> FactorizedBackProjector::Footprint::Spans() const {
  std::vector<RowSpan> spans;
  for (std::size_t r = 0; r < lo.size(); ++r) {
    if (lo[r] < hi[r]) spans.push_back({static_cast<int>(r), lo[r], hi[r]});
  }
  return spans;
}

int FactorizedBackProjector::pending_scans() const {
  std::size_t n = base_.size();
  for (const auto& level : levels_) {
    for (const Pending& part : level) n += part.image.pulses().size();
  }
  return static_cast<int>(n);
}

long long FactorizedBackProjector::Add(std::shared_ptr<const RangeProfile> profile,
                                       const Pose2& T_grid_sensor, const SensorGeometry& geometry,
                                       const ImageGrid& grid, cv::Mat* image) {
  const std::vector<float>& imag = sampling_.coherent ? profile->imag : profile->quadrature;
  if (imag.size() != profile->real.size()) {
    throw std::invalid_argument(
        "imaging.method ffbp needs analytic range profiles (RangeCompressor with quadrature in "
        "paper mode)");
  }
  geometry_ = geometry;
  base_.push_back({std::move(profile), T_grid_sensor});
  const int count = static_cast<int>(base_.size());
  // The footprint's scans: the first, the last (at TakeBase) and any that turned more than
  // kFootprintTurnRad since the last of them.
  if (count == 1 ||
      std::abs(NormalizeAngle(T_grid_sensor.yaw_rad - footprint_yaw_rad_)) > kFootprintTurnRad) {
    AddToFootprint(base_.back(), grid);
  }
  long long pixels = 0;
  if (count >= config_.base_scans) CloseBase(grid, image, &pixels);
  return pixels;
}

void FactorizedBackProjector::AddToFootprint(const SubaperturePulse& pulse, const ImageGrid& grid) {
  footprint_scans_ = base_.size();
  footprint_yaw_rad_ = pulse.T_grid_sensor.yaw_rad;
  const SectorShape sector{geometry_.fov_half_angle_rad, geometry_.min_range_m,
                           std::min(geometry_.max_range_m, pulse.profile->max_valid_range_m)};
  spans_.clear();
  if (pulse.profile->size() >= 2 && sector.max_range_m > sector.min_range_m &&
      ComputeSectorSpans(grid, pulse.T_grid_sensor, sector, &spans_) > 0) {
    base_footprint_.Add(spans_, grid.rows);
  }
}

std::optional<FactorizedBackProjector::Pending> FactorizedBackProjector::TakeBase(
    const ImageGrid& grid, cv::Mat* image, long long* pixels) {
  if (base_.size() >= 2 && footprint_scans_ < base_.size()) AddToFootprint(base_.back(), grid);
  footprint_scans_ = 0;
  std::vector<SubaperturePulse> scans;
  scans.swap(base_);
  Footprint footprint;
  std::swap(footprint, base_footprint_);
  std::optional<PolarSubaperture> polar =
      PolarSubaperture::FromPulses(scans, geometry_, sampling_, threads_);
  if (!polar) {
    *pixels += ProjectDirect(scans, grid, image);
    return std::nullopt;
  }
  return Pending{std::move(*polar), std::move(footprint)};
}

void FactorizedBackProjector::CloseBase(const ImageGrid& grid, cv::Mat* image, long long* pixels) {
  std::optional<Pending> part = TakeBase(grid, image, pixels);
  if (!part) return;
  if (levels_.empty()) {
    *pixels += Project(*part, grid, image);
    return;
  }
  levels_[0].push_back(std::move(*part));
  Carry(0, grid, image, pixels);
}

std::optional<FactorizedBackProjector::Pending> FactorizedBackProjector::MergeParts(
    const std::vector<Pending>& parts) {
  std::vector<const PolarSubaperture*> refs;
  for (const Pending& p : parts) refs.push_back(&p.image);
  std::optional<PolarSubaperture> merged =
      PolarSubaperture::Merge(refs, geometry_, sampling_, threads_);
  if (!merged) return std::nullopt;
  Pending out{std::move(*merged), {}};
  for (const Pending& p : parts) out.footprint.Add(p.footprint);
  return out;
}

void FactorizedBackProjector::Carry(int level, const ImageGrid& grid, cv::Mat* image,
                                    long long* pixels) {
  std::vector<Pending>& parts = levels_[static_cast<std::size_t>(level)];
  if (static_cast<int>(parts.size()) < config_.merge_factor) return;
  std::optional<Pending> merged = MergeParts(parts);
  if (!merged) {  // the parts do not fit one grid: each goes onto the image as it is
    for (const Pending& p : parts) *pixels += Project(p, grid, image);
    parts.clear();
    return;
  }
  parts.clear();
  if (level + 1 == static_cast<int>(levels_.size())) {
    *pixels += Project(*merged, grid, image);
    return;
  }
  levels_[static_cast<std::size_t>(level) + 1].push_back(std::move(*merged));
  Carry(level + 1, grid, image, pixels);
}

long long FactorizedBackProjector::Flush(const ImageGrid& grid, cv::Mat* image, cv::Rect* touched) {
  const long long pixels = FlushParts(grid, image);
  if (touched != nullptr) *touched = touched_;
  touched_ = cv::Rect();
  return pixels;
}

long long FactorizedBackProjector::FlushParts(const ImageGrid& grid, cv::Mat* image) {
  long long pixels = 0;
  // What is pending, oldest scans first: the highest levels, then the base.
  std::vector<Pending> parts;
  for (auto level = levels_.rbegin(); level != levels_.rend(); ++level) {
    for (Pending& p : *level) parts.push_back(std::move(p));
    level->clear();
  }
  if (!base_.empty()) {
    if (std::optional<Pending> part = TakeBase(grid, image, &pixels)) {
      parts.push_back(std::move(*part));
    }
  }
  if (parts.size() >= 2) {  // one projection instead of one per part, when they fit one grid
    if (std::optional<Pending> merged = MergeParts(parts)) {
      return pixels + Project(*merged, grid, image);
    }
  }
  for (const Pending& p : parts) pixels += Project(p, grid, image);
  return pixels;
}

long long FactorizedBackProjector::Project(const Pending& part, const ImageGrid& grid,
                                           cv::Mat* image) {
  const std::vector<RowSpan> spans = part.footprint.Spans();
  UniteBounds(&touched_, SpansBounds(spans));
  return part.image.ProjectInto(grid, spans, image, threads_);
}

long long FactorizedBackProjector::ProjectDirect(const std::vector<SubaperturePulse>& pulses,
                                                 const ImageGrid& grid, cv::Mat* image) {
  long long pixels = 0;
  for (const SubaperturePulse& p : pulses) {
    cv::Rect touched;
    pixels += direct_.Accumulate(*p.profile, p.T_grid_sensor, geometry_, grid, image, &touched);
    UniteBounds(&touched_, touched);
  }
  return pixels;
}

}  // namespace uwbsar
