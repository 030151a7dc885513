// Range compression by matched filtering (paper eqs. h(t) = s*(t), y = r * h),
// computed by FFT: y = IFFT(FFT(r) . conj(FFT(s))) on a zero-padded length with
// the pulse centred at lag 0, so y[k] peaks where the echo's centre lies.
// The analytic path keeps only positive frequencies (y + j H{y}) and can
// upsample by zero-padding the spectrum, which is exact for band-limited data.
//
// Not thread-safe: each thread uses its own instance (plans are shared by FFTW).
#pragma once

#include <complex>
#include <memory>
#include <vector>

namespace uwbsar {

class MatchedFilter {
 public:
  /// `pulse` sampled at fs with its centre at `pulse_center`; scans have `scan_length` samples.
  /// `analytic_upsampling` >= 1 sets the output rate of CompressAnalytic.
  MatchedFilter(const std::vector<float>& pulse, int pulse_center, int scan_length,
                int analytic_upsampling = 1);
  ~MatchedFilter();
  MatchedFilter(const MatchedFilter&) = delete;
  MatchedFilter& operator=(const MatchedFilter&) = delete;

  int scan_length() const { return scan_length_; }
  int fft_length() const { return fft_length_; }
  int analytic_upsampling() const { return upsampling_; }

  /// Real correlation, 'same' length: out[k] for k in [0, scan_length).
  void CompressReal(const float* scan, float* out);
  /// Analytic correlation: out[j] is the value at sample j / upsampling,
  /// j in [0, scan_length * upsampling).
  void CompressAnalytic(const float* scan, std::complex<float>* out);

 private:
  struct Plans;
  void ForwardSpectrum(const float* scan);

  int scan_length_;
  int fft_length_;
  int upsampling_;
  std::vector<std::complex<float>> pulse_spectrum_conj_;  ///< conj(FFT(s)) / N
  std::unique_ptr<Plans> plans_;
};

/// Smallest n >= min_length of the form 2^a 3^b 5^c 7^d (fast FFT sizes).
int NextFastFftLength(int min_length);

}  // namespace uwbsar
