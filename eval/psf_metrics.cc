#include "eval/psf_metrics.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace uwbsar {
namespace {

double Bilinear(const cv::Mat& img, double col, double row) {
  const int c0 = static_cast<int>(std::floor(col)), r0 = static_cast<int>(std::floor(row));
  if (c0 < 0 || r0 < 0 || c0 + 1 >= img.cols || r0 + 1 >= img.rows) return 0.0;
  const double fc = col - c0, fr = row - r0;
  const float* a = img.ptr<float>(r0);
  const float* b = img.ptr<float>(r0 + 1);
  return (1 - fr) * ((1 - fc) * a[c0] + fc * a[c0 + 1]) + fr * ((1 - fc) * b[c0] + fc * b[c0 + 1]);
}

/// Offset of the vertex of the parabola through (-1, a), (0, b), (1, c).
double ParabolicOffset(double a, double b, double c) {
  const double d = a - 2 * b + c;
  return std::abs(d) < 1e-20 ? 0.0 : std::clamp(0.5 * (a - c) / d, -0.5, 0.5);
}

struct CutResult {
  double width_m = 0.0;
  double max_sidelobe = 0.0;
};

CutResult AnalyseCut(const cv::Mat& img, const ImageGrid& grid, const Point2& peak,
                     const Point2& dir, double half_length_m) {
  const double step = grid.resolution_m / 8.0;
  const int n = static_cast<int>(half_length_m / step);
  std::vector<double> v(2 * n + 1);
  for (int i = -n; i <= n; ++i) {
    const double x = peak.x_m + i * step * dir.x_m, y = peak.y_m + i * step * dir.y_m;
    v[i + n] = Bilinear(img, grid.XToCol(x), grid.YToRow(y));
  }
  const double peak_value = v[n];
  const double half_power = peak_value / std::sqrt(2.0);
  CutResult result;
  double edges[2] = {0.0, 0.0};
  for (int side = 0; side < 2; ++side) {
    const int dirn = side == 0 ? -1 : 1;
    int i = n;
    while (i + dirn >= 0 && i + dirn <= 2 * n && v[i + dirn] >= half_power) i += dirn;
    const int j = i + dirn;
    if (j < 0 || j > 2 * n) {
      edges[side] = half_length_m;
    } else {
      const double t = (v[i] - half_power) / std::max(v[i] - v[j], 1e-30);
      edges[side] = (std::abs(i - n) + t) * step;
    }
    // The main lobe runs past the half-power point down to the first null (local
    // minimum); everything beyond it on the cut is sidelobe. Ripples above half
    // power are part of the main lobe, not sidelobes.
    int k = i;
    while (k + dirn >= 0 && k + dirn <= 2 * n && v[k + dirn] <= v[k]) k += dirn;
    for (int m = k + dirn; m >= 0 && m <= 2 * n; m += dirn) {
      result.max_sidelobe = std::max(result.max_sidelobe, v[m]);
    }
  }
  result.width_m = edges[0] + edges[1];
  return result;
}

}  // namespace

PsfMetrics MeasurePsf(const cv::Mat& detected, const ImageGrid& grid, const Point2& truth,
                      const Point2& range_direction, double search_radius_m,
                      double cut_half_length_m) {
  CV_Assert(detected.type() == CV_32FC1);
  PsfMetrics m;
  const int r = static_cast<int>(std::ceil(search_radius_m / grid.resolution_m));
  const int c0 = static_cast<int>(std::lround(grid.XToCol(truth.x_m)));
  const int r0 = static_cast<int>(std::lround(grid.YToRow(truth.y_m)));
  int best_c = -1, best_r = -1;
  float best = -1.0f;
  for (int row = std::max(1, r0 - r); row <= std::min(detected.rows - 2, r0 + r); ++row) {
    for (int col = std::max(1, c0 - r); col <= std::min(detected.cols - 2, c0 + r); ++col) {
      const float v = detected.at<float>(row, col);
      if (v > best) {
        best = v;
        best_c = col;
        best_r = row;
      }
    }
  }
  if (best_c < 0 || best <= 0.0f) return m;
  const double dc = ParabolicOffset(detected.at<float>(best_r, best_c - 1), best,
                                    detected.at<float>(best_r, best_c + 1));
  const double dr = ParabolicOffset(detected.at<float>(best_r - 1, best_c), best,
                                    detected.at<float>(best_r + 1, best_c));
  m.found = true;
  m.peak = grid.PixelToMetric(best_c + dc, best_r + dr);
  m.peak_value = best;
  m.position_error_m = std::hypot(m.peak.x_m - truth.x_m, m.peak.y_m - truth.y_m);
  const double norm = std::hypot(range_direction.x_m, range_direction.y_m);
  const Point2 range_dir{range_direction.x_m / norm, range_direction.y_m / norm};
  const Point2 cross_dir{-range_dir.y_m, range_dir.x_m};
  const CutResult range = AnalyseCut(detected, grid, m.peak, range_dir, cut_half_length_m);
  const CutResult cross = AnalyseCut(detected, grid, m.peak, cross_dir, cut_half_length_m);
  m.range_width_m = range.width_m;
  m.cross_range_width_m = cross.width_m;
  const double peak_cut = Bilinear(detected, grid.XToCol(m.peak.x_m), grid.YToRow(m.peak.y_m));
  const double sidelobe = std::max(range.max_sidelobe, cross.max_sidelobe);
  m.pslr_db = sidelobe > 0.0 && peak_cut > 0.0 ? 20.0 * std::log10(sidelobe / peak_cut) : -99.0;
  m.pslr_db = std::max(m.pslr_db, -99.0);
  return m;
}

}  // namespace uwbsar
