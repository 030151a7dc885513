#include "drivers/sim/scene_change.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <random>

#include "drivers/sim/scene_doors.h"
#include "drivers/sim/sim_environment.h"

namespace uwbsar::sim {
namespace {

constexpr std::uint64_t kSceneChangeStream = 0xc4a76e;
constexpr int kAttemptsPerEdit = 200;

double SegmentDistance(const Point2& p, const Point2& a, const Point2& b) {
  const double dx = b.x_m - a.x_m, dy = b.y_m - a.y_m;
  const double length2 = dx * dx + dy * dy;
  const double t =
      length2 > 0 ? std::clamp(((p.x_m - a.x_m) * dx + (p.y_m - a.y_m) * dy) / length2, 0.0, 1.0)
                  : 0.0;
  return std::hypot(p.x_m - a.x_m - t * dx, p.y_m - a.y_m - t * dy);
}

double PathDistance(const Point2& p, const std::vector<Point2>& path) {
  double best = path.empty() ? std::numeric_limits<double>::infinity()
                             : std::hypot(p.x_m - path[0].x_m, p.y_m - path[0].y_m);
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    best = std::min(best, SegmentDistance(p, path[i], path[i + 1]));
  }
  return best;
}

// The isolated blobs of occupied cells (8-connected) at most `max_extent_m` across.
std::vector<std::vector<int>> SmallObjects(const OccupancyGrid& g, double max_extent_m) {
  std::vector<std::vector<int>> objects;
  std::vector<char> seen(g.cells.size(), 0);
  const int max_cells = static_cast<int>(std::floor(max_extent_m / g.resolution_m + 1e-9));
  for (int start = 0; start < static_cast<int>(g.cells.size()); ++start) {
    if (seen[start] || !g.IsOccupied(start / g.cols, start % g.cols)) continue;
    std::vector<int> blob;
    std::deque<int> queue{start};
    seen[start] = 1;
    int r0 = g.rows, r1 = -1, c0 = g.cols, c1 = -1;
    while (!queue.empty()) {
      const int cell = queue.front();
      queue.pop_front();
      blob.push_back(cell);
      const int row = cell / g.cols, col = cell % g.cols;
      r0 = std::min(r0, row), r1 = std::max(r1, row), c0 = std::min(c0, col),
      c1 = std::max(c1, col);
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          const int r = row + dr, c = col + dc;
          if (!g.InBounds(r, c) || seen[r * g.cols + c] || !g.IsOccupied(r, c)) continue;
          seen[r * g.cols + c] = 1;
          queue.push_back(r * g.cols + c);
        }
      }
    }
    if (r1 - r0 < max_cells && c1 - c0 < max_cells) objects.push_back(std::move(blob));
  }
  return objects;
}

// The edits in progress: the grid as changed so far and the cells edited (never edited twice).
class Editor {
 public:
  Editor(const OccupancyGrid& grid, const std::vector<Point2>& route,
         const SimSceneChangeConfig& config, std::uint64_t seed)
      : grid_(grid),
        route_(route),
        config_(config),
        rng_(DeriveSeed(seed, kSceneChangeStream)),
        touched_(grid.cells.size(), 0),
        distance_(DistanceToPath(
            grid, route,
            std::max({config.reach_m, config.distance_max_m, config.distance_min_m}) +
                grid.resolution_m)) {}

  void RemoveAndMoveObjects() {
    std::vector<std::vector<int>> objects;
    for (auto& object : SmallObjects(grid_, config_.object_max_extent_m)) {
      if (Nearest(object) <= config_.reach_m) objects.push_back(std::move(object));
    }
    std::shuffle(objects.begin(), objects.end(), rng_);
    std::size_t next = 0;
    for (int n = 0; n < config_.objects_removed && next < objects.size(); ++n) {
      Apply(SceneEdit::Kind::kObjectRemoved, {}, objects[next++]);
    }
    for (int n = 0; n < config_.objects_moved && next < objects.size();) {
      n += Move(objects[next++]);
    }
  }

  void CloseDoors() {
    for (int n = 0; n < config_.doors_closed; ++n) {
      if (!PickDoor(FindDoorways(grid_, config_), config_.distance_min_m,
                    SceneEdit::Kind::kDoorClosed)) {
        return;
      }
    }
  }

  void OpenDoors() {
    for (int n = 0; n < config_.doors_opened; ++n) {
      if (!PickDoor(FindOpenableWalls(grid_, config_), 0.0, SceneEdit::Kind::kDoorOpened)) return;
    }
  }

