#include "imaging/tap_table.h"

#include <algorithm>
#include <cmath>

#include "imaging/polar_kernels.h"

namespace uwbsar {

void MakeTapTable(const RangeProfile& profile, const std::vector<float>& imag, double bin_size_m,
                  double kc, double min_range_m, double max_range_m, TapTable* table) {
  constexpr int kTaps = TapTable::kTaps;
  const double entry_m = profile.range_step_m;
  // Grid entries per profile entry: kTaps per bin, at least one and at most kTaps per entry
  // (profiles coarser than a bin, as some tests make, are tabulated at a quarter entry).
  const double per_entry = bin_size_m > 0.0 ? kTaps * entry_m / bin_size_m : kTaps;
  const int phases = std::min(kTaps, std::max(1, static_cast<int>(std::ceil(per_entry - 1e-9))));
  const double step_m = entry_m / phases;
  double offset_m[kTaps], w_re[kTaps], w_im[kTaps];  // o_m and exp(-j kc o_m) / kTaps
  for (int m = 0; m < kTaps; ++m) {
    offset_m[m] = bin_size_m * ((m + 0.5) / kTaps - 0.5);
    w_re[m] = std::cos(-kc * offset_m[m]) / kTaps;
    w_im[m] = std::sin(-kc * offset_m[m]) / kTaps;
  }
  const double knot0_m = profile.range_start_m - offset_m[0];
  const double x0_m = knot0_m + step_m * std::floor((min_range_m - step_m - knot0_m) / step_m);
  const int count = static_cast<int>(std::ceil((max_range_m + step_m - x0_m) / step_m)) + 1;
  const int per_phase = (count + phases - 1) / phases;

  // Entry phases * i + p is sum over taps m of w_m L(u_pm + i), u_pm = the profile index of
  // entry p plus o_m: a filter of the profile with fixed weights per phase.
  double u[kTaps][kTaps];
  int lo = 1 << 30, hi = -(1 << 30);
  for (int p = 0; p < phases; ++p) {
    for (int m = 0; m < kTaps; ++m) {
      u[p][m] = (x0_m + p * step_m + offset_m[m] - profile.range_start_m) / entry_m;
      lo = std::min(lo, static_cast<int>(std::floor(u[p][m])));
      hi = std::max(hi, static_cast<int>(std::floor(u[p][m])) + 1);
    }
  }
  const int width = hi - lo + 1;  // profile entries one table entry reads
  std::vector<float> c_re(static_cast<std::size_t>(width)), c_im(c_re.size());
  // The profile extended by its end values, from index lo, as far as the filter reads.
  const int n = static_cast<int>(profile.size());
  const int padded = per_phase + width - 1;
  std::vector<float> pad_re(static_cast<std::size_t>(padded)), pad_im(pad_re.size());
  for (int t = 0; t < padded; ++t) {
    const int k = std::min(std::max(lo + t, 0), n - 1);
    pad_re[static_cast<std::size_t>(t)] = profile.real[static_cast<std::size_t>(k)];
    pad_im[static_cast<std::size_t>(t)] = imag[static_cast<std::size_t>(k)];
  }
  table->x0_m = x0_m;
  table->step_m = step_m;
  table->re.assign(static_cast<std::size_t>(per_phase) * phases, 0.0f);
  table->im.assign(table->re.size(), 0.0f);
  std::vector<float> phase_re(static_cast<std::size_t>(per_phase)), phase_im(phase_re.size());
  for (int p = 0; p < phases; ++p) {
    std::fill(c_re.begin(), c_re.end(), 0.0f);
    std::fill(c_im.begin(), c_im.end(), 0.0f);
    for (int m = 0; m < kTaps; ++m) {
      const int a = static_cast<int>(std::floor(u[p][m]));
      const double f = u[p][m] - a;
      const std::size_t j = static_cast<std::size_t>(a - lo);
      c_re[j] += static_cast<float>(w_re[m] * (1.0 - f));
      c_im[j] += static_cast<float>(w_im[m] * (1.0 - f));
      c_re[j + 1] += static_cast<float>(w_re[m] * f);
      c_im[j + 1] += static_cast<float>(w_im[m] * f);
    }
    std::fill(phase_re.begin(), phase_re.end(), 0.0f);
    std::fill(phase_im.begin(), phase_im.end(), 0.0f);
    for (int j = 0; j < width; ++j) {
      AddComplexScaled(pad_re.data() + j, pad_im.data() + j, per_phase, c_re[j], c_im[j],
                       phase_re.data(), phase_im.data());
    }
    for (int i = 0; i < per_phase; ++i) {
      table->re[static_cast<std::size_t>(i) * phases + p] = phase_re[i];
      table->im[static_cast<std::size_t>(i) * phases + p] = phase_im[i];
    }
  }
  table->re.resize(static_cast<std::size_t>(count));
  table->im.resize(static_cast<std::size_t>(count));
}

}  // namespace uwbsar
