// Workday benchmark (issue "a working day on one building"): the same place driven again and
// again in one run, streamed from the simulator into SlamSystem in memory. Memory, session size
// and time per metre must follow the area mapped, not the hours driven
// (slam/session/place_views.h).
//
//   BM_WorkdayOfficeRing: the office ring (config/maps/office: 14,9 -> 4,9 -> 4,4 -> 16,4 ->
//     16,9 -> 14,9, 34 m) driven 10 times, seed 3.
//   BM_WorkdayFloor50: floor50's 1 km route driven 5 times (forward, back, forward, back,
//     forward: the route does not end where it starts), seed 1.
//
// Run by hand (the ring about 2 minutes, floor50 about an hour on 2 cores; not part of CI):
//   build/bin/uwbsar_bench --benchmark_filter=Workday
// A table on stdout gives, per lap, the SLAM time per metre by stage (wall clock), the process's
// CPU time per metre (steady under a changing load), keyframes kept and retired, loops
// accepted, VmRSS, the session's size if saved then, the lap's ATE, and the map a live run
// would write every 3 m on the ring (a 10 s snapshot), every 25 m on floor50: the mean kept-mosaic
// update of the lap against rendering every tile at the same moments. The bench's own work
// (renders, session writes) is left out of the CPU time.
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "backend/global_map.h"
#include "backend/incremental_mosaic.h"
#include "bench/resident_memory.h"
#include "slam/app_config.h"
#include "slam/map_job.h"
#include "slam/outputs/session_capture.h"
#include "slam/session/session_file.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;

std::string MapFile(const std::string& name) {
  return std::string(UWBSAR_SOURCE_DIR) + "/config/maps/" + name;
}

/// The waypoints of `laps` passes of `lap` (each pass reversed after a forward one when
/// `alternate`), as a route file in a temporary folder.
std::string WriteRoute(const std::vector<Point2>& lap, int laps, bool alternate,
                       const std::string& name) {
  const fs::path path = fs::temp_directory_path() / ("uwbsar_workday_" + name + ".txt");
  std::ofstream out(path);
  out << lap.front().x_m << ' ' << lap.front().y_m << '\n';
  for (int k = 0; k < laps; ++k) {
    std::vector<Point2> pass = lap;
    if (alternate && k % 2 == 1) pass.assign(lap.rbegin(), lap.rend());
    for (std::size_t i = 1; i < pass.size(); ++i) out << pass[i].x_m << ' ' << pass[i].y_m << '\n';
  }
  return path.string();
}

std::vector<Point2> ReadWaypoints(const std::string& path) {
  std::ifstream in(path);
  std::vector<Point2> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    Point2 p;
    if (std::sscanf(line.c_str(), "%lf %lf", &p.x_m, &p.y_m) == 2) out.push_back(p);
  }
  return out;
}

struct LapSample {
  double path_m = 0.0;
  TimestampNs stamp_ns = 0;
  slam::StageTimes times;
  std::size_t keyframes = 0, retired = 0;
  int accepted = 0;
  double rss_mib = 0.0;
  double session_mib = 0.0;
  double process_cpu_s = 0.0;         ///< CPU time of the whole process (simulator included)
  int snapshots = 0;                  ///< live-like map updates during the lap
  double mosaic_update_ms = 0.0;      ///< kept-mosaic updates of the lap, summed
  double mosaic_update_ms_max = 0.0;  ///< the slowest of them
  double mosaic_full_ms = 0.0;        ///< the whole map rendered from every tile, summed
  MosaicUpdate mosaic;                ///< what the kept-mosaic updates redid, summed
};

std::vector<MosaicTile> MosaicTiles(const slam::MapState& state) {
  std::vector<MosaicTile> tiles;
  for (const slam::TileSnapshot& k : state.slam.tiles) {
    tiles.push_back(
        {k.id, state.slam.poses.at(k.id), k.detected_grid, [&k] { return k.detected.Load(); }});
  }
  return tiles;
}

double MillisecondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// CPU seconds the process (or this thread) has used: unlike the stage times (wall clock), it
/// does not move with the machine's load, so a long run's first and last laps compare on a
/// shared machine.
double CpuSeconds(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Counts the feeding thread's CPU time spent on the bench's own measurements (map renders,
/// session writes) while alive, so that the run's CPU time per metre leaves it out.
class BenchWork {
 public:
  explicit BenchWork(double* total_s) : total_s_(total_s), t0_(Now()) {}
  ~BenchWork() { *total_s_ += Now() - t0_; }

 private:
  static double Now() { return CpuSeconds(CLOCK_THREAD_CPUTIME_ID); }
  double* total_s_;
  double t0_;
};

double Total(const slam::StageTimes& t) {
  return t.imaging_s + t.features_s + t.matching_s + t.optimization_s;
}

/// Maps `route`, sampling at every lap boundary (`lap_m` of odometry path); every keyframe's
/// true anchor is kept as it appears, so loops to keyframes retired later can still be judged.
slam::MapRun RunLaps(const Config& config, const std::string& map, const std::string& route,
                     std::uint64_t seed, double lap_m, double snapshot_every_m,
                     std::vector<LapSample>* laps, std::map<int, Pose2>* true_anchor) {
  std::vector<OdometrySample> truth;
  long long truth_seen = 0;
  IncrementalMosaic mosaic(config.slam.map_resolution_m, config.slam.mosaic_redraw_px);
  double next_snapshot_m = snapshot_every_m;
  LapSample lap_snapshots;   // this lap's snapshot figures so far
  double bench_cpu_s = 0.0;  // CPU time of the measurements themselves
  const fs::path session = fs::temp_directory_path() / "uwbsar_workday_session.uwbsar";
  slam::MapRun run = slam::MapSimulation(config, map, route, seed, [&](slam::MapRun* r) {
    for (const OdometrySample& g : r->ground_truth) {
      if (truth_seen++ % 4 == 0) truth.push_back(g);  // 50 Hz of the 200 Hz truth
    }
    r->ground_truth.clear();
    const auto state = r->slam->LockState();
    const auto& odometry = r->slam->odometry();
    if (odometry.empty() || truth.empty()) return;
    for (const slam::KeyframeRecord& k : r->slam->keyframes()) {
      if (true_anchor->count(k.keyframe.id)) continue;
      auto it =
          std::lower_bound(truth.begin(), truth.end(), k.keyframe.stamp_ns,
                           [](const OdometrySample& g, TimestampNs t) { return g.stamp_ns < t; });
      if (it == truth.end()) --it;
      (*true_anchor)[k.keyframe.id] =
          it->T_world_robot * (k.keyframe.T_world_robot.Inverse() * k.keyframe.T_world_anchor);
    }
    const double path_m = odometry.back().path_m;
    if (path_m >= next_snapshot_m && !r->slam->keyframes().empty()) {
      // What a live snapshot does to the map (slam/live/live_processor.cc): the kept mosaic
      // brought up to date, only what changed redrawn.
      // Against rendering every tile at the same moment.
      const BenchWork counted(&bench_cpu_s);
      next_snapshot_m = path_m + snapshot_every_m;
      const slam::MapState now = slam::CaptureMapState(*r);
      auto t0 = std::chrono::steady_clock::now();
      const MosaicUpdate u = mosaic.Update(MosaicTiles(now));
      lap_snapshots.mosaic.added += u.added;
      lap_snapshots.mosaic.removed += u.removed;
      lap_snapshots.mosaic.moved += u.moved;
      lap_snapshots.mosaic.tiles_drawn += u.tiles_drawn;
      lap_snapshots.mosaic.blocks_redone += u.blocks_redone;
      const double update_ms = MillisecondsSince(t0);
      lap_snapshots.mosaic_update_ms += update_ms;
      lap_snapshots.mosaic_update_ms_max = std::max(lap_snapshots.mosaic_update_ms_max, update_ms);
      t0 = std::chrono::steady_clock::now();
      GlobalMap full(config.slam.map_resolution_m);
      for (const MosaicTile& t : MosaicTiles(now)) full.AddTile(t.load(), t.grid, t.T_world_tile);
      lap_snapshots.mosaic_full_ms += MillisecondsSince(t0);
      ++lap_snapshots.snapshots;
    }
    if (path_m < lap_m * static_cast<double>(laps->size() + 1)) return;
    const BenchWork counted(&bench_cpu_s);
    LapSample s = lap_snapshots;
    lap_snapshots = LapSample();
    s.path_m = path_m;
    s.stamp_ns = odometry.back().stamp_ns;
    s.times = r->slam->times();
    s.keyframes = r->slam->keyframes().size();
    s.retired = r->slam->retired().size();
    for (const slam::LoopRecord& l : r->slam->loops()) s.accepted += l.validation.accepted;
    s.rss_mib = ResidentMiB();
    s.process_cpu_s = CpuSeconds(CLOCK_PROCESS_CPUTIME_ID) - bench_cpu_s;
    WriteSession(session.string(), slam::CaptureSession(*r));
    s.session_mib = static_cast<double>(fs::file_size(session)) / (1 << 20);
    laps->push_back(s);
    // As it goes (a long run read while it runs): the final table adds time and ATE per lap.
    std::fprintf(
        stderr,
        "lap %zu done: %.1f m, %zu kept, %zu retired, %d loops, %.0f MiB, "
        "session %.2f MiB, SLAM %.1f s, CPU %.0f s, %d map updates: kept mosaic %.0f ms "
        "(max %.0f; %zu added, %zu retired, %zu moved, %zu drawn, %zu blocks redone), every "
        "tile %.0f ms\n",
        laps->size(), s.path_m, s.keyframes, s.retired, s.accepted, s.rss_mib, s.session_mib,
        Total(s.times), s.process_cpu_s, s.snapshots, s.mosaic_update_ms / std::max(1, s.snapshots),
        s.mosaic_update_ms_max, s.mosaic.added, s.mosaic.removed, s.mosaic.moved,
        s.mosaic.tiles_drawn, s.mosaic.blocks_redone, s.mosaic_full_ms / std::max(1, s.snapshots));
  });
  fs::remove(session);
  run.ground_truth = std::move(truth);
  return run;
}

/// Accepted loops, and those more than 0.2 m or 5 deg from the truth.
std::pair<int, int> CountLoops(const slam::MapRun& run, const std::map<int, Pose2>& true_anchor) {
  int accepted = 0, false_accepted = 0;
  for (const slam::LoopRecord& l : run.slam->loops()) {
    if (!l.accepted()) continue;
    ++accepted;
    auto a = true_anchor.find(l.match_id), b = true_anchor.find(l.query_id);
    if (a == true_anchor.end() || b == true_anchor.end()) continue;
    const Pose2 truth = Between(a->second, b->second);
    const Pose2& T = l.validation.constraint.T_ij;
    false_accepted += std::hypot(T.x_m - truth.x_m, T.y_m - truth.y_m) > 0.2 ||
                      std::abs(NormalizeAngle(T.yaw_rad - truth.yaw_rad)) > 5.0 * M_PI / 180.0;
  }
  return {accepted, false_accepted};
}

/// `snapshot_every_m`: the map a live run would write, every this many metres (kept mosaic and
/// full render, both timed; the bench's own CPU time, left out of the run's).
void RunWorkday(benchmark::State& state, const std::string& map, const std::string& route,
                std::uint64_t seed, int num_laps, double snapshot_every_m) {
  const Config config;
  mallopt(M_ARENA_MAX, 2);  // as the uwbsar program does (tools/main.cc)
  for (auto _ : state) {
    // The lap's length: the route's polyline over the number of laps (corners are rounded when
    // driven, so a lap's sample comes a little after its end).
    const std::vector<Point2> w = ReadWaypoints(route);
    double route_m = 0.0;
    for (std::size_t i = 1; i < w.size(); ++i)
      route_m += std::hypot(w[i].x_m - w[i - 1].x_m, w[i].y_m - w[i - 1].y_m);
    const double lap_m = 0.98 * route_m / num_laps;
    std::vector<LapSample> laps;
    std::map<int, Pose2> true_anchor;
    const slam::MapRun run =
        RunLaps(config, map, route, seed, lap_m, snapshot_every_m, &laps, &true_anchor);
    if (laps.size() < 2) {
      state.SkipWithError("fewer than two laps sampled");
      return;
    }
    const std::vector<std::pair<TimestampNs, Pose2>> corrected = run.slam->CorrectedTrajectory();
    std::printf("%4s %8s %8s %8s %8s %8s %8s %8s %6s %7s %7s %8s %8s %7s %9s %8s\n", "lap",
                "path_m", "ms/m", "imaging", "features", "matching", "optimise", "cpu_ms/m", "kept",
                "retired", "loops", "RSS_MiB", "sess_MiB", "ate_cm", "upd_ms", "full_ms");
    LapSample previous;
    std::vector<double> ms_per_m, cpu_ms_per_m, ate_cm;
    for (std::size_t i = 0; i < laps.size(); ++i) {
      const LapSample& s = laps[i];
      const double m = s.path_m - previous.path_m;
      std::vector<std::pair<TimestampNs, Pose2>> lap;
      for (const auto& p : corrected) {
        if (p.first > previous.stamp_ns && p.first <= s.stamp_ns) lap.push_back(p);
      }
      const double ate = slam::TrajectoryError(lap, run.ground_truth).rmse_m * 100.0;
      ms_per_m.push_back((Total(s.times) - Total(previous.times)) / m * 1e3);
      cpu_ms_per_m.push_back((s.process_cpu_s - previous.process_cpu_s) / m * 1e3);
      ate_cm.push_back(ate);
      std::printf(
          "%4zu %8.1f %8.1f %8.1f %8.1f %8.2f %8.2f %8.1f %6zu %7zu %7d %8.0f %8.2f %7.2f %9.0f "
          "%8.0f\n",
          i + 1, s.path_m, ms_per_m.back(),
          (s.times.imaging_s - previous.times.imaging_s) / m * 1e3,
          (s.times.features_s - previous.times.features_s) / m * 1e3,
          (s.times.matching_s - previous.times.matching_s) / m * 1e3,
          (s.times.optimization_s - previous.times.optimization_s) / m * 1e3, cpu_ms_per_m.back(),
          s.keyframes, s.retired, s.accepted, s.rss_mib, s.session_mib, ate,
          s.mosaic_update_ms / std::max(1, s.snapshots),
          s.mosaic_full_ms / std::max(1, s.snapshots));
      previous = s;
    }
    const auto [accepted, false_accepted] = CountLoops(run, true_anchor);
    state.counters["laps"] = static_cast<double>(laps.size());
    state.counters["travel_m"] = laps.back().path_m;
    state.counters["peak_rss_MiB"] = slam::PeakMemoryMiB();
    state.counters["rss_last_over_first_lap"] = laps.back().rss_mib / laps.front().rss_mib;
    state.counters["session_last_over_first_lap"] =
        laps.back().session_mib / laps.front().session_mib;
    state.counters["ms_per_m_last_over_first_lap"] = ms_per_m.back() / ms_per_m.front();
    state.counters["cpu_ms_per_m_last_over_first_lap"] = cpu_ms_per_m.back() / cpu_ms_per_m.front();
    state.counters["keyframes_kept"] = static_cast<double>(run.slam->keyframes().size());
    state.counters["keyframes_retired"] = static_cast<double>(run.slam->retired().size());
    state.counters["loops_accepted"] = accepted;
    state.counters["false_loops_accepted"] = false_accepted;
    state.counters["ate_cm"] = slam::TrajectoryError(corrected, run.ground_truth).rmse_m * 100.0;
    state.counters["first_lap_ate_cm"] = ate_cm.front();
    state.counters["last_lap_ate_cm"] = ate_cm.back();
  }
}

void BM_WorkdayOfficeRing(benchmark::State& state) {
  const std::vector<Point2> ring = {{14, 9}, {4, 9}, {4, 4}, {16, 4}, {16, 9}, {14, 9}};
  RunWorkday(state, MapFile("office/office.yaml"), WriteRoute(ring, 10, false, "office"), 3, 10,
             3.0);  // 10 s at 0.3 m/s
}
BENCHMARK(BM_WorkdayOfficeRing)->Unit(benchmark::kSecond)->Iterations(1);

void BM_WorkdayFloor50(benchmark::State& state) {
  const std::vector<Point2> lap = ReadWaypoints(MapFile("floor50/route_1km.txt"));
  RunWorkday(state, MapFile("floor50/floor50.yaml"), WriteRoute(lap, 5, true, "floor50"), 1, 5,
             25.0);  // the full render of 500 keyframes every 3 m would triple the run
}
BENCHMARK(BM_WorkdayFloor50)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace uwbsar
