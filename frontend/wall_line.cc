#include "frontend/wall_line.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "frontend/profile_bins.h"
#include "frontend/wall_profile.h"

namespace uwbsar {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// A wall in the whole tile's profile.
struct Candidate {
  double offset_m = 0.0;  ///< across the path (the peak bin's centre)
  float height = 0.0f;    ///< the peak over the floor
  double contrast = 0.0;  ///< (height + floor) / floor
};

/// The walls of the profile: local maxima standing config.min_peak_contrast over its floor, at
/// least min_distance_m from the anchor, strongest first, at most max_lines_per_side a side and
/// more than two bands apart (the flanks and speckle of one wall are not a second wall).
std::vector<Candidate> PickWalls(const WallProfile& p, const WallLineConfig& config) {
  std::vector<Candidate> peaks;
  if (!(p.floor > 0.0)) return peaks;
  const int n = static_cast<int>(p.bins.size());
  for (int b = 1; b + 1 < n; ++b) {
    const float v = p.bins[static_cast<std::size_t>(b)];
    if (!(v > 0.0f) || v < p.bins[static_cast<std::size_t>(b - 1)] ||
        !(v > p.bins[static_cast<std::size_t>(b + 1)])) {
      continue;
    }
    Candidate c{(b + 0.5) * p.bin_m - p.half_width_m(), v, (v + p.floor) / p.floor};
    if (c.contrast >= config.min_peak_contrast && std::abs(c.offset_m) >= config.min_distance_m) {
      peaks.push_back(c);
    }
  }
  std::sort(peaks.begin(), peaks.end(),
            [](const Candidate& a, const Candidate& b) { return a.height > b.height; });
  std::vector<Candidate> walls;
  int left = 0, right = 0;
  for (const Candidate& c : peaks) {
    int& side = c.offset_m > 0.0 ? left : right;
    if (side >= config.max_lines_per_side) continue;
    const bool apart = std::all_of(walls.begin(), walls.end(), [&](const Candidate& w) {
      return std::abs(w.offset_m - c.offset_m) > 2.0 * config.band_m;
    });
    if (!apart) continue;
    walls.push_back(c);
    ++side;
  }
  return walls;
}

/// The tile within +-half_m of a wall's offset, summed into cells along the path (one pixel
/// wide) x bins across it (the profile's bins). half_m is two bands: the wall is searched in
/// the middle half (+-band), the outer parts give the floor beside it (a radar's wall is blurred
/// over a width like the band's, so the band alone would hold little but the wall).
struct Band {
  double centre_m = 0.0, half_m = 0.0, bin_m = 0.0;  ///< across the path
  double along0_m = 0.0, cell_m = 0.0;               ///< cell k covers along0 + [k, k+1) cell
  int cells = 0, bins = 0;
  std::vector<float> sums;  ///< cells x bins
  std::vector<int> imaged;  ///< pixels > 0 per cell

