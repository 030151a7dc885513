#include "imaging/polar_subaperture.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "imaging/polar_kernels.h"
#include "imaging/tap_table.h"

namespace uwbsar {
namespace {

/// Sectors seen from the centre must stay within this angle of the mean boresight: beyond it,
/// psi = sin(angle) samples the image too unevenly (and at 90 deg not at all).
constexpr double kMaxAngleFromBoresightRad = 80.0 * M_PI / 180.0;

/// The farthest range a scan images (its sector, cut where the profile's samples end).
double MaxRangeM(const SubaperturePulse& p, const SensorGeometry& g) {
  return std::min(g.max_range_m, p.profile->max_valid_range_m);
}

/// Runs body(begin, end) over [0, n) in `threads` stripes (each index once; disjoint outputs).
template <typename Body>
void ForStripes(int n, int threads, const Body& body) {
  if (threads <= 1 || n < 2) {
    body(0, n);
    return;
  }
  cv::parallel_for_(
      cv::Range(0, threads),
      [&](const cv::Range& r) {
        for (int s = r.start; s < r.end; ++s) {
          body(static_cast<int>(static_cast<long long>(n) * s / threads),
               static_cast<int>(static_cast<long long>(n) * (s + 1) / threads));
        }
      },
      threads);
}

}  // namespace

bool PolarSubaperture::PlanGrid(const SensorGeometry& g, const PolarSampling& sampling,
                                std::vector<std::pair<double, double>>* boresights_out) {
  const double n = static_cast<double>(pulses_.size());
  double sx = 0.0, sy = 0.0, sc = 0.0, ss = 0.0;
  std::vector<std::pair<double, double>> boresights;  // cos, sin of each scan's yaw
  boresights.reserve(pulses_.size());
  for (const SubaperturePulse& p : pulses_) {
    sx += p.T_grid_sensor.x_m;
    sy += p.T_grid_sensor.y_m;
    boresights.emplace_back(std::cos(p.T_grid_sensor.yaw_rad), std::sin(p.T_grid_sensor.yaw_rad));
    sc += boresights.back().first;
    ss += boresights.back().second;
  }
  const double norm = std::hypot(sc, ss);
  if (pulses_.empty() || norm < 1e-6 * n) return false;
  cx_m_ = sx / n;
  cy_m_ = sy / n;
  bx_ = sc / norm;
  by_ = ss / norm;
  ax_ = by_;
  ay_ = -bx_;

  // Angular extent of the sectors seen from C, from points along their boundaries (the extreme
  // directions to a region lie on its boundary), and the farthest antenna from C. Boundary
  // directions relative to the boresight, once: t in [0, 1] across the sector.
  constexpr int kSteps = 8;
  double across_cos[kSteps + 1], across_sin[kSteps + 1];
  for (int i = 0; i <= kSteps; ++i) {
    const double angle = g.fov_half_angle_rad * (2.0 * i / kSteps - 1.0);
    across_cos[i] = std::cos(angle);
    across_sin[i] = std::sin(angle);
  }
  const double cos_limit = std::cos(kMaxAngleFromBoresightRad);
  double sin_lo = 1.0, sin_hi = -1.0, max_offset_m = 0.0, max_range_m = 0.0;
  for (std::size_t k = 0; k < pulses_.size(); ++k) {
    const SubaperturePulse& p = pulses_[k];
    const double ux = p.T_grid_sensor.x_m - cx_m_, uy = p.T_grid_sensor.y_m - cy_m_;
    max_offset_m = std::max(max_offset_m, std::sqrt(ux * ux + uy * uy));
    const double r_max = MaxRangeM(p, g);
    if (r_max <= g.min_range_m) continue;  // images nothing (direct gives 0 too)
    max_range_m = std::max(max_range_m, r_max);
    const double c = boresights[k].first, sn = boresights[k].second;
    // The point at range_m along the relative direction (ca, sa) of this scan's sector.
    auto visit = [&](double range_m, double ca, double sa) {
      const double dx = ux + range_m * (c * ca - sn * sa);
      const double dy = uy + range_m * (sn * ca + c * sa);
      const double r = std::sqrt(dx * dx + dy * dy);
      if (dx * bx_ + dy * by_ <= cos_limit * r) return false;
      const double s = (dx * ax_ + dy * ay_) / r;
      sin_lo = std::min(sin_lo, s);
      sin_hi = std::max(sin_hi, s);
      return true;
    };
    for (int i = 0; i <= kSteps; ++i) {
      const double range = g.min_range_m + (r_max - g.min_range_m) * i / kSteps;
      if (!visit(g.min_range_m, across_cos[i], across_sin[i]) ||
          !visit(r_max, across_cos[i], across_sin[i]) ||
          !visit(range, across_cos[0], across_sin[0]) ||
          !visit(range, across_cos[kSteps], across_sin[kSteps])) {
        return false;
      }
    }
  }
  if (max_range_m <= 0.0) return false;

  // psi step: a scan at offset u from C sees sample (r, psi) at delay r - u . dir(psi), and
  // d(u . dir)/dpsi = u.a - u.b tan(angle): one two-way fringe per lambda / (2 H) of psi.
  const double max_sin = std::max(std::abs(sin_lo), std::abs(sin_hi));
  const double max_tan = max_sin / std::sqrt(std::max(1e-12, 1.0 - max_sin * max_sin));
  double extent_m = 0.0;
  for (const SubaperturePulse& p : pulses_) {
    const double ux = p.T_grid_sensor.x_m - cx_m_, uy = p.T_grid_sensor.y_m - cy_m_;
    extent_m =
        std::max(extent_m, std::abs(ux * ax_ + uy * ay_) + std::abs(ux * bx_ + uy * by_) * max_tan);
  }
  // At least kMinSectorRows rows across the sectors, whose edges the samples resolve: a short
  // sub-aperture (one scan) has few fringes, but its image still ends at the sector's edges.
  constexpr double kMinSectorRows = 8.0;
  const double step = std::min(
      sampling.min_wavelength_m / (2.0 * std::max(extent_m, 1e-6) * sampling.angular_oversampling),
      (sin_hi - sin_lo) / kMinSectorRows);
  const double margin = std::min(step, 0.05);  // samples just outside, for interpolation
  psi0_ = std::max(-1.0, sin_lo - margin);
  const double psi1 = std::min(1.0, sin_hi + margin);
  angle_samples_ = std::max(2, static_cast<int>(std::ceil((psi1 - psi0_) / step)) + 1);
  psi_step_ = (psi1 - psi0_) / (angle_samples_ - 1);

  range_step_m_ = sampling.range_step_m;
  range0_m_ = std::max(0.0, g.min_range_m - max_offset_m - range_step_m_);
  const double range1_m = max_range_m + max_offset_m + range_step_m_;
  range_samples_ = std::max(2, static_cast<int>(std::ceil((range1_m - range0_m_) / range_step_m_)));
  if (boresights_out != nullptr) *boresights_out = std::move(boresights);
  return true;
}

void PolarSubaperture::RowDirection(int j, double* dx, double* dy) const {
  const double psi = psi0_ + j * psi_step_;
  const double c = std::sqrt(std::max(0.0, 1.0 - psi * psi));
  *dx = psi * ax_ + c * bx_;
  *dy = psi * ay_ + c * by_;
}

std::optional<PolarSubaperture> PolarSubaperture::FromPulses(std::vector<SubaperturePulse> pulses,
                                                             const SensorGeometry& g,
                                                             const PolarSampling& sampling,
                                                             int threads) {
  PolarSubaperture s;
  s.pulses_ = std::move(pulses);
  s.coherent_ = sampling.coherent;
  s.kc_ = sampling.carrier_wavenumber_rad_per_m;
  std::vector<std::pair<double, double>> boresights;  // cos, sin of each scan's yaw
  if (!s.PlanGrid(g, sampling, &boresights)) return std::nullopt;
  const int nr = s.range_samples_;
  const std::size_t size = static_cast<std::size_t>(s.angle_samples_) * nr;
  s.re_.assign(size, 0.0f);
  s.im_.assign(size, 0.0f);
  const float cos_fov = static_cast<float>(std::cos(g.fov_half_angle_rad));
  const float min_r = static_cast<float>(g.min_range_m);
  const float dr = static_cast<float>(s.range_step_m_);
  // Each sample holds, per scan, the mean of a few taps over one range bin, at baseband: the
  // scan's TapTable G (imaging/tap_table.h) at the sample's range from the scan's antenna,
  // times exp(-j kc r), which is applied once per row.
  std::vector<float> to_base_re(static_cast<std::size_t>(nr)), to_base_im(to_base_re.size());
  for (int i = 0; i < nr; ++i) {
    const double phase = -s.kc_ * (s.range0_m_ + i * s.range_step_m_);
    to_base_re[static_cast<std::size_t>(i)] = static_cast<float>(std::cos(phase));
    to_base_im[static_cast<std::size_t>(i)] = static_cast<float>(std::sin(phase));
  }
  // Per scan: its G table and the row parameters that do not depend on the row.
  struct ScanTable {
    TapTable g;
    PulseRow row{};
    double ex = 0.0, ey = 0.0, bx = 0.0, by = 0.0;
  };
  std::vector<ScanTable> tables(s.pulses_.size());
  ForStripes(static_cast<int>(s.pulses_.size()), threads, [&](int k_begin, int k_end) {
    for (int k = k_begin; k < k_end; ++k) {
      const SubaperturePulse& p = s.pulses_[static_cast<std::size_t>(k)];
      const RangeProfile& prof = *p.profile;
      const double max_r = MaxRangeM(p, g);
      if (max_r <= g.min_range_m || prof.size() < 2) continue;
      ScanTable& st = tables[static_cast<std::size_t>(k)];
      MakeTapTable(prof, s.coherent_ ? prof.imag : prof.quadrature, g.bin_size_m, s.kc_,
                   g.min_range_m, max_r, &st.g);
      // Sample (r) relative to this scan's antenna: e + r dir, e = C - U.
      st.ex = s.cx_m_ - p.T_grid_sensor.x_m;
      st.ey = s.cy_m_ - p.T_grid_sensor.y_m;
      st.bx = boresights[static_cast<std::size_t>(k)].first;
      st.by = boresights[static_cast<std::size_t>(k)].second;
      PulseRow& t = st.row;
      t.r0 = static_cast<float>(s.range0_m_);
      t.dr = dr;
      t.e2 = static_cast<float>(st.ex * st.ex + st.ey * st.ey);
      t.e_b = static_cast<float>(st.ex * st.bx + st.ey * st.by);
      t.min_r = min_r;
      t.max_r = static_cast<float>(max_r);
      t.cos_fov = cos_fov;
      t.inv_step = static_cast<float>(1.0 / st.g.step_m);
      t.start_index = static_cast<float>(st.g.x0_m / st.g.step_m);
      t.last = static_cast<int>(st.g.re.size()) - 2;
    }
  });

  ForStripes(s.angle_samples_, threads, [&](int j_begin, int j_end) {
    for (int j = j_begin; j < j_end; ++j) {
      double dir_x, dir_y;
      s.RowDirection(j, &dir_x, &dir_y);
      float* __restrict out_re = s.re_.data() + static_cast<std::size_t>(j) * nr;
      float* __restrict out_im = s.im_.data() + static_cast<std::size_t>(j) * nr;
      for (const ScanTable& st : tables) {
        if (st.g.re.empty()) continue;
        PulseRow t = st.row;
        t.e_dir = static_cast<float>(st.ex * dir_x + st.ey * dir_y);
        t.dir_b = static_cast<float>(dir_x * st.bx + dir_y * st.by);
        AddPulseRow(t, st.g.re.data(), st.g.im.data(), nr, out_re, out_im);
      }
      for (int i = 0; i < nr; ++i) {
        const float v = out_re[i], w = out_im[i];
        out_re[i] = v * to_base_re[i] - w * to_base_im[i];
        out_im[i] = v * to_base_im[i] + w * to_base_re[i];
      }
    }
  });
  return s;
}

std::optional<PolarSubaperture> PolarSubaperture::Merge(
    const std::vector<const PolarSubaperture*>& parts, const SensorGeometry& g,
    const PolarSampling& sampling, int threads) {
  PolarSubaperture s;
  for (const PolarSubaperture* part : parts) {
    s.pulses_.insert(s.pulses_.end(), part->pulses_.begin(), part->pulses_.end());
  }
  s.coherent_ = sampling.coherent;
  s.kc_ = sampling.carrier_wavenumber_rad_per_m;
  if (!s.PlanGrid(g, sampling)) return std::nullopt;
  const int nr = s.range_samples_;
  const std::size_t size = static_cast<std::size_t>(s.angle_samples_) * nr;
  s.re_.assign(size, 0.0f);
  s.im_.assign(size, 0.0f);
  const float r0 = static_cast<float>(s.range0_m_), dr = static_cast<float>(s.range_step_m_);
  const float kc = static_cast<float>(s.kc_);

  ForStripes(s.angle_samples_, threads, [&](int j_begin, int j_end) {
    for (int j = j_begin; j < j_end; ++j) {
      double dir_x, dir_y;
      s.RowDirection(j, &dir_x, &dir_y);
      float* __restrict out_re = s.re_.data() + static_cast<std::size_t>(j) * nr;
      float* __restrict out_im = s.im_.data() + static_cast<std::size_t>(j) * nr;
      for (const PolarSubaperture* part : parts) {
        const PolarSubaperture& p = *part;
        // This row's samples relative to the part's centre: e + r dir, e = C - C_part.
        const double ex = s.cx_m_ - p.cx_m_, ey = s.cy_m_ - p.cy_m_;
        PartRow t;
        t.r0 = r0;
        t.dr = dr;
        t.e_dir = static_cast<float>(ex * dir_x + ey * dir_y);
        t.e2 = static_cast<float>(ex * ex + ey * ey);
        t.e_a = static_cast<float>(ex * p.ax_ + ey * p.ay_);
        t.e_b = static_cast<float>(ex * p.bx_ + ey * p.by_);
        t.dir_a = static_cast<float>(dir_x * p.ax_ + dir_y * p.ay_);
        t.dir_b = static_cast<float>(dir_x * p.bx_ + dir_y * p.by_);
        t.p_r0 = static_cast<float>(p.range0_m_);
        t.p_inv_dr = static_cast<float>(1.0 / p.range_step_m_);
        t.p_psi0 = static_cast<float>(p.psi0_);
        t.p_inv_dpsi = static_cast<float>(1.0 / p.psi_step_);
        t.kc = kc;
        t.rows = p.angle_samples_;
        t.cols = p.range_samples_;
        AddPartRowComplex(t, p.re_.data(), p.im_.data(), nr, out_re, out_im);
      }
    }
  });
  return s;
}

long long PolarSubaperture::ProjectInto(const ImageGrid& grid, const std::vector<RowSpan>& spans,
                                        cv::Mat* image, int threads) const {
  long long pixels = 0;
  for (const RowSpan& sp : spans) pixels += sp.col_end - sp.col_begin;
  SpanRow base;
  base.res = static_cast<float>(grid.resolution_m);
  base.ax = static_cast<float>(ax_);
  base.ay = static_cast<float>(ay_);
  base.bx = static_cast<float>(bx_);
  base.by = static_cast<float>(by_);
  base.r0 = static_cast<float>(range0_m_);
  base.inv_dr = static_cast<float>(1.0 / range_step_m_);
  base.psi0 = static_cast<float>(psi0_);
  base.inv_dpsi = static_cast<float>(1.0 / psi_step_);
  base.kc = static_cast<float>(kc_);
  base.rows = angle_samples_;
  base.cols = range_samples_;
  ForStripes(static_cast<int>(spans.size()), threads, [&](int b, int e) {
    for (int k = b; k < e; ++k) {
      const RowSpan& sp = spans[static_cast<std::size_t>(k)];
      SpanRow t = base;
      // Offsets from C in double first: the grid may sit far from its frame's origin.
      t.dy = static_cast<float>(grid.RowToY(sp.row) - cy_m_);
      t.dx0 = static_cast<float>(grid.ColToX(sp.col_begin) - cx_m_);
      float* out = image->ptr<float>(sp.row);
      if (coherent_) {
        ProjectSpanComplex(t, re_.data(), im_.data(), sp.col_end - sp.col_begin,
                           out + 2 * static_cast<std::size_t>(sp.col_begin));
      } else {
        ProjectSpanReal(t, re_.data(), im_.data(), sp.col_end - sp.col_begin, out + sp.col_begin);
      }
    }
  });
  return pixels;
}

}  // namespace uwbsar
