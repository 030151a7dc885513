#include "imaging/polar_kernels.h"

#include <algorithm>
#include <cmath>

namespace uwbsar {
namespace {

/// sin and cos of x (|x| < 1e4 rad) to about 1e-6, branch-free so that the loops calling it
/// vectorise: Cody-Waite reduction to [-pi/4, pi/4], Taylor polynomials, quadrant by selects.
inline void SinCos(float x, float* s, float* c) {
  const float q = std::nearbyint(x * 0.636619772f);
  float y = x - q * 1.5703125f;  // pi/2 split so that q * part is exact
  y -= q * 4.837512969970703125e-4f;
  y -= q * 7.54978995489188216e-8f;
  const float y2 = y * y;
  const float sp = y + y * y2 * (-1.6666667e-1f + y2 * (8.3333333e-3f + y2 * -1.9841270e-4f));
  const float cp =
      1.0f + y2 * (-0.5f + y2 * (4.1666667e-2f + y2 * (-1.3888889e-3f + y2 * 2.4801587e-5f)));
  const int m = static_cast<int>(q) & 3;
  const float odd = static_cast<float>(m & 1);  // selects by arithmetic, so that it vectorises
  const float ss = sp + odd * (cp - sp);
  const float cc = cp + odd * (sp - cp);
  *s = ss * (1.0f - static_cast<float>(m & 2));
  *c = cc * (1.0f - static_cast<float>((m + 1) & 2));
}

/// Where a sample falls in a polar image of rows x cols: the cell, bilinear weights and `keep`,
/// 1 inside and 0 outside (outside samples read the border and are multiplied by 0). Masks are
/// products of 0/1 floats, not bools: boolean logic stops GCC from vectorising these loops.
struct Cell {
  int index;     ///< row * cols + col of the top-left corner
  float wi, wj;  ///< weights along range (col) and angle (row)
  float keep;
};
inline float Step(bool condition) { return condition ? 1.0f : 0.0f; }
inline Cell Locate(float fj, float fi, int rows, int cols) {
  const float fi_max = static_cast<float>(cols - 1), fj_max = static_cast<float>(rows - 1);
  Cell c;
  const float fic = std::min(std::max(fi, 0.0f), fi_max);
  const float fjc = std::min(std::max(fj, 0.0f), fj_max);
  c.keep = Step(fic == fi) * Step(fjc == fj);
  const int i0 = std::min(static_cast<int>(fic), cols - 2);
  const int j0 = std::min(static_cast<int>(fjc), rows - 2);
  c.wi = fic - static_cast<float>(i0);
  c.wj = fjc - static_cast<float>(j0);
  c.index = j0 * cols + i0;
  return c;
}
inline float Bilinear(const float* __restrict p, int cols, const Cell& c) {
  const float top = p[c.index] + c.wi * (p[c.index + 1] - p[c.index]);
  const float bottom = p[c.index + cols] + c.wi * (p[c.index + cols + 1] - p[c.index + cols]);
  return top + c.wj * (bottom - top);
}

inline Cell LocateInPart(const PartRow& t, int i, float* r_out, float* rp_out, float* keep) {
  const float r = t.r0 + static_cast<float>(i) * t.dr;
  const float rp = std::sqrt(std::max(1e-12f, t.e2 + 2.0f * r * t.e_dir + r * r));
  const float psi = (t.e_a + r * t.dir_a) / rp;
  const Cell cell =
      Locate((psi - t.p_psi0) * t.p_inv_dpsi, (rp - t.p_r0) * t.p_inv_dr, t.rows, t.cols);
  *keep = cell.keep * Step(t.e_b + r * t.dir_b > 0.0f);
  *r_out = r;
  *rp_out = rp;
  return cell;
}

inline Cell LocatePixel(const SpanRow& t, int c, float* r_out, float* keep) {
  const float dx = t.dx0 + static_cast<float>(c) * t.res;
  const float r = std::sqrt(std::max(1e-12f, dx * dx + t.dy * t.dy));
  const float psi = (dx * t.ax + t.dy * t.ay) / r;
  const Cell cell = Locate((psi - t.psi0) * t.inv_dpsi, (r - t.r0) * t.inv_dr, t.rows, t.cols);
  *keep = cell.keep * Step(dx * t.bx + t.dy * t.by > 0.0f);
  *r_out = r;
  return cell;
}

/// The baseband image at pixel c brought back to the carrier: (re, im) times `keep`.
inline void PixelValue(const SpanRow& t, const float* __restrict in_re,
                       const float* __restrict in_im, int c, float* re, float* im) {
  float r, keep;
  const Cell cell = LocatePixel(t, c, &r, &keep);
  const float v = Bilinear(in_re, t.cols, cell), w = Bilinear(in_im, t.cols, cell);
  float sn, cs;
  SinCos(t.kc * r, &sn, &cs);  // back from baseband: times exp(j kc r)
  *re = keep * (v * cs - w * sn);
  *im = keep * (v * sn + w * cs);
}

}  // namespace

void AddComplexScaled(const float* __restrict re, const float* __restrict im, int n, float c_re,
                      float c_im, float* __restrict out_re, float* __restrict out_im) {
  for (int i = 0; i < n; ++i) {
    out_re[i] += c_re * re[i] - c_im * im[i];
    out_im[i] += c_re * im[i] + c_im * re[i];
  }
}

void AddPulseRow(PulseRow t, const float* __restrict table_re, const float* __restrict table_im,
                 int n, float* __restrict out_re, float* __restrict out_im) {
  // The same sector test as BackProjector's, at the polar samples.
  for (int i = 0; i < n; ++i) {
    const float r = t.r0 + static_cast<float>(i) * t.dr;
    const float range = std::sqrt(std::max(0.0f, t.e2 + 2.0f * r * t.e_dir + r * r));
    const float keep = Step(range >= t.min_r) * Step(range <= t.max_r) *
                       Step(t.e_b + r * t.dir_b >= range * t.cos_fov);
    const float pos = range * t.inv_step - t.start_index;
    const int k = std::min(std::max(static_cast<int>(pos), 0), t.last);
    const float frac = pos - static_cast<float>(k);
    out_re[i] += keep * (table_re[k] + frac * (table_re[k + 1] - table_re[k]));
    out_im[i] += keep * (table_im[k] + frac * (table_im[k + 1] - table_im[k]));
  }
}

void AddPartRowComplex(PartRow t, const float* __restrict in_re, const float* __restrict in_im,
                       int n, float* __restrict out_re, float* __restrict out_im) {
  for (int i = 0; i < n; ++i) {
    float r, rp, keep;
    const Cell cell = LocateInPart(t, i, &r, &rp, &keep);
    const float v = Bilinear(in_re, t.cols, cell), w = Bilinear(in_im, t.cols, cell);
    // From the part's baseband at rp to this grid's at r: times exp(j kc (rp - r)).
    float sn, cs;
    SinCos(t.kc * (rp - r), &sn, &cs);
    out_re[i] += keep * (v * cs - w * sn);
    out_im[i] += keep * (v * sn + w * cs);
  }
}

void ProjectSpanReal(SpanRow t, const float* __restrict in_re, const float* __restrict in_im, int n,
                     float* __restrict out) {
  for (int c = 0; c < n; ++c) {
    float re, im;
    PixelValue(t, in_re, in_im, c, &re, &im);
    out[c] += re;
  }
}

void ProjectSpanComplex(SpanRow t, const float* __restrict in_re, const float* __restrict in_im,
                        int n, float* __restrict out) {
  for (int c = 0; c < n; ++c) {
    float re, im;
    PixelValue(t, in_re, in_im, c, &re, &im);
    out[2 * c] += re;
    out[2 * c + 1] += im;
  }
}

}  // namespace uwbsar
