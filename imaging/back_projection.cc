#include "imaging/back_projection.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "imaging/zeroed_mat.h"

namespace uwbsar {
namespace {

struct LookupFrame {
  // Sensor position in the grid frame, in double: grids may sit far from their frame's
  // origin (world coordinates of 1e5 m have a float spacing of 8 mm), so each span's
  // offset from the sensor is formed in double and only the small difference is float.
  double sx, sy;
  float inv_step;     // 1 / range step
  float start_index;  // range_start / step
  int last_index;     // table size - 2 (the highest i with i + 1 valid)
};

// The inner loops are branch-free over a contiguous span so that the compiler
// can vectorise the range computation; the table read is a gather.
void AccumulateRealSpans(const RowSpan* begin, const RowSpan* end, const ImageGrid& grid,
                         const LookupFrame& f, const float* __restrict table, cv::Mat* image) {
  const float res = static_cast<float>(grid.resolution_m);
  for (const RowSpan* s = begin; s != end; ++s) {
    float* row = image->ptr<float>(s->row);
    const float dy = static_cast<float>(grid.RowToY(s->row) - f.sy);
    const float dy2 = dy * dy;
    const float dx0 = static_cast<float>(grid.ColToX(s->col_begin) - f.sx);
    const int n = s->col_end - s->col_begin;
    float* __restrict out = row + s->col_begin;
    for (int k = 0; k < n; ++k) {
      const float dx = dx0 + static_cast<float>(k) * res;
      const float pos = std::sqrt(dx * dx + dy2) * f.inv_step - f.start_index;
      const int i = std::min(std::max(static_cast<int>(pos), 0), f.last_index);
      const float frac = pos - static_cast<float>(i);
      out[k] += table[i] + frac * (table[i + 1] - table[i]);
    }
  }
}

void AccumulateComplexSpans(const RowSpan* begin, const RowSpan* end, const ImageGrid& grid,
                            const LookupFrame& f, const float* __restrict re,
                            const float* __restrict im, cv::Mat* image) {
  const float res = static_cast<float>(grid.resolution_m);
  for (const RowSpan* s = begin; s != end; ++s) {
    float* row = image->ptr<float>(s->row);
    const float dy = static_cast<float>(grid.RowToY(s->row) - f.sy);
    const float dy2 = dy * dy;
    const float dx0 = static_cast<float>(grid.ColToX(s->col_begin) - f.sx);
    const int n = s->col_end - s->col_begin;
    float* __restrict out = row + 2 * s->col_begin;
    for (int k = 0; k < n; ++k) {
      const float dx = dx0 + static_cast<float>(k) * res;
      const float pos = std::sqrt(dx * dx + dy2) * f.inv_step - f.start_index;
      const int i = std::min(std::max(static_cast<int>(pos), 0), f.last_index);
      const float frac = pos - static_cast<float>(i);
      out[2 * k] += re[i] + frac * (re[i + 1] - re[i]);
      out[2 * k + 1] += im[i] + frac * (im[i + 1] - im[i]);
    }
  }
}

}  // namespace

cv::Mat MakeSarImage(const ImageGrid& grid, bool coherent) {
  return ZeroedMat(grid.rows, grid.cols, coherent ? CV_32FC2 : CV_32FC1);
}

long long BackProjector::Accumulate(const RangeProfile& profile, const Pose2& T_grid_sensor,
                                    const SensorGeometry& geometry, const ImageGrid& grid,
                                    cv::Mat* image, cv::Rect* touched) {
  if (touched != nullptr) *touched = cv::Rect();
  assert(image->rows == grid.rows && image->cols == grid.cols);
  assert(image->type() == (profile.coherent() ? CV_32FC2 : CV_32FC1));
  if (profile.size() < 2) return 0;
  SectorShape sector{geometry.fov_half_angle_rad, geometry.min_range_m,
                     std::min(geometry.max_range_m, profile.max_valid_range_m)};
  if (sector.max_range_m <= sector.min_range_m) return 0;
  spans_.clear();
  const long long pixels = ComputeSectorSpans(grid, T_grid_sensor, sector, &spans_);
  if (spans_.empty()) return 0;
  if (touched != nullptr) *touched = SpansBounds(spans_);

  LookupFrame f;
  f.sx = T_grid_sensor.x_m;
  f.sy = T_grid_sensor.y_m;
  f.inv_step = static_cast<float>(1.0 / profile.range_step_m);
  f.start_index = static_cast<float>(profile.range_start_m / profile.range_step_m);
  f.last_index = static_cast<int>(profile.size()) - 2;

  auto run = [&](const RowSpan* b, const RowSpan* e) {
    if (profile.coherent()) {
      AccumulateComplexSpans(b, e, grid, f, profile.real.data(), profile.imag.data(), image);
    } else {
      AccumulateRealSpans(b, e, grid, f, profile.real.data(), image);
    }
  };
  if (stripes_ <= 1) {
    run(spans_.data(), spans_.data() + spans_.size());
    return pixels;
  }
  // Spans of one row never overlap, and each stripe owns whole spans, so threads
  // write disjoint pixels and the result does not depend on scheduling.
  const int n = static_cast<int>(spans_.size());
  cv::parallel_for_(
      cv::Range(0, stripes_),
      [&](const cv::Range& r) {
        for (int stripe = r.start; stripe < r.end; ++stripe) {
          const int b = static_cast<int>(static_cast<long long>(n) * stripe / stripes_);
          const int e = static_cast<int>(static_cast<long long>(n) * (stripe + 1) / stripes_);
          run(spans_.data() + b, spans_.data() + e);
        }
      },
      stripes_);
  return pixels;
}

}  // namespace uwbsar
