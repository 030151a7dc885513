// RangeCompressor: an echo compresses to a peak at its range (paper and coherent
// mode), the table covers the sector's ranges with padding and stops at the scan's
// last sample, leading samples are zeroed, and a change of scan length is handled.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "imaging/pulse.h"
#include "imaging/range_profile.h"

namespace uwbsar {
namespace {

SensorGeometry Geometry() {
  SensorGeometry g;
  g.fov_half_angle_rad = 0.5;
  g.min_range_m = 0.4;
  g.max_range_m = 3.0;
  g.range_offset_m = 0.0;
  g.bin_size_m = RangeBinSizeM(PulseConfig{});
  g.num_samples = 600;
  return g;
}

/// A scan of `length` samples holding the transmitted pulse centred on each of `centres`.
std::vector<float> Echoes(int length, const std::vector<int>& centres, float amplitude = 1.0f) {
  const GaussianPulse pulse{PulseConfig{}};
  const std::vector<float> s = pulse.Sampled();
  const int c = pulse.CenterIndex();
  std::vector<float> scan(static_cast<std::size_t>(length), 0.0f);
  for (int centre : centres) {
    for (int i = 0; i < static_cast<int>(s.size()); ++i) {
      const int k = centre - c + i;
      if (k >= 0 && k < length) scan[static_cast<std::size_t>(k)] += amplitude * s[i];
    }
  }
  return scan;
}

/// Range of the strongest entry of a profile (magnitude in coherent mode).
double PeakRangeM(const RangeProfile& p) {
  std::size_t best = 0;
  double best_v = -1.0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const double v = p.coherent() ? std::hypot(p.real[k], p.imag[k]) : p.real[k];
    if (v > best_v) best_v = v, best = k;
  }
  return p.range_start_m + static_cast<double>(best) * p.range_step_m;
}

double LastRangeM(const RangeProfile& p) {
  return p.range_start_m + static_cast<double>(p.size() - 1) * p.range_step_m;
}

TEST(RangeCompressorTest, PaperModeEchoPeaksAtItsRange) {
  const SensorGeometry g = Geometry();
  RangeCompressor compressor(PulseConfig{}, g, /*coherent=*/false, 4);
  const auto profile = compressor.Compress(Echoes(600, {200}));
  EXPECT_FALSE(profile->coherent());
  EXPECT_DOUBLE_EQ(profile->range_step_m, g.bin_size_m);  // no upsampling in paper mode
  EXPECT_NEAR(PeakRangeM(*profile), 200 * g.bin_size_m, 0.5 * g.bin_size_m);
}

TEST(RangeCompressorTest, CoherentModeEchoPeaksAtItsRangeOnAnUpsampledTable) {
  const SensorGeometry g = Geometry();
  RangeCompressor compressor(PulseConfig{}, g, /*coherent=*/true, 4);
  const auto profile = compressor.Compress(Echoes(600, {321}));
  ASSERT_TRUE(profile->coherent());
  EXPECT_EQ(profile->imag.size(), profile->real.size());
  EXPECT_DOUBLE_EQ(profile->range_step_m, g.bin_size_m / 4);
  EXPECT_NEAR(PeakRangeM(*profile), 321 * g.bin_size_m, profile->range_step_m);
}

TEST(RangeCompressorTest, TableCoversTheSectorRangesWithPadding) {
  const SensorGeometry g = Geometry();
  for (const bool coherent : {false, true}) {
    RangeCompressor compressor(PulseConfig{}, g, coherent, 4);
    const auto profile = compressor.Compress(Echoes(600, {200}));
    const double step = profile->range_step_m;
    EXPECT_LE(profile->range_start_m, g.min_range_m - step) << coherent;
    EXPECT_GE(LastRangeM(*profile), g.max_range_m + step) << coherent;
    // Two entries of padding, not the whole scan.
    EXPECT_GT(profile->range_start_m, g.min_range_m - 4 * step) << coherent;
    EXPECT_LT(LastRangeM(*profile), g.max_range_m + 4 * step) << coherent;
    EXPECT_NEAR(profile->max_valid_range_m, (600 * (coherent ? 4 : 1) - 1) * step, 1e-9);
  }
}

TEST(RangeCompressorTest, ScanShorterThanMaxRangeEndsAtItsLastSample) {
  const SensorGeometry g = Geometry();  // 300 samples reach 1.93 m < max_range_m
  RangeCompressor compressor(PulseConfig{}, g, /*coherent=*/false, 1);
  const auto profile = compressor.Compress(Echoes(300, {150}));
  EXPECT_NEAR(profile->max_valid_range_m, 299 * g.bin_size_m, 1e-9);
  EXPECT_NEAR(LastRangeM(*profile), profile->max_valid_range_m, 1e-9);
  EXPECT_LT(profile->max_valid_range_m, g.max_range_m);
}

TEST(RangeCompressorTest, RangeOffsetBeyondMinRangeStartsTheTableAtSampleZero) {
  SensorGeometry g = Geometry();
  g.range_offset_m = 0.5;  // sample 0 already lies beyond min_range_m
  RangeCompressor compressor(PulseConfig{}, g, /*coherent=*/false, 1);
  const auto profile = compressor.Compress(Echoes(600, {200}));
  EXPECT_DOUBLE_EQ(profile->range_start_m, 0.5);
  EXPECT_NEAR(PeakRangeM(*profile), 0.5 + 200 * g.bin_size_m, 0.5 * g.bin_size_m);
}

TEST(RangeCompressorTest, LeadingSamplesAreZeroedBeforeCompression) {
  SensorGeometry g = Geometry();
  g.min_range_m = 0.0;  // the table starts at sample 0: a leading echo would show
  g.zero_leading_samples = 60;
  RangeCompressor compressor(PulseConfig{}, g, /*coherent=*/false, 1);
  std::vector<float> with_leakage = Echoes(600, {200});
  const std::vector<float> leakage = Echoes(600, {30}, 10.0f);
  for (int k = 0; k < 60; ++k) with_leakage[k] += leakage[k];
  const auto clean = compressor.Compress(Echoes(600, {200}));
  const auto leaky = compressor.Compress(with_leakage);
  EXPECT_EQ(leaky->real, clean->real);
  EXPECT_NEAR(PeakRangeM(*leaky), 200 * g.bin_size_m, 0.5 * g.bin_size_m);
}

TEST(RangeCompressorTest, AChangeOfScanLengthGivesTheSameProfileAsAFreshCompressor) {
  const SensorGeometry g = Geometry();
  RangeCompressor reused(PulseConfig{}, g, /*coherent=*/true, 4);
  reused.Compress(Echoes(600, {200}));
  const auto shorter = reused.Compress(Echoes(400, {250}));
  RangeCompressor fresh(PulseConfig{}, g, /*coherent=*/true, 4);
  const auto expected = fresh.Compress(Echoes(400, {250}));
  ASSERT_EQ(shorter->size(), expected->size());
  float peak = 0.0f, diff = 0.0f;
  for (std::size_t k = 0; k < expected->size(); ++k) {
    peak = std::max(peak, std::abs(expected->real[k]));
    diff = std::max(diff, std::abs(shorter->real[k] - expected->real[k]));
    diff = std::max(diff, std::abs(shorter->imag[k] - expected->imag[k]));
  }
  EXPECT_LE(diff, 1e-5f * peak);
  EXPECT_NEAR(PeakRangeM(*shorter), 250 * g.bin_size_m, shorter->range_step_m);
  EXPECT_NEAR(shorter->max_valid_range_m, (400 * 4 - 1) * shorter->range_step_m, 1e-9);
}

}  // namespace
}  // namespace uwbsar