  void AddObjects() {
    std::vector<double> along{0.0};  // arc length at each waypoint
    for (std::size_t i = 1; i < route_.size(); ++i) {
      along.push_back(along.back() + std::hypot(route_[i].x_m - route_[i - 1].x_m,
                                                route_[i].y_m - route_[i - 1].y_m));
    }
    if (along.back() <= 0) return;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int n = 0, attempts = 0;
         n < config_.objects_added && attempts < kAttemptsPerEdit * config_.objects_added;
         ++attempts) {
      const double s = along.back() * unit(rng_);
      const std::size_t i = std::min<std::size_t>(
          std::upper_bound(along.begin(), along.end(), s) - along.begin(), route_.size() - 1);
      const Point2 &a = route_[i - 1], &b = route_[i];
      const double length = along[i] - along[i - 1];
      if (length <= 0) continue;
      const double ux = (b.x_m - a.x_m) / length, uy = (b.y_m - a.y_m) / length;
      const double t = s - along[i - 1];
      const double side = unit(rng_) < 0.5 ? -1.0 : 1.0;
      const double d =
          config_.distance_min_m + (config_.distance_max_m - config_.distance_min_m) * unit(rng_);
      const double size = config_.object_size_min_m +
                          (config_.object_size_max_m - config_.object_size_min_m) * unit(rng_);
      const Point2 centre{a.x_m + ux * t - side * uy * d, a.y_m + uy * t + side * ux * d};
      if (PathDistance(centre, route_) < config_.distance_min_m - 1e-9) continue;
      std::vector<int> cells;
      if (!Square(centre, size, &cells) || !Placeable(cells)) continue;
      Apply(SceneEdit::Kind::kObjectAdded, std::move(cells), {});
      ++n;
    }
  }

  SceneChange Result() { return {std::move(grid_), std::move(edits_)}; }

 private:
  double Nearest(const std::vector<int>& cells) const {
    double best = std::numeric_limits<double>::infinity();
    for (int c : cells) best = std::min(best, static_cast<double>(distance_[c]));
    return best;
  }

  Point2 Centre(const std::vector<int>& cells) const {
    Point2 sum;
    const double n = static_cast<double>(cells.size());
    for (int c : cells) {
      const Point2 p = grid_.CellCenter(c / grid_.cols, c % grid_.cols);
      sum.x_m += p.x_m / n;
      sum.y_m += p.y_m / n;
    }
    return sum;
  }

  // Free, unedited cells that touch no occupied cell (8 neighbours).
  bool Placeable(const std::vector<int>& cells) const {
    for (int cell : cells) {
      const int row = cell / grid_.cols, col = cell % grid_.cols;
      if (!grid_.IsFree(row, col) || touched_[cell]) return false;
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          if (grid_.InBounds(row + dr, col + dc) && grid_.IsOccupied(row + dr, col + dc)) {
            return false;
          }
        }
      }
    }
    return true;
  }

  // The cells whose centres lie in the square of side `size_m` around `centre` (at least the
  // cell holding it); false when it leaves the grid.
  bool Square(const Point2& centre, double size_m, std::vector<int>* cells) const {
    double r = 0.0, c = 0.0;
    grid_.WorldToCell(centre, &r, &c);
    const double half = 0.5 * size_m / grid_.resolution_m;
    int r0 = static_cast<int>(std::ceil(r - half - 0.5)), r1 = static_cast<int>(r + half - 0.5);
    int c0 = static_cast<int>(std::ceil(c - half - 0.5)), c1 = static_cast<int>(c + half - 0.5);
    if (r1 < r0 || c1 < c0)
      r0 = r1 = static_cast<int>(std::floor(r)), c0 = c1 = static_cast<int>(std::floor(c));
    if (!grid_.InBounds(r0, c0) || !grid_.InBounds(r1, c1)) return false;
    *cells = CellBox{r0, r1, c0, c1}.Cells(grid_.cols);
    return true;
  }

  // Moves `object` move_min_m .. move_max_m in a random direction; false (and the object left
  // where it was) when no place is found.
  bool Move(const std::vector<int>& object) {
    for (int c : object) grid_.cells[c] = OccupancyGrid::kFree;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int attempt = 0; attempt < kAttemptsPerEdit; ++attempt) {
      const double d = config_.move_min_m + (config_.move_max_m - config_.move_min_m) * unit(rng_);
      const double angle = 2.0 * M_PI * unit(rng_);
      const int dc = static_cast<int>(std::lround(d * std::cos(angle) / grid_.resolution_m));
      const int dr = -static_cast<int>(std::lround(d * std::sin(angle) / grid_.resolution_m));
      std::vector<int> moved;
      for (int cell : object) {
        const int row = cell / grid_.cols + dr, col = cell % grid_.cols + dc;
        if (!grid_.InBounds(row, col)) break;
        moved.push_back(row * grid_.cols + col);
      }
      bool overlaps = false;  // a cell both freed and occupied would not change
      for (int cell : moved) overlaps |= std::count(object.begin(), object.end(), cell) > 0;
      if (moved.size() != object.size() || overlaps || !Placeable(moved) ||
          PathDistance(Centre(moved), route_) < config_.distance_min_m) {
        continue;
      }
      Apply(SceneEdit::Kind::kObjectMoved, std::move(moved), object);
      return true;
    }
    for (int c : object) grid_.cells[c] = OccupancyGrid::kOccupied;
    return false;
  }

  // A random one of `doors` within reach_m of the route, no closer than `min_distance_m`, of
  // cells no edit touched yet; false when there is none.
  bool PickDoor(const std::vector<CellBox>& doors, double min_distance_m, SceneEdit::Kind kind) {
    std::vector<std::vector<int>> usable;
    for (const CellBox& box : doors) {
      std::vector<int> cells = box.Cells(grid_.cols);
      const double nearest = Nearest(cells);
      bool untouched = true;
      for (int c : cells) untouched &= !touched_[c];
      if (untouched && nearest <= config_.reach_m && nearest >= min_distance_m) {
        usable.push_back(std::move(cells));
      }
    }
    if (usable.empty()) return false;
    std::uniform_int_distribution<std::size_t> pick(0, usable.size() - 1);
    std::vector<int>& cells = usable[pick(rng_)];
    if (kind == SceneEdit::Kind::kDoorClosed) {
      Apply(kind, std::move(cells), {});
    } else {
      Apply(kind, {}, std::move(cells));
    }
    return true;
  }

  void Apply(SceneEdit::Kind kind, std::vector<int> occupied, std::vector<int> freed) {
    for (int c : freed) grid_.cells[c] = OccupancyGrid::kFree, touched_[c] = 1;
    for (int c : occupied) grid_.cells[c] = OccupancyGrid::kOccupied, touched_[c] = 1;
    const Point2 where = Centre(occupied.empty() ? freed : occupied);
    edits_.push_back({kind, where, std::move(occupied), std::move(freed)});
  }

  OccupancyGrid grid_;
  const std::vector<Point2>& route_;
  const SimSceneChangeConfig& config_;
  std::mt19937_64 rng_;
  std::vector<char> touched_;
  std::vector<float> distance_;
  std::vector<SceneEdit> edits_;
};

}  // namespace