  const float* Cell(int k) const { return sums.data() + static_cast<std::size_t>(k) * bins; }
  double AcrossM(double bin) const { return centre_m - half_m + (bin + 0.5) * bin_m; }
  double AlongM(double cell) const { return along0_m + (cell + 0.5) * cell_m; }
};

Band SumBand(const cv::Mat& detected, const ImageGrid& grid, double heading_rad, double centre_m,
             double half_m, double bin_m) {
  const double ux = std::cos(heading_rad), uy = std::sin(heading_rad);
  const GridProjection along(grid, ux, uy), across(grid, -uy, ux);
  Band band;
  band.centre_m = centre_m;
  band.half_m = half_m;
  band.bin_m = bin_m;
  band.bins = static_cast<int>(std::lround(2.0 * half_m / bin_m));
  // The tile's extent along the path: its corners' pixel centres.
  const double t[4] = {along.At(0, 0), along.At(grid.cols - 1, 0), along.At(0, grid.rows - 1),
                       along.At(grid.cols - 1, grid.rows - 1)};
  band.cell_m = grid.resolution_m;
  band.along0_m = *std::min_element(t, t + 4) - 0.5 * band.cell_m;
  band.cells = static_cast<int>((*std::max_element(t, t + 4) - band.along0_m) / band.cell_m) + 1;
  band.sums.assign(static_cast<std::size_t>(band.cells) * band.bins, 0.0f);
  band.imaged.assign(static_cast<std::size_t>(band.cells), 0);
  // Pixels whose footprint reaches into the band: across = AtRow(r) + per_col c lies within
  // reach of the centre, an interval of columns on each row.
  const double reach_m = half_m + 0.5 * across.footprint_m;
  const double first_edge_m = centre_m - half_m + 0.5 * across.footprint_m;  // as in the profile
  const double width_bins = across.footprint_m / bin_m;
  for (int r = 0; r < grid.rows; ++r) {
    const double s_row = across.AtRow(r);
    int c_begin = 0, c_end = grid.cols;
    if (std::abs(across.per_col_m) > 1e-12) {
      const double a = (centre_m - reach_m - s_row) / across.per_col_m;
      const double b = (centre_m + reach_m - s_row) / across.per_col_m;
      c_begin = std::max(0, static_cast<int>(std::ceil(std::min(a, b))));
      c_end = std::min(grid.cols, static_cast<int>(std::floor(std::max(a, b))) + 1);
    } else if (std::abs(s_row - centre_m) > reach_m) {
      continue;
    }
    const float* row = detected.ptr<float>(r);
    for (int c = c_begin; c < c_end; ++c) {
      if (!(row[c] > 0.0f)) continue;
      const int k = std::clamp(static_cast<int>((along.At(c, r) - band.along0_m) / band.cell_m), 0,
                               band.cells - 1);
      ++band.imaged[static_cast<std::size_t>(k)];
      SpreadOverBins((s_row + across.per_col_m * c - first_edge_m) / bin_m, width_bins, row[c],
                     band.sums.data() + static_cast<std::size_t>(k) * band.bins, band.bins);
    }
  }
  return band;
}

/// Where the wall lies across the path within cells [begin, end) of the band, if it shows.
struct StripPeak {
  bool shows = false;
  double across_m = 0.0;  ///< the wall's offset along the path's left normal
  double along_m = 0.0;   ///< where along the path the wall's energy in the strip lies
  double energy = 0.0;    ///< the wall's energy above the floor in the strip
};

StripPeak FindStripPeak(const Band& band, int begin, int end, double min_contrast) {
  StripPeak result;
  std::vector<float> profile(static_cast<std::size_t>(band.bins), 0.0f);
  int imaged = 0;
  for (int k = begin; k < end; ++k) {
    imaged += band.imaged[static_cast<std::size_t>(k)];
    const float* cell = band.Cell(k);
    for (int b = 0; b < band.bins; ++b) profile[static_cast<std::size_t>(b)] += cell[b];
  }
  if (imaged == 0) return result;
  // The floor: the lower quartile of the imaged bins (a wall and its flanks may fill half of
  // them, so not the median).
  std::vector<float> sorted;
  for (const float v : profile) {
    if (v > 0.0f) sorted.push_back(v);
  }
  if (sorted.size() < 4) return result;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 4, sorted.end());
  const double floor = sorted[sorted.size() / 4];
  // The peak within +-band (the middle half); one on its edge may be a wall beyond it, or the
  // flank of one.
  const int search_begin = band.bins / 4, search_end = band.bins - band.bins / 4;
  const int peak = static_cast<int>(
      std::max_element(profile.begin() + search_begin, profile.begin() + search_end) -
      profile.begin());
  if (peak == search_begin || peak + 1 == search_end ||
      profile[static_cast<std::size_t>(peak)] < min_contrast * floor) {
    return result;
  }
  // Below a bin: the centroid above the floor within +-half a band of it, moved onto the
  // centroid until it settles (the wall's spread across the path is symmetric; a parabola
  // through three bins of a speckled profile is several times noisier).
  const int reach = std::max(1, band.bins / 8);
  double centre = peak;
  for (int iteration = 0; iteration < 5; ++iteration) {
    const int c = static_cast<int>(std::lround(centre));
    double mass = 0.0, moment = 0.0;
    for (int b = std::max(0, c - reach); b <= std::min(band.bins - 1, c + reach); ++b) {
      const double w = profile[static_cast<std::size_t>(b)] - floor;
      if (w <= 0.0) continue;
      mass += w;
      moment += w * b;
    }
    if (!(mass > 0.0)) break;
    const double moved = moment / mass;
    const bool settled = std::abs(moved - centre) < 1e-3;
    centre = moved;
    if (settled) break;
  }
  // Along: the cells weighted by the wall's energy above the floor near the wall.
  const int at = static_cast<int>(std::lround(centre));
  const int lo = std::max(0, at - reach), hi = std::min(band.bins, at + reach + 1);
  const double cell_floor = floor * (hi - lo) / std::max(1, end - begin);
  double weight = 0.0, moment = 0.0;
  for (int k = begin; k < end; ++k) {
    const float* cell = band.Cell(k);
    double w = -cell_floor;
    for (int b = lo; b < hi; ++b) w += cell[b];
    if (w <= 0.0) continue;
    weight += w;
    moment += w * band.AlongM(k);
  }
  if (!(weight > 0.0)) return result;
  result.shows = true;
  result.across_m = band.AcrossM(centre);
  result.along_m = moment / weight;
  result.energy = weight;
  return result;
}

