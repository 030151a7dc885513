#include "backend/navigation_grid.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/errors.h"

namespace uwbsar {
namespace {

/// The cell lattice: multiples of cell_m in the map frame, so that grids of one map line up.
struct Lattice {
  double cell_m = 0.05;
  long long col0 = 0, row_top = 0;  ///< lattice column of column 0, lattice row of row 0
  int rows = 0, cols = 0;

  /// The cell index of a map point; -1 outside.
  long long Index(double x_m, double y_m) const {
    const long long c = static_cast<long long>(std::floor(x_m / cell_m)) - col0;
    const long long r = row_top - static_cast<long long>(std::floor(y_m / cell_m));
    if (c < 0 || r < 0 || c >= cols || r >= rows) return -1;
    return r * cols + c;
  }
};

/// Per-keyframe marks and the fused log-odds of every cell.
class Fusion {
 public:
  Fusion(std::size_t cells, const NavigationGridConfig& config)
      : config_(config), log_odds_(cells, 0.0f), mark_(cells, -1) {}

  void MarkFree(long long i) { Mark(i, 2 * keyframe_); }
  void MarkHit(long long i) { Mark(i, 2 * keyframe_ + 1); }

  /// Adds this keyframe's marks: a cell any of its lines saw occupied counts as a hit (a
  /// surface is what stopped the pulse), else as a miss.
  void EndKeyframe() {
    const float clamp = static_cast<float>(config_.log_odds_clamp);
    for (const long long i : touched_) {
      const auto u = static_cast<std::size_t>(i);
      const double delta = mark_[u] & 1 ? config_.log_odds_hit : config_.log_odds_miss;
      log_odds_[u] = std::clamp(log_odds_[u] + static_cast<float>(delta), -clamp, clamp);
    }
    touched_.clear();
    ++keyframe_;
  }
  const std::vector<float>& log_odds() const { return log_odds_; }

 private:
  /// One int per cell: 2 x keyframe, + 1 once a line of it hit the cell (a hit outranks a miss).
  void Mark(long long i, int mark) {
    if (i < 0) return;
    int& m = mark_[static_cast<std::size_t>(i)];
    if (m < 2 * keyframe_) touched_.push_back(i);
    m = std::max(m, mark);
  }

  const NavigationGridConfig& config_;
  std::vector<float> log_odds_;
  std::vector<int> mark_;
  std::vector<long long> touched_;
  int keyframe_ = 0;
};

/// The lattice covering every tile and the path's discs.
Lattice CoveringLattice(const std::vector<NavigationKeyframe>& keyframes,
                        const std::vector<Pose2>& path, double footprint_m, double cell_m,
                        double max_cells) {
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  auto include = [&](const Point2& p, double pad) {
    x0 = std::min(x0, p.x_m - pad), x1 = std::max(x1, p.x_m + pad);
    y0 = std::min(y0, p.y_m - pad), y1 = std::max(y1, p.y_m + pad);
  };
  for (const NavigationKeyframe& k : keyframes) {
    const ImageGrid& g = k.grid;
    for (const double c : {-0.5, g.cols - 0.5}) {
      for (const double r : {-0.5, g.rows - 0.5})
        include(k.T_map_anchor * g.PixelToMetric(c, r), 0);
    }
  }
  for (const Pose2& p : path) include({p.x_m, p.y_m}, footprint_m + cell_m);
  Lattice l;
  l.cell_m = cell_m;
  if (!(x1 >= x0) || !(y1 >= y0)) return l;
  const double cols = std::floor(x1 / cell_m) - std::floor(x0 / cell_m) + 1;
  const double rows = std::floor(y1 / cell_m) - std::floor(y0 / cell_m) + 1;
  if (!(cols * rows <= max_cells)) {
    throw InputError("the navigation grid would be " + std::to_string(cols) + " x " +
                     std::to_string(rows) + " cells at " + std::to_string(cell_m) +
                     " m, more than limits.max_image_pixels; refused before allocation");
  }
  l.col0 = static_cast<long long>(std::floor(x0 / cell_m));
  l.row_top = static_cast<long long>(std::floor(y1 / cell_m));
  l.cols = static_cast<int>(cols);
  l.rows = static_cast<int>(rows);
  return l;
}

/// Casts the lines of one keyframe into `fusion`.
class KeyframeCaster {
 public:
  KeyframeCaster(const NavigationKeyframe& k, const NavigationGridConfig& config,
                 const Lattice& lattice, float reference, Fusion* fusion)
      : k_(k),
        config_(config),
        lattice_(lattice),
        fusion_(fusion),
        hit_level_(static_cast<float>(config.return_fraction) * reference),
        support_level_(static_cast<float>(config.ridge_support_fraction) * reference),
        step_m_(std::min(k.grid.resolution_m, 0.5 * lattice.cell_m)),
        half_width_px_(
            static_cast<int>(std::lround(0.5 * config.ray_width_m / k.grid.resolution_m))) {}

