#include "pipeline/session_mosaic.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "backend/global_map.h"

namespace uwbsar::pipeline {
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

}  // namespace

cv::Mat RenderSessionMosaic(const SessionData& session, const Config& config, ImageGrid* grid,
                            cv::Mat* observed) {
  const JoinedMosaic mode = config.session.joined_mosaic;
  return RenderSessionMosaic(session, config.slam.map_resolution_m, mode, grid, observed,
                             config.slam.occupancy_reference_percentile);
}

cv::Mat RenderSessionMosaic(const SessionData& session, double resolution_m, JoinedMosaic mode,
                            ImageGrid* grid, cv::Mat* observed, double reference_percentile) {
  if (mode == JoinedMosaic::kMean) {
    GlobalMap global(resolution_m);
    for (const SessionKeyframe& k : session.keyframes) {
      global.AddTile(k.detected, k.detected_grid, k.T_map_anchor);
    }
    return global.Render(grid, observed);
  }
  // Each run's mean mosaic, in units of its own reference level (the occupancy rule's), so
  // that a brighter run does not raise the threshold over another's walls; all on the world
  // lattice, so each is a block-aligned part of the union.
  struct RunMap {
    ImageGrid grid;
    cv::Mat map, observed;
  };
  std::set<int> ids;
  for (const SessionKeyframe& k : session.keyframes) ids.insert(k.trajectory);
  std::vector<RunMap> runs;
  for (int id : ids) {
    GlobalMap global(resolution_m);
    for (const SessionKeyframe& k : session.keyframes) {
      if (k.trajectory == id) global.AddTile(k.detected, k.detected_grid, k.T_map_anchor);
    }
    RunMap r;
    r.map = global.Render(&r.grid, &r.observed);
    if (r.map.empty()) continue;
    r.map *= 1.0 / ReferenceLevel(r.map, r.observed, reference_percentile);
    runs.push_back(std::move(r));
  }
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

}  // namespace uwbsar::pipeline