/// Least squares across = at_anchor + slope * along through the strips' positions, each
/// weighted by its wall energy (weights of mean 1): a strip that shows little of the wall (a
/// doorway, the tile's end) places it less precisely.
struct LineFit {
  bool ok = false;  ///< false: no energy, or no two distinct positions along the path
  int n = 0;
  double slope = 0.0, at_anchor_m = 0.0;
  double t_mean_m = 0.0, stt = 0.0;  ///< weighted mean along, and sum of squares about it
  double squares = 0.0;              ///< weighted sum of squared residuals

  double Residual(const StripPeak& p) const {
    return p.across_m - (at_anchor_m + slope * p.along_m);
  }
};

LineFit FitLine(const std::vector<StripPeak>& strips) {
  LineFit fit;
  fit.n = static_cast<int>(strips.size());
  double total = 0.0;
  for (const StripPeak& p : strips) total += p.energy;
  if (!(total > 0.0)) return fit;
  std::vector<double> w;
  for (const StripPeak& p : strips) w.push_back(fit.n * p.energy / total);
  double s_mean = 0.0;
  for (std::size_t i = 0; i < strips.size(); ++i) {
    fit.t_mean_m += w[i] * strips[i].along_m / fit.n;
    s_mean += w[i] * strips[i].across_m / fit.n;
  }
  double sts = 0.0;
  for (std::size_t i = 0; i < strips.size(); ++i) {
    const double dt = strips[i].along_m - fit.t_mean_m;
    fit.stt += w[i] * dt * dt;
    sts += w[i] * dt * (strips[i].across_m - s_mean);
  }
  if (!(fit.stt > 0.0)) return fit;
  fit.ok = true;
  fit.slope = sts / fit.stt;
  fit.at_anchor_m = s_mean - fit.slope * fit.t_mean_m;
  for (std::size_t i = 0; i < strips.size(); ++i) {
    fit.squares += w[i] * fit.Residual(strips[i]) * fit.Residual(strips[i]);
  }
  return fit;
}

}  // namespace

std::vector<WallLineObservation> FindWallLines(const cv::Mat& detected, const ImageGrid& grid,
                                               double heading_rad,
                                               const WallProfileConfig& config) {
  return FindWallLines(detected, grid, ComputeWallProfile(detected, grid, heading_rad, config),
                       config);
}