  void Cast(const Pose2& T_anchor_sensor, const SensorGeometry& sensor, const WallRidge* ridge) {
    const Point2 o{T_anchor_sensor.x_m, T_anchor_sensor.y_m};
    const double dx = std::cos(T_anchor_sensor.yaw_rad), dy = std::sin(T_anchor_sensor.yaw_rad);
    const int n = static_cast<int>(std::ceil(sensor.max_range_m / step_m_));
    int hit = -1, end = n;  // first strong return; first sample without data
    for (int i = 0; i <= n; ++i) {
      const double r = i * step_m_;
      const float v = Sample(o.x_m + r * dx, o.y_m + r * dy, -dy, dx);
      // Closer than min_range_m nothing is imaged: the pulse crossed it (the blind zone
      // beside the path is free, as the robot's radars see no closer).
      if (r < sensor.min_range_m) continue;
      if (!(v > 0.0f)) {
        end = i;
        break;
      }
      if (v >= hit_level_) {
        hit = i;
        break;
      }
    }
    if (ridge != nullptr && ridge->found) {
      const double along = ridge->normal_x * dx + ridge->normal_y * dy;
      const double r =
          (ridge->offset_m - ridge->normal_x * o.x_m - ridge->normal_y * o.y_m) / along;
      const int i = static_cast<int>(std::lround(r / step_m_));
      if (std::abs(along) > 0.5 && r >= sensor.min_range_m && (hit < 0 || i < hit) && i < end &&
          Supported(i, o, dx, dy)) {
        hit = i;
      }
    }
    const int margin = static_cast<int>(std::lround(config_.free_margin_m / step_m_));
    const int free_end = hit >= 0 ? hit - margin : (config_.free_without_return ? end : 0);
    for (int i = 0; i < free_end; ++i) fusion_->MarkFree(CellAt(o, dx, dy, i));
    if (hit < 0) return;
    const int thick =
        std::max(0, static_cast<int>(std::lround(config_.wall_thickness_m / step_m_)));
    for (int i = hit; i <= hit + thick; ++i) fusion_->MarkHit(CellAt(o, dx, dy, i));
  }

 private:
  long long CellAt(const Point2& o, double dx, double dy, int i) const {
    const Point2 p = k_.T_map_anchor * Point2{o.x_m + i * step_m_ * dx, o.y_m + i * step_m_ * dy};
    return lattice_.Index(p.x_m, p.y_m);
  }
  /// The strongest tile pixel within ray_width_m / 2 of (x, y) across the line (normal
  /// (nx, ny)): a wall imaged as a dashed row of scatterers stops every line that meets it. 0
  /// where nothing was imaged.
  float Sample(double x, double y, double nx, double ny) const {
    float best = 0.0f;
    for (int j = -half_width_px_; j <= half_width_px_; ++j) {
      const double t = j * k_.grid.resolution_m;
      const double col = k_.grid.XToCol(x + t * nx), row = k_.grid.YToRow(y + t * ny);
      if (!k_.grid.Contains(col, row)) continue;
      best = std::max(best, k_.detected->at<float>(static_cast<int>(std::lround(row)),
                                                   static_cast<int>(std::lround(col))));
    }
    return best;
  }
  /// The tile has some echo within wall_thickness_m of sample i.
  bool Supported(int i, const Point2& o, double dx, double dy) const {
    const int w = std::max(1, static_cast<int>(std::lround(config_.wall_thickness_m / step_m_)));
    for (int j = std::max(0, i - w); j <= i + w; ++j) {
      const double r = j * step_m_;
      if (Sample(o.x_m + r * dx, o.y_m + r * dy, -dy, dx) >= support_level_) return true;
    }
    return false;
  }

