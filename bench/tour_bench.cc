// Building tours: the generated floors of config/maps/tours (office_block: a single 60 m ring
// whose only loops are at its start; office_block_sheared: the same 2 deg off square, for the
// right-angle prior) and tours on office and floor50, each mapped with the default
// configuration over several seeds. Reported per run: ring closed (SLAM ATE >= 3x better than
// odometry), ATE, odometry ATE, loops accepted / validated / candidates, false loops, recall per
// candidate with true overlap and per revisit (eval/tour/tour_eval.h), loops found by the per-radar
// pass (radar_match.h) and the keyframe thread's feature and matching time. Targets: every ring
// closes, 0 false loops, ATE <= 5 cm.
//
// Run by hand (about 1-2 minutes per run on 2 cores; not part of CI; entry 6 is the route of
// TourRunTest):
//   build/bin/uwbsar_bench --benchmark_filter=Tour
// UWBSAR_TOUR_SEEDS=N runs seeds 1..N (default 5; UWBSAR_TOUR_FIRST_SEED=K: K..K+N-1);
// UWBSAR_TOUR_CONFIG=FILE.yaml maps with that configuration instead of the defaults (for
// comparisons); UWBSAR_TOUR_VERBOSE=1 lists every validated loop. The base and the drive:
// UWBSAR_TOUR_SPEED=0.08 drives every route at that speed (simulator.route.speed_mps; 0.08:
// the slow tours of issue 44, 700 s and more each, about 3x the time per run);
// UWBSAR_TOUR_BASE=wheel simulates a wheel-only base and maps it with backend.odometry_model
// wheel (gyro: the kobuki_gyro base and the gyro model, the defaults);
// UWBSAR_TOUR_BIAS_SIGMAS=3 fixes the gyro's turn-on bias at +3 sigma on every seed
// (simulator.odometry.gyro.turn_on_bias_sigmas). With a gyro base each run also prints its
// true gyro bias beside the estimate (eval/tour/gyro_bias_eval.h).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "app/app_config_io.h"
#include "eval/tour/gyro_bias_eval.h"
#include "eval/tour/tour_eval.h"

