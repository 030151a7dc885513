// The inner loops of imaging/polar_subaperture.h: forming a polar image from scans, merging
// polar images, projecting one onto pixels. Each takes plain values and restrict pointers and is
// compiled in its own file (-march=native), out of line: inlined into the callers' lambdas, GCC
// loses the restrict qualifiers and no longer vectorises them (the bilinear gathers may alias
// the output). The loops are branch-free: masks are products of 0/1 floats.
#pragma once

namespace uwbsar {

/// out += (c_re + j c_im) (re + j im), over n values.
void AddComplexScaled(const float* __restrict re, const float* __restrict im, int n, float c_re,
                      float c_im, float* __restrict out_re, float* __restrict out_im);

/// One scan's contribution along a polar row: sample i lies at e + r dir from the antenna.
struct PulseRow {
  float r0, dr, e_dir, e2, e_b, dir_b, min_r, max_r, cos_fov, inv_step, start_index;
  int last;  ///< table size - 2
};
/// Adds one scan's complex table (planar), linearly interpolated at each sample's range,
/// where its sector holds the sample (the same sector test as BackProjector's).
void AddPulseRow(PulseRow t, const float* __restrict table_re, const float* __restrict table_im,
                 int n, float* __restrict out_re, float* __restrict out_im);

/// A part's image sampled along a row of the merged grid: sample i lies at e + r dir from the
/// part's centre, i.e. at range rp and psi (e_a + r dir_a) / rp of the part.
struct PartRow {
  float r0, dr, e_dir, e2, e_a, e_b, dir_a, dir_b, p_r0, p_inv_dr, p_psi0, p_inv_dpsi, kc;
  int rows, cols;  ///< of the part
};
/// Adds the part's baseband image, bilinearly interpolated and moved to this grid's baseband
/// (times exp(j kc (rp - r))).
void AddPartRowComplex(PartRow t, const float* __restrict in_re, const float* __restrict in_im,
                       int n, float* __restrict out_re, float* __restrict out_im);

/// The polar image sampled along a row span of pixels: pixel c lies at (dx0 + c res, dy) from
/// the centre.
struct SpanRow {
  float dx0, dy, res, ax, ay, bx, by, r0, inv_dr, psi0, inv_dpsi, kc;
  int rows, cols;  ///< of the polar image
};
/// Adds the real part of the image at the carrier (paper mode) to a CV_32FC1 row.
void ProjectSpanReal(SpanRow t, const float* __restrict in_re, const float* __restrict in_im, int n,
                     float* __restrict out);
/// Adds the image at the carrier to an interleaved CV_32FC2 row (coherent mode).
void ProjectSpanComplex(SpanRow t, const float* __restrict in_re, const float* __restrict in_im,
                        int n, float* __restrict out);

}  // namespace uwbsar