std::vector<WallLineObservation> FindWallLines(const cv::Mat& detected, const ImageGrid& grid,
                                               const WallProfile& profile,
                                               const WallProfileConfig& config) {
  const double heading_rad = profile.heading_rad;
  const WallLineConfig& lines = config.landmarks;
  std::vector<WallLineObservation> result;
  for (const Candidate& wall : PickWalls(profile, lines)) {
    const Band band =
        SumBand(detected, grid, heading_rad, wall.offset_m, 2.0 * lines.band_m, config.bin_m);
    // The extent along the path in which the wall shows: from the first to the last of
    // 4 x strips segments of the band's imaged cells that show it.
    int first = 0, last = band.cells - 1;
    while (first <= last && band.imaged[static_cast<std::size_t>(first)] == 0) ++first;
    while (last >= first && band.imaged[static_cast<std::size_t>(last)] == 0) --last;
    const int segments = 4 * lines.strips;
    if (last - first + 1 < segments) continue;
    int begin = -1, end = -1;
    for (int s = 0; s < segments; ++s) {
      const int a = first + (last + 1 - first) * s / segments;
      const int b = first + (last + 1 - first) * (s + 1) / segments;
      if (!FindStripPeak(band, a, b, lines.min_peak_contrast).shows) continue;
      if (begin < 0) begin = a;
      end = b;
    }
    // Each strip at least a segment long: a wall seen over a short piece has no angle.
    if (begin < 0 || (end - begin) * segments < lines.strips * (last + 1 - first)) continue;
    // The wall's position across the path in each strip; a line through them.
    std::vector<StripPeak> shown;
    for (int s = 0; s < lines.strips; ++s) {
      const StripPeak peak =
          FindStripPeak(band, begin + (end - begin) * s / lines.strips,
                        begin + (end - begin) * (s + 1) / lines.strips, lines.min_peak_contrast);
      if (peak.shows) shown.push_back(peak);
    }
    if (static_cast<int>(shown.size()) < std::max(2, lines.min_strips)) continue;
    const LineFit fit = FitLine(shown);
    if (!fit.ok) continue;
    const int n = fit.n;
    const double slope = fit.slope, at_anchor_m = fit.at_anchor_m, t_mean = fit.t_mean_m;
    const double stt = fit.stt, squares = fit.squares;
    WallLineObservation line;
    line.fit_rms_m = std::sqrt(squares / n);
    if (line.fit_rms_m > lines.max_fit_rms_m) continue;  // a corner or a step, not one wall
    // The wall runs along d = heading + angle; its left normal is d + 90 deg. A point of it,
    // at_anchor_m along the path's left normal from the anchor, lies cos(angle) * at_anchor_m
    // from the anchor along the wall's normal.
    const double angle_rad = std::atan(slope);
    line.normal_rad = NormalizeAngle(heading_rad + angle_rad + 0.5 * kPi);  // [-pi, pi) ...
    if (line.normal_rad <= -kPi) line.normal_rad = kPi;                     // ... to (-pi, pi]
    line.offset_m = std::cos(angle_rad) * at_anchor_m;
    // The configured uncertainties, combined with the fit's standard errors (offset at the
    // anchor, slope): they grow when the strips scatter about the line or span little of the
    // path. A strip's variance: the residuals' (n - 2 degrees of freedom), at least a bin's
    // square (three strips on a line by chance do not make a precise angle).
    const double strip_var = std::max(n > 2 ? squares / (n - 2) : 0.0, config.bin_m * config.bin_m);
    const double offset_var = strip_var * (1.0 / n + t_mean * t_mean / stt);
    line.offset_std_m = std::sqrt(lines.offset_std_m * lines.offset_std_m + offset_var);
    const double angle_std_rad = lines.angle_std_deg * kPi / 180.0;
    line.normal_std_rad = std::sqrt(angle_std_rad * angle_std_rad + strip_var / stt);
    line.begin_m = shown.front().along_m;
    line.end_m = shown.back().along_m;
    line.contrast = wall.contrast;
    line.num_strips = n;
    result.push_back(line);
  }
  std::stable_sort(result.begin(), result.end(),
                   [](const WallLineObservation& a, const WallLineObservation& b) {
                     return a.contrast > b.contrast;
                   });
  return result;
}

}  // namespace uwbsar
