#include "frontend/wall_profile.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "frontend/profile_bins.h"

namespace uwbsar {
namespace {

/// Normalised cross-correlation of a[q + shift] with b[q] over the bins both cover.
double Correlation(const std::vector<float>& a, const std::vector<float>& b, int shift) {
  const int n = static_cast<int>(a.size());
  const int begin = std::max(0, -shift), end = std::min(n, n - shift);
  if (end - begin < 10) return -1.0;
  double mean_a = 0.0, mean_b = 0.0;
  for (int q = begin; q < end; ++q) mean_a += a[q + shift], mean_b += b[q];
  mean_a /= end - begin;
  mean_b /= end - begin;
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (int q = begin; q < end; ++q) {
    const double x = a[q + shift] - mean_a, y = b[q] - mean_b;
    ab += x * y;
    aa += x * x;
    bb += y * y;
  }
  return aa > 0.0 && bb > 0.0 ? ab / std::sqrt(aa * bb) : -1.0;
}

}  // namespace

WallProfile ComputeWallProfile(const cv::Mat& detected, const ImageGrid& grid, double heading_rad,
                               const WallProfileConfig& config) {
  if (detected.type() != CV_32FC1 || detected.rows != grid.rows || detected.cols != grid.cols) {
    throw std::invalid_argument("ComputeWallProfile: a CV_32FC1 image of the grid's size");
  }
  WallProfile p;
  p.heading_rad = heading_rad;
  p.bin_m = config.bin_m;
  const int num_bins = 2 * static_cast<int>(std::lround(config.half_width_m / config.bin_m));
  p.bins.assign(static_cast<std::size_t>(num_bins), 0.0f);
  // Offset of pixel (c, r) along the path's left normal; its footprint starts half a footprint
  // lower, which lies (that - first_edge_m) / bin_m bins from the profile's first bin edge.
  const GridProjection across(grid, -std::sin(heading_rad), std::cos(heading_rad));
  const double first_edge_m = -p.half_width_m() + 0.5 * across.footprint_m;
  const double width_bins = across.footprint_m / config.bin_m;
  for (int r = 0; r < detected.rows; ++r) {
    const float* row = detected.ptr<float>(r);
    const double s_row = across.AtRow(r) - first_edge_m;
    for (int c = 0; c < detected.cols; ++c) {
      if (!(row[c] > 0.0f)) continue;
      SpreadOverBins((s_row + across.per_col_m * c) / config.bin_m, width_bins, row[c],
                     p.bins.data(), num_bins);
    }
  }
  // The floor: the median of the bins the tile imaged. It is the same wherever a tile is (the
  // imaged band's edges, sidelobes), so it is removed; walls stand out of it by their contrast.
  std::vector<float> imaged;
  for (const float v : p.bins) {
    if (v > 0.0f) imaged.push_back(v);
  }
  if (imaged.empty()) return p;
  std::nth_element(imaged.begin(), imaged.begin() + imaged.size() / 2, imaged.end());
  const float floor = imaged[imaged.size() / 2];
  p.floor = floor;
  float peak = 0.0f;
  for (float& v : p.bins) {
    peak = std::max(peak, v);
    v = std::max(0.0f, v - floor);
  }
  p.contrast = floor > 0.0f ? peak / floor : 0.0;
  return p;
}

namespace {

/// The best shift of b against a within +-reach bins of `centre` (bins): its correlation, the
/// shift refined below a bin by a parabola, and whether the peak lies on the searched range's
/// edge.
struct Shift {
  double correlation = -1.0;
  double bins = 0.0;
  bool on_edge = false;
};

Shift BestShift(const std::vector<float>& a, const std::vector<float>& b, int centre, int reach) {
  std::vector<double> score(static_cast<std::size_t>(2 * reach + 1));
  int best = -1;
  for (int k = 0; k <= 2 * reach; ++k) {
    score[static_cast<std::size_t>(k)] = Correlation(a, b, centre - reach + k);
    if (best < 0 || score[static_cast<std::size_t>(k)] > score[static_cast<std::size_t>(best)]) {
      best = k;
    }
  }
  Shift s;
  s.correlation = score[static_cast<std::size_t>(best)];
  double refined = best;
  if (best > 0 && best < 2 * reach) {  // parabola through the peak and its neighbours
    const double l = score[static_cast<std::size_t>(best - 1)];
    const double m = score[static_cast<std::size_t>(best)];
    const double r = score[static_cast<std::size_t>(best + 1)];
    const double curvature = l - 2.0 * m + r;
    if (curvature < 0.0) refined += 0.5 * (l - r) / curvature;
  }
  s.bins = centre - reach + refined;
  s.on_edge = best == 0 || best == 2 * reach;
  return s;
}

/// The profile's bins on one side of the path (`left`: offsets > 0), the other side zeroed;
/// empty when that side shows no wall (its highest bin under min_wall_contrast x the floor).
std::vector<float> SideBins(const WallProfile& p, bool left, double min_wall_contrast) {
  std::vector<float> side(p.bins.size(), 0.0f);
  const std::size_t half = p.bins.size() / 2;  // bin half is the first at an offset > 0
  float peak = 0.0f;
  for (std::size_t j = left ? half : 0; j < (left ? p.bins.size() : half); ++j) {
    side[j] = p.bins[j];
    peak = std::max(peak, p.bins[j]);
  }
  if (!(p.floor > 0.0) || (peak + p.floor) / p.floor < min_wall_contrast) return {};
  return side;
}

}  // namespace

WallProfileAlignment AlignWallProfiles(const WallProfile& a, const WallProfile& b,
                                       double predicted_offset_m, const WallProfileConfig& config) {
  if (a.bins.size() != b.bins.size() || a.bin_m != b.bin_m) {
    throw std::invalid_argument("AlignWallProfiles: profiles of different geometry");
  }
  WallProfileAlignment result;
  char text[96];
  if (std::min(a.contrast, b.contrast) < config.min_wall_contrast) {
    std::snprintf(text, sizeof text, "no wall: profile contrast %.1f < %.1f",
                  std::min(a.contrast, b.contrast), config.min_wall_contrast);
    result.reason = text;
    return result;
  }
  // a's offset s_a of a world point is b's s_b plus b's anchor offset: a[q + shift] ~ b[q].
  const int centre = static_cast<int>(std::lround(predicted_offset_m / a.bin_m));
  const int reach = static_cast<int>(std::lround(config.search_m / a.bin_m));
  const Shift whole = BestShift(a.bins, b.bins, centre, reach);
  result.correlation = whole.correlation;
  result.offset_m = whole.bins * a.bin_m;
  if (whole.on_edge) {
    std::snprintf(text, sizeof text, "peak on the edge of the +-%.2f m search", config.search_m);
    result.reason = text;
    return result;
  }
  if (result.correlation < config.min_correlation) {
    std::snprintf(text, sizeof text, "correlation %.2f < %.2f", result.correlation,
                  config.min_correlation);
    result.reason = text;
    return result;
  }
  // Where both sides show walls, each side aligned alone must tell the same shift: when they
  // do not, the tiles saw different things on one side (a cabinet here, another one there) and
  // the whole profile's peak is a compromise between them.
  if (config.max_side_disagreement_m > 0.0) {
    double side_offset_m[2];
    bool both = true;
    for (int left = 0; left < 2 && both; ++left) {
      const std::vector<float> sa = SideBins(a, left, config.min_wall_contrast);
      const std::vector<float> sb = SideBins(b, left, config.min_wall_contrast);
      const Shift s = sa.empty() || sb.empty() ? Shift{} : BestShift(sa, sb, centre, reach);
      both = !sa.empty() && !sb.empty() && !s.on_edge;
      side_offset_m[left] = s.bins * a.bin_m;
    }
    if (both) {
      result.side_disagreement_m = std::abs(side_offset_m[1] - side_offset_m[0]);
      if (result.side_disagreement_m > config.max_side_disagreement_m) {
        std::snprintf(text, sizeof text, "the two sides' walls disagree by %.1f cm > %.1f cm",
                      100.0 * result.side_disagreement_m, 100.0 * config.max_side_disagreement_m);
        result.reason = text;
        return result;
      }
    }
  }
  result.accepted = true;
  return result;
}

}  // namespace uwbsar
