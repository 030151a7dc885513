// What a robot team asks of map.pgm (issue 29), as checks the acceptance tests share: the
// cells the robot swept are free; no free cell lies where the ground-truth grid has a wall or
// cannot be seen from the path; an A* planner with the robot's radius finds the route on it
// and never crosses a ground-truth wall. The SLAM map frame is the simulator's world frame
// (the odometry starts at the true start pose), so both grids are compared where they lie.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <queue>
#include <sstream>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar::testing {

struct SweptFigures {
  int swept = 0;  ///< cells whose centre lies within the radius of a path pose
  int free = 0;   ///< of them, free in the map
  double fraction() const { return swept > 0 ? static_cast<double>(free) / swept : 0.0; }
};

inline SweptFigures SweptFree(const OccupancyGrid& map, const std::vector<Pose2>& path,
                              double radius_m) {
  std::vector<std::uint8_t> swept(map.cells.size(), 0);
  const int reach = static_cast<int>(std::ceil(radius_m / map.resolution_m)) + 1;
  for (const Pose2& p : path) {
    int row = 0, col = 0;
    double fr = 0, fc = 0;
    map.WorldToCell({p.x_m, p.y_m}, &fr, &fc);
    row = static_cast<int>(std::floor(fr)), col = static_cast<int>(std::floor(fc));
    for (int r = row - reach; r <= row + reach; ++r) {
      for (int c = col - reach; c <= col + reach; ++c) {
        if (!map.InBounds(r, c)) continue;
        const Point2 centre = map.CellCenter(r, c);
        if (std::hypot(centre.x_m - p.x_m, centre.y_m - p.y_m) <= radius_m) {
          swept[static_cast<std::size_t>(r) * map.cols + c] = 1;
        }
      }
    }
  }
  SweptFigures f;
  for (std::size_t i = 0; i < swept.size(); ++i) {
    if (!swept[i]) continue;
    ++f.swept;
    f.free += map.cells[i] >= 0 && map.cells[i] < OccupancyGrid::kOccupiedMinValue;
  }
  return f;
}

/// Cells of `truth` a ray from a pose of `path` (every 0.5 deg, up to `range_m`) reaches
/// through free cells: what the path can see. Occupied and unknown cells stop a ray.
inline std::vector<std::uint8_t> VisibleFromPath(const OccupancyGrid& truth,
                                                 const std::vector<Pose2>& path, double range_m) {
  std::vector<std::uint8_t> seen(truth.cells.size(), 0);
  const double step = 0.5 * truth.resolution_m;
  Point2 last{1e300, 1e300};
  for (const Pose2& p : path) {
    if (std::hypot(p.x_m - last.x_m, p.y_m - last.y_m) < 0.05) continue;
    last = {p.x_m, p.y_m};
    for (int a = 0; a < 720; ++a) {
      const double dx = std::cos(a * M_PI / 360.0), dy = std::sin(a * M_PI / 360.0);
      for (double r = 0.0; r <= range_m; r += step) {
        int row = 0, col = 0;
        if (!truth.CellOf({p.x_m + r * dx, p.y_m + r * dy}, &row, &col) ||
            !truth.IsFree(row, col)) {
          break;
        }
        seen[static_cast<std::size_t>(row) * truth.cols + col] = 1;
      }
    }
  }
  return seen;
}

struct BehindWallFigures {
  int free = 0;          ///< free cells of the map
  int bad = 0;           ///< of them, occupied or not visible from the path in the truth
  int bad_occupied = 0;  ///< of those, occupied in the truth
  double fraction() const { return free > 0 ? static_cast<double>(bad) / free : 0.0; }
};

