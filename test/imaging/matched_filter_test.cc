#include "imaging/matched_filter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "drivers/sim/echo_simulator.h"
#include "imaging/pulse.h"
#include "slam/app_config.h"

namespace uwbsar {
namespace {

std::vector<float> Pulse(int* center) {
  const GaussianPulse pulse{PulseConfig{}};
  *center = pulse.CenterIndex();
  return pulse.Sampled();
}

// 'same'-length correlation by the definition: y[k] = sum_j r[k + j - c] s[j].
std::vector<double> DirectCorrelation(const std::vector<float>& r, const std::vector<float>& s,
                                      int c) {
  std::vector<double> y(r.size(), 0.0);
  for (int k = 0; k < static_cast<int>(r.size()); ++k) {
    for (int j = 0; j < static_cast<int>(s.size()); ++j) {
      const int n = k + j - c;
      if (n >= 0 && n < static_cast<int>(r.size())) y[k] += double(r[n]) * s[j];
    }
  }
  return y;
}

TEST(MatchedFilterTest, FftCorrelationEqualsDirectCorrelationForAnyLength) {
  int center = 0;
  const std::vector<float> pulse = Pulse(&center);
  std::mt19937 rng(1);
  std::normal_distribution<float> noise(0.0f, 1.0f);
  for (int length : {37, 1000, 1500, 1023}) {
    std::vector<float> scan(length);
    for (float& v : scan) v = noise(rng);
    MatchedFilter filter(pulse, center, length);
    std::vector<float> fast(length);
    filter.CompressReal(scan.data(), fast.data());
    // FFT result is scaled by 1/N relative to the raw correlation (unit conventions aside).
    const std::vector<double> direct = DirectCorrelation(scan, pulse, center);
    double max_err = 0.0, max_val = 0.0;
    for (int k = 0; k < length; ++k) {
      max_err = std::max(max_err, std::abs(fast[k] - direct[k]));
      max_val = std::max(max_val, std::abs(direct[k]));
    }
    EXPECT_LT(max_err, 1e-4 * max_val) << "length " << length;
  }
}

TEST(MatchedFilterTest, EchoPeaksAtItsDelayBin) {
  const Config config;
  const SensorGeometry geometry = SensorGeometry::FromConfig(config.radars[0], config.pulse);
  EchoSimulator sim(config.pulse, geometry, EchoModel{});
  int center = 0;
  const std::vector<float> pulse = Pulse(&center);
  MatchedFilter filter(pulse, center, 1000, 4);
  for (double range_m : {0.5, 1.234, 2.9}) {
    std::vector<float> scan(1000, 0.0f);
    sim.AddEcho(range_m, 1.0, &scan);
    std::vector<float> real(1000);
    filter.CompressReal(scan.data(), real.data());
    const int peak = static_cast<int>(std::max_element(real.begin(), real.end()) - real.begin());
    // The real output is sampled at 3.2 samples per carrier cycle: its largest
    // sample may sit on a neighbouring crest, half a wavelength away in range.
    const double half_wavelength_m = kSpeedOfLightMps / config.pulse.center_frequency_hz / 2;
    EXPECT_NEAR(peak * geometry.bin_size_m, range_m, half_wavelength_m + geometry.bin_size_m);
    // The analytic envelope peaks at the exact range (upsampled by 4).
    std::vector<std::complex<float>> z(4000);
    filter.CompressAnalytic(scan.data(), z.data());
    int best = 0;
    for (int j = 0; j < 4000; ++j) best = std::abs(z[j]) > std::abs(z[best]) ? j : best;
    EXPECT_NEAR(best * geometry.bin_size_m / 4, range_m, geometry.bin_size_m / 4 + 1e-4);
  }
}

TEST(MatchedFilterTest, AnalyticRealPartEqualsRealCompression) {
  int center = 0;
  const std::vector<float> pulse = Pulse(&center);
  std::mt19937 rng(2);
  std::normal_distribution<float> noise(0.0f, 1.0f);
  std::vector<float> scan(1000);
  for (float& v : scan) v = noise(rng);
  MatchedFilter plain(pulse, center, 1000, 1);
  MatchedFilter up(pulse, center, 1000, 4);
  std::vector<float> real(1000);
  std::vector<std::complex<float>> z1(1000), z4(4000);
  plain.CompressReal(scan.data(), real.data());
  plain.CompressAnalytic(scan.data(), z1.data());
  up.CompressAnalytic(scan.data(), z4.data());
  double max_val = 0;
  for (float v : real) max_val = std::max(max_val, double(std::abs(v)));
  for (int k = 0; k < 1000; ++k) {
    EXPECT_NEAR(z1[k].real(), real[k], 1e-4 * max_val);
    // Upsampling interpolates: every 4th sample is an original one.
    EXPECT_NEAR(std::abs(z4[4 * k] - z1[k]), 0.0, 1e-4 * max_val);
  }
}

TEST(MatchedFilterTest, FastLengthsHaveOnlySmallPrimeFactors) {
  EXPECT_EQ(NextFastFftLength(1047), 1050);
  EXPECT_EQ(NextFastFftLength(1024), 1024);
  EXPECT_EQ(NextFastFftLength(11), 12);
}

}  // namespace
}  // namespace uwbsar
