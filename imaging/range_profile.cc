#include "imaging/range_profile.h"

#include <algorithm>
#include <cmath>

#include "imaging/pulse.h"

namespace uwbsar {

RangeCompressor::RangeCompressor(const PulseConfig& pulse, const SensorGeometry& geometry,
                                 bool coherent, int oversampling, bool quadrature)
    : pulse_(pulse),
      geometry_(geometry),
      coherent_(coherent),
      quadrature_(quadrature && !coherent),
      oversampling_(coherent ? std::max(1, oversampling) : 1) {
  const GaussianPulse model(pulse);
  pulse_samples_ = model.Sampled();
  pulse_center_ = model.CenterIndex();
}

void RangeCompressor::EnsureFilter(int length) {
  if (filter_ && filter_->scan_length() == length) return;
  filter_ = std::make_unique<MatchedFilter>(pulse_samples_, pulse_center_, length, oversampling_);
  scratch_real_.resize(length);
  scratch_analytic_.resize(static_cast<std::size_t>(length) * oversampling_);
}

std::shared_ptr<const RangeProfile> RangeCompressor::Compress(const std::vector<float>& samples) {
  const int length = static_cast<int>(samples.size());
  EnsureFilter(length);
  scratch_in_.assign(samples.begin(), samples.end());
  const int zeroed = std::min(geometry_.zero_leading_samples, length);
  std::fill(scratch_in_.begin(), scratch_in_.begin() + zeroed, 0.0f);

  auto profile = std::make_shared<RangeProfile>();
  const double step = geometry_.bin_size_m / oversampling_;
  const int table_length = length * oversampling_;
  // Keep only the entries the sector can reach, with two of padding each side so
  // that linear interpolation never reads outside the table.
  const int first = std::clamp(
      static_cast<int>(std::floor((geometry_.min_range_m - geometry_.range_offset_m) / step)) - 2,
      0, table_length - 1);
  const int last = std::clamp(
      static_cast<int>(std::ceil((geometry_.max_range_m - geometry_.range_offset_m) / step)) + 2,
      first + 1, table_length - 1);
  profile->range_start_m = geometry_.range_offset_m + first * step;
  profile->range_step_m = step;
  profile->max_valid_range_m = geometry_.range_offset_m + (table_length - 1) * step;
  if (coherent_ || quadrature_) {
    filter_->CompressAnalytic(scratch_in_.data(), scratch_analytic_.data());
    profile->real.resize(static_cast<std::size_t>(last - first + 1));
    std::vector<float>& imag = coherent_ ? profile->imag : profile->quadrature;
    imag.resize(profile->real.size());
    for (int k = first; k <= last; ++k) {
      profile->real[k - first] = scratch_analytic_[k].real();
      imag[k - first] = scratch_analytic_[k].imag();
    }
  } else {
    filter_->CompressReal(scratch_in_.data(), scratch_real_.data());
    profile->real.assign(scratch_real_.begin() + first, scratch_real_.begin() + last + 1);
  }
  return profile;
}

}  // namespace uwbsar