namespace uwbsar {
namespace {

struct Tour {
  const char* name;
  const char* map;
  const char* route;
};

const std::vector<Tour>& Tours() {
  static const std::vector<Tour> tours = {
      {"ring_offices", "tours/ring_offices.yaml", "tours/ring_offices_tour.txt"},
      {"hall_wing", "tours/hall_wing.yaml", "tours/hall_wing_tour.txt"},
      {"two_rings", "tours/two_rings.yaml", "tours/two_rings_tour.txt"},
      {"office", "office/office.yaml", "office/route_loops.txt"},
      {"floor50", "floor50/floor50.yaml", "floor50/route_tour.txt"},
      {"office_block", "tours/office_block.yaml", "tours/office_block_tour.txt"},  // one ring
      {"two_rings_west", "tours/two_rings.yaml", "tours/two_rings_west.txt"},      // TourRunTest
      {"office_block_sheared", "tours/office_block_sheared.yaml",  // 2 deg off square
       "tours/office_block_sheared_tour.txt"},
  };
  return tours;
}

std::string MapsFile(const std::string& name) {
  return std::string(UWBSAR_SOURCE_DIR) + "/config/maps/" + name;
}

/// The base and drive of the UWBSAR_TOUR_SPEED, _BASE and _BIAS_SIGMAS variables, over `config`.
Config WithTourBase(Config config) {
  if (const char* speed = std::getenv("UWBSAR_TOUR_SPEED")) {
    config.simulator.route.speed_mps = std::atof(speed);
  }
  if (const char* base = std::getenv("UWBSAR_TOUR_BASE")) {
    const bool wheel = std::string(base) == "wheel";
    config.simulator.odometry.profile = wheel ? "wheel" : "kobuki_gyro";
    config.backend.odometry_model = wheel ? OdometryModel::kWheel : OdometryModel::kGyro;
  }
  if (const char* sigmas = std::getenv("UWBSAR_TOUR_BIAS_SIGMAS")) {
    config.simulator.odometry.gyro.turn_on_bias_sigmas = std::atof(sigmas);
  }
  ValidateConfig(config, "the UWBSAR_TOUR_* variables");
  const std::optional<double> sigmas = config.simulator.odometry.gyro.turn_on_bias_sigmas;
  char gyro[80] = "";  // a wheel base has none
  if (config.simulator.odometry.profile != "wheel" && sigmas) {
    std::snprintf(gyro, sizeof(gyro), ", gyro turn-on bias at %+g sigma", *sigmas);
  } else if (config.simulator.odometry.profile != "wheel") {
    std::snprintf(gyro, sizeof(gyro), ", gyro turn-on bias drawn per seed");
  }
  std::printf("tours: %s base, %.3f m/s%s\n", config.simulator.odometry.profile.c_str(),
              config.simulator.route.speed_mps, gyro);
  return config;
}

void BM_Tour(benchmark::State& state) {
  const Tour& tour = Tours()[static_cast<std::size_t>(state.range(0))];
  const char* seeds_env = std::getenv("UWBSAR_TOUR_SEEDS");
  const int seeds = seeds_env ? std::atoi(seeds_env) : 5;
  const char* first_env = std::getenv("UWBSAR_TOUR_FIRST_SEED");
  const int first_seed = first_env ? std::atoi(first_env) : 1;
  const char* config_env = std::getenv("UWBSAR_TOUR_CONFIG");
  Config config = WithTourBase(config_env ? LoadConfig(config_env) : Config{});
  config.simulator.route.clearance_m = 0.3;  // every route keeps 0.45 m from obstacles
  for (auto _ : state) {
    int closed = 0, false_loops = 0, overlap = 0, overlap_accepted = 0, revisits = 0, recalled = 0;
    double worst_ate_m = 0.0;
    for (int seed = first_seed; seed < first_seed + seeds; ++seed) {
      const slam::MapRun run =
          slam::MapSimulation(config, MapsFile(tour.map), MapsFile(tour.route), seed);
      const eval::TourEvaluation e = eval::EvaluateTour(run);
      const slam::StageTimes times = run.slam->times();
      int by_radar = 0;
      for (const slam::LoopRecord& l : run.slam->loops()) by_radar += l.accepted() && l.by_radar;
      std::printf(
          "%s seed %d: %s; %d loops by radar; %d right-angle priors (walls' spread %.2f deg); "
          "features %.1f s, matching %.1f s\n",
          tour.name, seed, eval::FormatTourEvaluation(e).c_str(), by_radar,
          run.slam->graph().RightAnglePriors(), run.slam->graph().BuildingSpreadDeg(),
          times.features_s, times.matching_s);
      const eval::GyroBiasEvaluation bias = eval::EvaluateGyroBias(run, config, seed);
      if (bias.segments > 0) std::printf("  %s\n", eval::FormatGyroBiasEvaluation(bias).c_str());
      for (const auto& [trajectory, c] : run.slam->graph().OdometryCalibrations()) {
        std::printf(
            "  odometry calibration: scale %+.4f, heading drift %+.5f rad/m, rotation %+.4f\n",
            c[0], c[1], c[2]);
      }
      if (std::getenv("UWBSAR_TOUR_VERBOSE")) {
        for (const slam::LoopRecord& l : run.slam->loops()) {
          if (!l.validation.accepted) continue;
          std::printf("  loop %d -> %d%s%s: akaze %d orb %d, backend %s chi2 %.2f\n", l.match_id,
                      l.query_id, l.guided ? " guided" : "", l.by_radar ? " by radar" : "",
                      l.Match(DetectorKind::kAkaze).good_matches,
                      l.Match(DetectorKind::kOrb).good_matches,
                      l.rejected_by_backend ? "rejected" : "accepted", l.chi2);
        }
      }
      std::fflush(stdout);
      closed += e.ring_closed;
      false_loops += e.false_accepted;
      worst_ate_m = std::max(worst_ate_m, e.ate_m);
      overlap += e.overlap_candidates;
      overlap_accepted += e.overlap_accepted;
      revisits += e.revisits;
      recalled += e.revisits_recalled;
    }
    std::printf(
        "%s: %d/%d rings closed, %d false loops, worst ATE %.2f cm, recall %.2f of "
        "candidates, %.2f of revisits\n",
        tour.name, closed, seeds, false_loops, worst_ate_m * 100,
        overlap ? double(overlap_accepted) / overlap : 0.0,
        revisits ? double(recalled) / revisits : 0.0);
    state.counters["closed"] = closed;
    state.counters["false"] = false_loops;
    state.counters["worst_ate_cm"] = worst_ate_m * 100;
  }
}
BENCHMARK(BM_Tour)->DenseRange(0, 7)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace uwbsar