/// Our free cells against the truth seen from the true path `truth_path`.
inline BehindWallFigures FreeBehindWalls(const OccupancyGrid& map, const OccupancyGrid& truth,
                                         const std::vector<Pose2>& truth_path, double range_m) {
  const std::vector<std::uint8_t> seen = VisibleFromPath(truth, truth_path, range_m);
  BehindWallFigures f;
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.cols; ++c) {
      if (!map.IsFree(r, c)) continue;
      ++f.free;
      int tr = 0, tc = 0;
      if (!truth.CellOf(map.CellCenter(r, c), &tr, &tc)) {
        ++f.bad;
        continue;
      }
      if (truth.IsOccupied(tr, tc)) ++f.bad_occupied;
      if (!seen[static_cast<std::size_t>(tr) * truth.cols + tc]) ++f.bad;
    }
  }
  return f;
}

/// A* on `map`, 8-connected, through free cells farther than `robot_radius_m` from every
/// occupied cell (unknown cells are not entered). The cell centres of the path from `start`
/// to `goal`, or empty when there is none.
inline std::vector<Point2> PlanPath(const OccupancyGrid& map, const Point2& start,
                                    const Point2& goal, double robot_radius_m) {
  const int n = map.rows * map.cols;
  std::vector<std::uint8_t> passable(static_cast<std::size_t>(n), 0);
  for (int i = 0; i < n; ++i) passable[i] = map.IsFree(i / map.cols, i % map.cols);
  const int reach = static_cast<int>(std::ceil(robot_radius_m / map.resolution_m));
  for (int r = 0; r < map.rows; ++r) {  // inflate the obstacles by the robot's radius
    for (int c = 0; c < map.cols; ++c) {
      if (!map.IsOccupied(r, c)) continue;
      for (int dr = -reach; dr <= reach; ++dr) {
        for (int dc = -reach; dc <= reach; ++dc) {
          if (map.InBounds(r + dr, c + dc) &&
              std::hypot(dr, dc) * map.resolution_m <= robot_radius_m) {
            passable[static_cast<std::size_t>((r + dr) * map.cols + c + dc)] = 0;
          }
        }
      }
    }
  }
  int sr = 0, sc = 0, gr = 0, gc = 0;
  if (!map.CellOf(start, &sr, &sc) || !map.CellOf(goal, &gr, &gc)) return {};
  const int s = sr * map.cols + sc, g = gr * map.cols + gc;
  if (!passable[s] || !passable[g]) return {};
  std::vector<double> cost(static_cast<std::size_t>(n), 1e300);
  std::vector<int> parent(static_cast<std::size_t>(n), -1);
  auto h = [&](int i) { return std::hypot(i / map.cols - gr, i % map.cols - gc); };
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  cost[s] = 0.0;
  open.push({h(s), s});
  while (!open.empty()) {
    const auto [f, i] = open.top();
    open.pop();
    if (i == g) break;
    if (f > cost[i] + h(i) + 1e-9) continue;
    const int r = i / map.cols, c = i % map.cols;
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        if ((dr == 0 && dc == 0) || !map.InBounds(r + dr, c + dc)) continue;
        const int j = (r + dr) * map.cols + c + dc;
        // A diagonal step may not cut the corner of a blocked cell.
        if (!passable[j] || !passable[r * map.cols + c + dc] ||
            !passable[(r + dr) * map.cols + c]) {
          continue;
        }
        const double next = cost[i] + std::hypot(dr, dc);
        if (next < cost[j]) {
          cost[j] = next;
          parent[j] = i;
          open.push({next + h(j), j});
        }
      }
    }
  }
  if (parent[g] < 0 && g != s) return {};
  std::vector<Point2> path;
  for (int i = g; i >= 0; i = parent[i]) path.push_back(map.CellCenter(i / map.cols, i % map.cols));
  std::reverse(path.begin(), path.end());
  return path;
}

