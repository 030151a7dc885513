// One scan's range profile as the base polar images of fast factorised back-projection read it
// (imaging/polar_subaperture.h): the mean of kTaps samples spread over one range bin, at
// baseband. Linear interpolation of a profile leaves artefacts periodic in its bin, which a
// polar grid as coarse as the base's would fold into the baseband; the mean over a bin cancels
// them (and is flat over the baseband).
//
// A tap's offset along a polar sample's range is its offset along the scan's range to well under
// a micrometre (the antennas of a base lie within centimetres of its centre, the samples
// decimetres away), so the taps' sum at baseband is, per scan, one function of the scan's range:
//   G(rho) = sum_m L(rho + o_m) exp(-j kc o_m) / kTaps,  o_m = bin (2m + 1 - kTaps) / (2 kTaps),
// L the profile (analytic: real + j imag or quadrature) linearly interpolated, extended by its
// end values. The sample at polar range r receives exp(-j kc r) G(rho).
//
// G is piecewise linear with knots at the profile's entries less o_m. When the bin is q entries
// (q = 1 in paper mode, 4 in coherent), they all lie on the grid from range_start - o_0 in steps
// of min(entry, bin / kTaps), which the table samples: linearly interpolated, it is exact. Its
// entries are a short filter of the profile's, one per phase of the grid within an entry.
#pragma once

#include <vector>

#include "imaging/range_profile.h"

namespace uwbsar {

struct TapTable {
  static constexpr int kTaps = 4;
  double x0_m = 0.0;    ///< range of entry 0
  double step_m = 0.0;  ///< range between entries
  std::vector<float> re, im;
};

/// G of `profile` (with `imag`: its imag or quadrature) on the grid above, covering
/// [min_range_m, max_range_m] with an entry to spare at each end. kc = 4 pi fc / c.
void MakeTapTable(const RangeProfile& profile, const std::vector<float>& imag, double bin_size_m,
                  double kc, double min_range_m, double max_range_m, TapTable* table);

}  // namespace uwbsar
