// A range-compressed scan prepared for back-projection: a lookup table over
// range, cropped to the radar's imaged ranges, real (paper mode) or complex
// analytic and upsampled (coherent mode).
#pragma once

#include <complex>
#include <memory>
#include <vector>

#include "imaging/matched_filter.h"
#include "imaging/pulse_config.h"
#include "imaging/sensor_geometry.h"

namespace uwbsar {

struct RangeProfile {
  double range_start_m = 0.0;      ///< range of table entry 0
  double range_step_m = 0.0;       ///< range between entries (bin size / upsampling)
  double max_valid_range_m = 0.0;  ///< farthest range the scan's samples cover
  /// Paper mode: the compressed samples. Coherent mode: the real part of the
  /// upsampled analytic signal (planar storage so the lookup vectorises).
  std::vector<float> real;
  std::vector<float> imag;  ///< coherent mode only: imaginary part of the analytic signal
  /// Paper mode, when asked (imaging.method ffbp): the Hilbert transform of `real` at the same
  /// samples, so that real + j quadrature is the analytic signal whose real part is imaged.
  std::vector<float> quadrature;
  bool coherent() const { return !imag.empty(); }
  std::size_t size() const { return real.size(); }
};

/// Turns raw scans into RangeProfiles for one radar. Not thread-safe (owns FFT buffers).
class RangeCompressor {
 public:
  /// `quadrature`: paper mode also fills RangeProfile::quadrature.
  RangeCompressor(const PulseConfig& pulse, const SensorGeometry& geometry, bool coherent,
                  int oversampling, bool quadrature = false);

  /// Compresses `samples` (any length > 1; the filter is rebuilt if the length changes).
  /// Samples below geometry.zero_leading_samples are zeroed first, as the reference does.
  std::shared_ptr<const RangeProfile> Compress(const std::vector<float>& samples);

 private:
  void EnsureFilter(int length);

  PulseConfig pulse_;
  SensorGeometry geometry_;
  bool coherent_;
  bool quadrature_;
  int oversampling_;
  std::vector<float> pulse_samples_;
  int pulse_center_ = 0;
  std::unique_ptr<MatchedFilter> filter_;
  std::vector<float> scratch_in_;
  std::vector<float> scratch_real_;
  std::vector<std::complex<float>> scratch_analytic_;
};

}  // namespace uwbsar
