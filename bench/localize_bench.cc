// Localisation in a changed building over several tours and change seeds (the acceptance of
// changed_building_test.cc, whole): each tour's day-1 map (seed 1); on day 2 the building changed
// (simulator.scene_change seed 1..N: objects added, removed and moved, a door closed and one
// opened), a person walks past, and the run starts a third of the way round in a moved and turned
// odometry frame. Reported per run (eval/tour/localization_eval.h): first fix, keyframes lost
// after it, registered, map-frame error against the day-1 map's own, false fixes, and the real-time
// factor (log time over processing time). Targets: fix within 5 m, <= 5 % lost, error <= the
// map's + 3 cm, worst pose <= 30 cm, no false fix.
//
// Run by hand (a few minutes per tour on 2 cores; not part of CI):
//   build/bin/uwbsar_bench --benchmark_filter=LocalizeChangedBuilding
// UWBSAR_LOCALIZE_SEEDS=N: change seeds 1..N (default 5); UWBSAR_LOCALIZE_CONFIG=FILE.yaml: the
// robot's configuration (e.g. a calibration file from `uwbsar calibrate`); UWBSAR_LOCALIZE_
// REGISTRATION=0: registration against the map off (loops and walls alone, for comparison);
// UWBSAR_LOCALIZE_UNCHANGED=1: the day-2 building unchanged and nobody walking;
// UWBSAR_LOCALIZE_OBJECTS=N: N objects added instead of simulator.scene_change.objects_added (6;
// the real buildings had 18 and 44 on 62-70 m).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "app/app_config_io.h"
#include "eval/tour/localization_eval.h"
#include "slam/localization/localize_job.h"
#include "slam/outputs/session_capture.h"

namespace uwbsar {
namespace {

struct LocalizeTour {
  const char* name;
  const char* map;
  const char* route;
};

const LocalizeTour kTours[] = {
    {"hall_wing", "tours/hall_wing.yaml", "tours/hall_wing_tour.txt"},
    {"ring_offices", "tours/ring_offices.yaml", "tours/ring_offices_tour.txt"},
    {"two_rings", "tours/two_rings.yaml", "tours/two_rings_tour.txt"},
};

std::string MapsFile(const std::string& name) {
  return std::string(UWBSAR_SOURCE_DIR) + "/config/maps/" + name;
}

bool EnvIs(const char* name, const char* value) {
  const char* v = std::getenv(name);
  return v != nullptr && std::string(v) == value;
}

void BM_LocalizeChangedBuilding(benchmark::State& state) {
  const LocalizeTour& tour = kTours[state.range(0)];
  const char* seeds_env = std::getenv("UWBSAR_LOCALIZE_SEEDS");
  const int seeds = seeds_env ? std::atoi(seeds_env) : 5;
  const char* config_env = std::getenv("UWBSAR_LOCALIZE_CONFIG");
  Config config = config_env ? LoadConfig(config_env) : Config{};
  config.simulator.route.clearance_m = 0.3;
  if (EnvIs("UWBSAR_LOCALIZE_REGISTRATION", "0")) {
    config.place_recognition.registration.enabled = false;
  }
  const bool unchanged = EnvIs("UWBSAR_LOCALIZE_UNCHANGED", "1");
  const std::string dir =
      (std::filesystem::temp_directory_path() / "uwbsar_localize_bench").string();
  std::filesystem::create_directories(dir);
  const std::string route = dir + "/" + tour.name + "_day2.txt";
  eval::WriteRouteTail(MapsFile(tour.route), 1.0 / 3.0, route);
  for (auto _ : state) {
    const slam::MapRun day1 =
        slam::MapSimulation(config, MapsFile(tour.map), MapsFile(tour.route), /*seed=*/1);
    const SessionData map = slam::CaptureSession(day1);
    const double map_error_m = eval::MapFrameError(day1).rmse_m;
    const char* objects = std::getenv("UWBSAR_LOCALIZE_OBJECTS");
    std::printf(
        "%s: day-1 map-frame error %.2f cm; registration %s; building %s (%s objects added)\n",
        tour.name, map_error_m * 100, config.place_recognition.registration.enabled ? "on" : "off",
        unchanged ? "unchanged" : "changed, one person walking",
        unchanged ? "no"
        : objects ? objects
                  : "6");
    double worst_fix_m = 0.0, worst_lost = 0.0, worst_excess_m = -1.0, worst_max_m = 0.0;
    int never = 0, false_fixes = 0;
    for (int change = 1; change <= seeds; ++change) {
      Config day2 = config;
      if (!unchanged) {
        day2.simulator.scene_change.seed = static_cast<std::uint64_t>(change);
        day2.simulator.people.count = 1;
        if (const char* objects = std::getenv("UWBSAR_LOCALIZE_OBJECTS")) {
          day2.simulator.scene_change.objects_added = std::atoi(objects);
        }
      }
      const slam::LocalizeRun run = slam::LocalizeSimulation(
          map, day2, MapsFile(tour.map), route, /*scene_seed=*/1,
          /*seed=*/10 + static_cast<std::uint64_t>(change), {4.0, -3.0, 1.0});
      const eval::LocalizationEvaluation e = eval::EvaluateLocalization(run);
      std::printf("  change seed %d: %s; real-time factor %.1f\n", change,
                  eval::FormatLocalizationEvaluation(e).c_str(),
                  run.processing_s > 0 ? run.log_duration_s / run.processing_s : 0.0);
      std::fflush(stdout);
      if (!e.placed) {
        ++never;
        continue;
      }
      worst_fix_m = std::max(worst_fix_m, e.first_fix_path_m);
      worst_lost = std::max(worst_lost, e.after_fix > 0 ? 1.0 * e.lost_after_fix / e.after_fix : 0);
      worst_excess_m = std::max(worst_excess_m, e.rmse_m - map_error_m);
      worst_max_m = std::max(worst_max_m, e.max_m);
      false_fixes += e.false_fixes;
    }
    state.counters["never_placed"] = never;
    state.counters["worst_fix_m"] = worst_fix_m;
    state.counters["worst_lost_fraction"] = worst_lost;
    state.counters["worst_rmse_over_map_cm"] = worst_excess_m * 100;
    state.counters["worst_pose_cm"] = worst_max_m * 100;
    state.counters["false_fixes"] = false_fixes;
  }
}
BENCHMARK(BM_LocalizeChangedBuilding)->DenseRange(0, 2)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace uwbsar
