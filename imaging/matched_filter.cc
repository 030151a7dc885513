#include "imaging/matched_filter.h"

#include <fftw3.h>

#include <cassert>
#include <cstring>
#include <mutex>

namespace uwbsar {
namespace {

// FFTW's planner is not thread-safe; execution with the new-array API is.
std::mutex& PlannerMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

// FFTW_ESTIMATE keeps the plans (and so the results) identical run to run,
// which the byte-identical-output promise of `uwbsar map` depends on.
struct MatchedFilter::Plans {
  float* real = nullptr;                 ///< N real samples
  fftwf_complex* spectrum = nullptr;     ///< N/2 + 1 bins
  fftwf_complex* up_spectrum = nullptr;  ///< N * U bins (analytic, zero-padded)
  fftwf_complex* up_time = nullptr;      ///< N * U samples
  fftwf_plan forward = nullptr;
  fftwf_plan backward_real = nullptr;
  fftwf_plan backward_analytic = nullptr;
};

int NextFastFftLength(int min_length) {
  for (int n = std::max(1, min_length);; ++n) {
    int m = n;
    for (int p : {2, 3, 5, 7}) {
      while (m % p == 0) m /= p;
    }
    if (m == 1) return n;
  }
}

MatchedFilter::MatchedFilter(const std::vector<float>& pulse, int pulse_center, int scan_length,
                             int analytic_upsampling)
    : scan_length_(scan_length),
      fft_length_(NextFastFftLength(scan_length + static_cast<int>(pulse.size()))),
      upsampling_(analytic_upsampling),
      plans_(std::make_unique<Plans>()) {
  assert(scan_length > 0 && !pulse.empty() && analytic_upsampling >= 1);
  const int n = fft_length_;
  const int nu = n * upsampling_;
  {
    std::lock_guard<std::mutex> lock(PlannerMutex());
    plans_->real = fftwf_alloc_real(n);
    plans_->spectrum = fftwf_alloc_complex(n / 2 + 1);
    plans_->up_spectrum = fftwf_alloc_complex(nu);
    plans_->up_time = fftwf_alloc_complex(nu);
    plans_->forward = fftwf_plan_dft_r2c_1d(n, plans_->real, plans_->spectrum, FFTW_ESTIMATE);
    plans_->backward_real = fftwf_plan_dft_c2r_1d(n, plans_->spectrum, plans_->real, FFTW_ESTIMATE);
    plans_->backward_analytic =
        fftwf_plan_dft_1d(nu, plans_->up_spectrum, plans_->up_time, FFTW_BACKWARD, FFTW_ESTIMATE);
  }
  // Kernel with the pulse centre at index 0 (negative lags wrap to the end), so
  // that correlation output index k is the echo-centre position.
  std::memset(plans_->real, 0, sizeof(float) * n);
  for (int j = 0; j < static_cast<int>(pulse.size()); ++j) {
    plans_->real[((j - pulse_center) % n + n) % n] = pulse[j];
  }
  fftwf_execute(plans_->forward);
  pulse_spectrum_conj_.resize(n / 2 + 1);
  const float scale = 1.0f / static_cast<float>(n);  // FFTW transforms are unnormalised
  for (int k = 0; k <= n / 2; ++k) {
    pulse_spectrum_conj_[k] =
        std::conj(std::complex<float>(plans_->spectrum[k][0], plans_->spectrum[k][1])) * scale;
  }
}

MatchedFilter::~MatchedFilter() {
  std::lock_guard<std::mutex> lock(PlannerMutex());
  fftwf_destroy_plan(plans_->forward);
  fftwf_destroy_plan(plans_->backward_real);
  fftwf_destroy_plan(plans_->backward_analytic);
  fftwf_free(plans_->real);
  fftwf_free(plans_->spectrum);
  fftwf_free(plans_->up_spectrum);
  fftwf_free(plans_->up_time);
}

void MatchedFilter::ForwardSpectrum(const float* scan) {
  std::memcpy(plans_->real, scan, sizeof(float) * scan_length_);
  std::memset(plans_->real + scan_length_, 0, sizeof(float) * (fft_length_ - scan_length_));
  fftwf_execute_dft_r2c(plans_->forward, plans_->real, plans_->spectrum);
  for (int k = 0; k <= fft_length_ / 2; ++k) {
    const std::complex<float> y =
        std::complex<float>(plans_->spectrum[k][0], plans_->spectrum[k][1]) *
        pulse_spectrum_conj_[k];
    plans_->spectrum[k][0] = y.real();
    plans_->spectrum[k][1] = y.imag();
  }
}

void MatchedFilter::CompressReal(const float* scan, float* out) {
  ForwardSpectrum(scan);
  fftwf_execute_dft_c2r(plans_->backward_real, plans_->spectrum, plans_->real);
  std::memcpy(out, plans_->real, sizeof(float) * scan_length_);
}

void MatchedFilter::CompressAnalytic(const float* scan, std::complex<float>* out) {
  ForwardSpectrum(scan);
  const int n = fft_length_;
  const int nu = n * upsampling_;
  // Analytic signal: DC and Nyquist once, positive frequencies twice, negative zero.
  // Zero-padding the spectrum to N*U upsamples by U (band-limited interpolation).
  fftwf_complex* z = plans_->up_spectrum;
  std::memset(z, 0, sizeof(fftwf_complex) * nu);
  z[0][0] = plans_->spectrum[0][0];
  z[0][1] = plans_->spectrum[0][1];
  const int half = n / 2;
  for (int k = 1; k < half + (n % 2); ++k) {
    z[k][0] = 2.0f * plans_->spectrum[k][0];
    z[k][1] = 2.0f * plans_->spectrum[k][1];
  }
  if (n % 2 == 0) {
    z[half][0] = plans_->spectrum[half][0];
    z[half][1] = plans_->spectrum[half][1];
  }
  fftwf_execute_dft(plans_->backward_analytic, z, plans_->up_time);
  const int count = scan_length_ * upsampling_;
  for (int j = 0; j < count; ++j) {
    out[j] = std::complex<float>(plans_->up_time[j][0], plans_->up_time[j][1]);
  }
}

}  // namespace uwbsar
