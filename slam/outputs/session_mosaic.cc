#include "slam/outputs/session_mosaic.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <vector>

#include "backend/global_map.h"
#include "core/errors.h"

namespace uwbsar::slam {
namespace {

/// The value at `percentile` of the observed pixels (1 when none).
float ReferenceLevel(const cv::Mat& map, const cv::Mat& observed, double percentile) {
  std::vector<float> v;
  for (int r = 0; r < map.rows; ++r) {
    const float* m = map.ptr<float>(r);
    const unsigned char* o = observed.ptr<unsigned char>(r);
    for (int c = 0; c < map.cols; ++c) {
      if (o[c]) v.push_back(m[c]);
    }
  }
  if (v.empty()) return 1.0f;
  const std::size_t k =
      std::min(v.size() - 1, static_cast<std::size_t>(percentile / 100.0 * double(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k] > 0.0f ? v[k] : 1.0f;
}

/// One run's mean mosaic on the world lattice (a block-aligned part of the union's) and
/// its occupancy reference level.
struct RunMap {
  int id = 0;
  ImageGrid grid;
  cv::Mat map, observed;
  float reference = 1.0f;
};

std::vector<RunMap> RunMosaics(const SessionData& session, double resolution_m,
                               double reference_percentile) {
  std::set<int> ids;
  for (const SessionKeyframe& k : session.keyframes) ids.insert(k.trajectory);
  std::vector<RunMap> runs;
  for (int id : ids) {
    GlobalMap global(resolution_m);
    for (const SessionKeyframe& k : session.keyframes) {
      if (k.trajectory == id) global.AddTile(k.detected.Load(), k.detected_grid, k.T_map_anchor);
    }
    RunMap r;
    r.id = id;
    r.map = global.Render(&r.grid, &r.observed);
    if (r.map.empty()) continue;
    r.reference = ReferenceLevel(r.map, r.observed, reference_percentile);
    runs.push_back(std::move(r));
  }
  return runs;
}

/// The per-pixel max of the runs' mosaics over the union of their grids.
cv::Mat MaxOfRuns(const std::vector<RunMap>& runs, double resolution_m, ImageGrid* grid,
                  cv::Mat* observed) {
  *grid = ImageGrid{};
  grid->resolution_m = resolution_m;
  if (runs.empty()) {
    *observed = cv::Mat();
    return cv::Mat();
  }
  double x0 = runs[0].grid.x0_m, y0 = runs[0].grid.y0_m, x1 = x0, y1 = y0;
  for (const RunMap& r : runs) {
    x0 = std::min(x0, r.grid.x0_m);
    y0 = std::max(y0, r.grid.y0_m);
    x1 = std::max(x1, r.grid.x0_m + (r.grid.cols - 1) * resolution_m);
    y1 = std::min(y1, r.grid.y0_m - (r.grid.rows - 1) * resolution_m);
  }
  *grid = runs[0].grid;
  grid->x0_m = x0;
  grid->y0_m = y0;
  grid->cols = static_cast<int>(std::lround((x1 - x0) / resolution_m)) + 1;
  grid->rows = static_cast<int>(std::lround((y0 - y1) / resolution_m)) + 1;
  cv::Mat out = cv::Mat::zeros(grid->rows, grid->cols, CV_32FC1);
  *observed = cv::Mat::zeros(grid->rows, grid->cols, CV_8UC1);
  for (const RunMap& r : runs) {
    const cv::Rect roi(static_cast<int>(std::lround((r.grid.x0_m - x0) / resolution_m)),
                       static_cast<int>(std::lround((y0 - r.grid.y0_m) / resolution_m)),
                       r.grid.cols, r.grid.rows);
    cv::Mat dst = out(roi);
    cv::max(dst, r.map, dst);
    cv::Mat o = (*observed)(roi);
    cv::bitwise_or(o, r.observed, o);
  }
  return out;
}

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.6g", v);
  return buf;
}

/// What the session came from, for errors: its file, else its runs' inputs.
std::string SessionSource(const SessionData& session) {
  if (!session.source.empty()) return session.source;
  std::string out;
  for (const SessionTrajectory& t : session.trajectories)
    out += (out.empty() ? "" : ", ") + t.input;
  return out.empty() ? "session" : out;
}

}  // namespace

void CheckSessionMosaicExtent(const SessionData& session, double resolution_m, double max_pixels) {
  if (session.keyframes.empty() || !(resolution_m > 0)) return;
  // The lattice of the mosaic, without allocating a block of it.
  const GlobalMap lattice(resolution_m);
  GlobalMap::BlockSpan span;
  for (const SessionKeyframe& k : session.keyframes) {
    span.Include(lattice.TileBlocks(k.detected_grid, k.T_map_anchor));
  }
  const double pixels = lattice.SpanPixels(span);
  if (!(pixels <= max_pixels)) {
    const double block_m = lattice.block_px() * resolution_m;
    throw InputError(SessionSource(session) + ": the map of its keyframes spans x " +
                     Num(static_cast<double>(span.bc0) * block_m) + " .. " +
                     Num(static_cast<double>(span.bc1 + 1) * block_m) + " m, y " +
                     Num(-static_cast<double>(span.br1 + 1) * block_m) + " .. " +
                     Num(-static_cast<double>(span.br0) * block_m) + " m: " + Num(pixels) +
                     " pixels at " + Num(resolution_m) + " m, more than limits.max_image_pixels (" +
                     Num(max_pixels) + "); refused before allocation");
  }
}

cv::Mat RenderSessionMosaic(const SessionData& session, const Config& config, ImageGrid* grid,
                            cv::Mat* observed) {
  const JoinedMosaic mode = config.session.joined_mosaic;
  return RenderSessionMosaic(session, config.slam.map_resolution_m, mode, grid, observed,
                             config.slam.occupancy_reference_percentile,
                             config.limits.max_image_pixels);
}

cv::Mat RenderSessionMosaic(const SessionData& session, double resolution_m, JoinedMosaic mode,
                            ImageGrid* grid, cv::Mat* observed, double reference_percentile,
                            double max_pixels) {
  CheckSessionMosaicExtent(session, resolution_m, max_pixels);
  const auto mosaic = [&](const auto& scale_of) {
    GlobalMap global(resolution_m);
    for (const SessionKeyframe& k : session.keyframes) {
      global.AddTile(k.detected.Load() * scale_of(k.trajectory), k.detected_grid, k.T_map_anchor);
    }
    return global.Render(grid, observed);
  };
  if (mode == JoinedMosaic::kMean) return mosaic([](int) { return 1.0; });
  std::vector<RunMap> runs = RunMosaics(session, resolution_m, reference_percentile);
  if (mode == JoinedMosaic::kNormalizedMean) {
    // Every tile in units of its run's reference level, averaged as within one run: where
    // both runs observed, each pixel is a vote weighted by the runs' tiles, which is the
    // occupancy rule applied to the runs' evidence together (see session_config.h).
    std::map<int, double> scale;
    for (const RunMap& r : runs) scale[r.id] = 1.0 / r.reference;
    return mosaic(
        [&](int trajectory) { return scale.count(trajectory) ? scale[trajectory] : 1.0; });
  }
  // kNormalizedMax: each run's mosaic in units of its reference level, saturated at that
  // level: the max of the runs then has at least the percentile's share of its observed
  // pixels at 1, so the occupancy rule's reference on the joined map is 1 and each run's walls
  // are thresholded as in its own map (the joined occupied cells are the union of the runs').
  // Unsaturated, the runs' brightest 1 % add up and raise the reference over all of them.
  for (RunMap& r : runs) {
    r.map *= 1.0 / r.reference;
    cv::min(r.map, 1.0, r.map);
  }
  return MaxOfRuns(runs, resolution_m, grid, observed);
}

}  // namespace uwbsar::slam