  const NavigationKeyframe& k_;
  const NavigationGridConfig& config_;
  const Lattice& lattice_;
  Fusion* fusion_;
  float hit_level_, support_level_;
  double step_m_;
  int half_width_px_;
};

}  // namespace

float TileReferenceLevel(const std::vector<NavigationKeyframe>& keyframes, double percentile) {
  // Every 4th pixel of every 4th row: the percentile of a whole run's tiles without holding
  // them all again (100 MB on a 75 m run).
  constexpr int kStride = 4;
  std::vector<float> values;
  for (const NavigationKeyframe& k : keyframes) {
    const cv::Mat& t = *k.detected;
    for (int r = 0; r < t.rows; r += kStride) {
      const float* p = t.ptr<float>(r);
      for (int c = 0; c < t.cols; c += kStride) {
        if (p[c] > 0.0f) values.push_back(p[c]);
      }
    }
  }
  if (values.empty()) return 0.0f;
  const std::size_t k =
      std::min(values.size() - 1,
               static_cast<std::size_t>(percentile / 100.0 * static_cast<double>(values.size())));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

OccupancyGrid BuildNavigationGrid(const std::vector<NavigationKeyframe>& keyframes,
                                  const std::vector<Pose2>& path,
                                  const std::vector<SensorGeometry>& sensors,
                                  const NavigationGridConfig& config, double cell_m,
                                  float reference_level, double max_cells) {
  for (const NavigationKeyframe& k : keyframes) {
    if (k.detected == nullptr || k.detected->type() != CV_32FC1 ||
        k.detected->rows != k.grid.rows || k.detected->cols != k.grid.cols) {
      throw std::invalid_argument("BuildNavigationGrid: a CV_32FC1 tile of its grid's size");
    }
  }
  const Lattice lattice =
      CoveringLattice(keyframes, path, config.footprint_radius_m, cell_m, max_cells);
  OccupancyGrid grid;
  grid.resolution_m = cell_m;
  grid.rows = lattice.rows;
  grid.cols = lattice.cols;
  grid.origin = {static_cast<double>(lattice.col0) * cell_m,
                 static_cast<double>(lattice.row_top - lattice.rows + 1) * cell_m, 0.0};
  const std::size_t num_cells = static_cast<std::size_t>(grid.rows) * grid.cols;
  grid.cells.assign(num_cells, OccupancyGrid::kUnknown);
  if (num_cells == 0) return grid;

  Fusion fusion(num_cells, config);
  const double step_rad = config.ray_angle_step_deg * M_PI / 180.0;
  const int num_side = config.SideLines();
  for (const NavigationKeyframe& k : keyframes) {
    KeyframeCaster caster(k, config, lattice, reference_level, &fusion);
    Point2 last{INFINITY, INFINITY};
    for (const Pose2& robot : k.T_anchor_robot) {
      // One set of lines per ray_spacing_m of path (and at the first pose).
      if (std::hypot(robot.x_m - last.x_m, robot.y_m - last.y_m) < config.ray_spacing_m) continue;
      last = {robot.x_m, robot.y_m};
      for (std::size_t s = 0; s < sensors.size(); ++s) {
        const Pose2 T_anchor_sensor = robot * sensors[s].T_robot_sensor;
        const WallRidge* ridge = s < k.ridges.size() ? &k.ridges[s] : nullptr;
        for (int a = -num_side; a <= num_side; ++a) {
          const Pose2 line{T_anchor_sensor.x_m, T_anchor_sensor.y_m,
                           T_anchor_sensor.yaw_rad + a * step_rad};
          // Off-boresight lines cross the wall obliquely: only the cross-track one uses the ridge.
          caster.Cast(line, sensors[s], a == 0 ? ridge : nullptr);
        }
      }
    }
    fusion.EndKeyframe();
  }
  const std::vector<float>& log_odds = fusion.log_odds();
  for (std::size_t i = 0; i < num_cells; ++i) {
    if (log_odds[i] >= config.occupied_log_odds) {
      grid.cells[i] = OccupancyGrid::kOccupied;
    } else if (log_odds[i] <= config.free_log_odds) {
      grid.cells[i] = OccupancyGrid::kFree;
    }
  }
  // The robot's swept discs are free: it was there.
  const double radius = config.footprint_radius_m;
  const int reach = static_cast<int>(std::ceil(radius / cell_m)) + 1;
  Point2 last{INFINITY, INFINITY};
  for (const Pose2& p : path) {
    if (std::hypot(p.x_m - last.x_m, p.y_m - last.y_m) < 0.25 * cell_m) continue;
    last = {p.x_m, p.y_m};
    const long long pc = static_cast<long long>(std::floor(p.x_m / cell_m));
    const long long pr = static_cast<long long>(std::floor(p.y_m / cell_m));
    for (long long r = pr - reach; r <= pr + reach; ++r) {
      for (long long c = pc - reach; c <= pc + reach; ++c) {
        const double cx = (static_cast<double>(c) + 0.5) * cell_m;
        const double cy = (static_cast<double>(r) + 0.5) * cell_m;
        if (std::hypot(cx - p.x_m, cy - p.y_m) > radius) continue;
        const long long i = lattice.Index(cx, cy);
        if (i >= 0) grid.cells[static_cast<std::size_t>(i)] = OccupancyGrid::kFree;
      }
    }
  }
  return grid;
}

}  // namespace uwbsar