int SceneChange::Count(SceneEdit::Kind kind) const {
  return static_cast<int>(std::count_if(edits.begin(), edits.end(),
                                        [&](const SceneEdit& e) { return e.kind == kind; }));
}

std::vector<float> DistanceToPath(const OccupancyGrid& grid, const std::vector<Point2>& path,
                                  double cap_m) {
  std::vector<float> distance(grid.cells.size(), static_cast<float>(cap_m));
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Point2& a = path[i];
    const Point2& b = path[std::min(i + 1, path.size() - 1)];
    // The cells of the segment's box grown by cap_m (corners through the grid's rotation).
    double r0 = grid.rows, r1 = 0, c0 = grid.cols, c1 = 0;
    for (double x : {std::min(a.x_m, b.x_m) - cap_m, std::max(a.x_m, b.x_m) + cap_m}) {
      for (double y : {std::min(a.y_m, b.y_m) - cap_m, std::max(a.y_m, b.y_m) + cap_m}) {
        double r = 0.0, c = 0.0;
        grid.WorldToCell({x, y}, &r, &c);
        r0 = std::min(r0, r), r1 = std::max(r1, r), c0 = std::min(c0, c), c1 = std::max(c1, c);
      }
    }
    const int row_end = std::min(grid.rows - 1, static_cast<int>(r1));
    const int col_end = std::min(grid.cols - 1, static_cast<int>(c1));
    for (int row = std::max(0, static_cast<int>(r0)); row <= row_end; ++row) {
      for (int col = std::max(0, static_cast<int>(c0)); col <= col_end; ++col) {
        float& d = distance[row * grid.cols + col];
        d = std::min(d, static_cast<float>(SegmentDistance(grid.CellCenter(row, col), a, b)));
      }
    }
  }
  return distance;
}

SceneChange DrawSceneChange(const OccupancyGrid& grid, const std::vector<Point2>& route,
                            const SimSceneChangeConfig& config, std::uint64_t seed) {
  Editor editor(grid, route, config, seed);
  editor.RemoveAndMoveObjects();
  editor.CloseDoors();
  editor.OpenDoors();
  editor.AddObjects();
  return editor.Result();
}

}  // namespace uwbsar::sim