/// True when a segment of `path` passes through an occupied cell of `truth` (sampled every
/// quarter cell).
inline bool CrossesWall(const OccupancyGrid& truth, const std::vector<Point2>& path) {
  const double step = 0.25 * truth.resolution_m;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const Point2& a = path[i - 1];
    const Point2& b = path[i];
    const double length = std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
    for (double t = 0.0; t <= length; t += step) {
      const double u = length > 0 ? t / length : 0.0;
      int r = 0, c = 0;
      if (truth.CellOf({a.x_m + u * (b.x_m - a.x_m), a.y_m + u * (b.y_m - a.y_m)}, &r, &c) &&
          truth.IsOccupied(r, c)) {
        return true;
      }
    }
  }
  return false;
}

/// The pose of `path` farthest from its first one.
inline Pose2 FarthestFromStart(const std::vector<Pose2>& path) {
  Pose2 best = path.front();
  double best_m = -1.0;
  for (const Pose2& p : path) {
    const double d = std::hypot(p.x_m - path.front().x_m, p.y_m - path.front().y_m);
    if (d > best_m) best_m = d, best = p;
  }
  return best;
}

/// The poses of a TUM file (t x y z qx qy qz qw; yaw from the quaternion).
inline std::vector<Pose2> ReadTumPoses(const std::string& path) {
  std::ifstream in(path);
  std::vector<Pose2> poses;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    double t, x, y, z, qx, qy, qz, qw;
    if (s >> t >> x >> y >> z >> qx >> qy >> qz >> qw) {
      poses.push_back({x, y, 2.0 * std::atan2(qz, qw)});
    }
  }
  return poses;
}

/// Every acceptance figure of issue 29 for one run, printed and asserted: `map` (our map.pgm)
/// against `truth` (the simulator's grid), `slam_path` the corrected trajectory (map frame),
/// `truth_path` the true one.
inline void ExpectNavigationMap(const char* name, const OccupancyGrid& map,
                                const OccupancyGrid& truth, const std::vector<Pose2>& slam_path,
                                const std::vector<Pose2>& truth_path) {
  constexpr double kRobotRadiusM = 0.2;
  ASSERT_FALSE(slam_path.empty());
  ASSERT_FALSE(truth_path.empty());
  const SweptFigures swept = SweptFree(map, slam_path, kRobotRadiusM);
  // 3.5 m: the radars' reach (3 m from antennas 0.18 m off the centre) and a margin.
  const BehindWallFigures behind = FreeBehindWalls(map, truth, truth_path, 3.5);
  const Point2 start{slam_path.front().x_m, slam_path.front().y_m};
  const Pose2 far = FarthestFromStart(slam_path);
  const std::vector<Point2> plan = PlanPath(map, start, {far.x_m, far.y_m}, kRobotRadiusM);
  double plan_m = 0.0;
  for (std::size_t i = 1; i < plan.size(); ++i) {
    plan_m += std::hypot(plan[i].x_m - plan[i - 1].x_m, plan[i].y_m - plan[i - 1].y_m);
  }
  std::printf(
      "%s navigation grid: swept cells free %d / %d = %.2f %%; free cells behind walls %d / %d = "
      "%.2f %% (%d on a wall); A* start -> farthest point (%.2f m away): %s, %.2f m%s\n",
      name, swept.free, swept.swept, 100.0 * swept.fraction(), behind.bad, behind.free,
      100.0 * behind.fraction(), behind.bad_occupied,
      std::hypot(far.x_m - start.x_m, far.y_m - start.y_m), plan.empty() ? "none" : "found", plan_m,
      !plan.empty() && CrossesWall(truth, plan) ? ", CROSSES A WALL" : "");
  EXPECT_GE(swept.fraction(), 0.99) << name;
  EXPECT_LE(behind.fraction(), 0.01) << name;
  EXPECT_GT(behind.free, swept.swept) << name << ": the radars free more than the footprint";
  ASSERT_FALSE(plan.empty()) << name << ": A* found no path";
  EXPECT_FALSE(CrossesWall(truth, plan)) << name;
}

}  // namespace uwbsar::testing
