// Simulator benchmarks: a 15 m depart-return run in the bundled seed_hall room
// with two radars at 100 Hz, 1000 samples per scan, must simulate in well under a minute on one
// core. Reports seconds of simulation per metre of route.
#include <benchmark/benchmark.h>

#include <random>
#include <string>

#include "drivers/sim/radar_simulator.h"
#include "drivers/sim/sim_stream.h"
#include "slam/app_config.h"

namespace uwbsar {
namespace {

std::string SeedHallMap() {
  // This file is bench/sim_bench.cc in the source tree; the map is config/maps/seed_hall.
  const std::string here = __FILE__;
  return here.substr(0, here.rfind("/bench/")) + "/config/maps/seed_hall/seed_hall.yaml";
}

// The whole recording (ground truth 200 Hz, odometry 50 Hz, 2 radars at 100 Hz), in memory.
void BM_SimulateSeedHallDepartReturn(benchmark::State& state) {
  const Config config;
  double metres = 0.0;
  long long scans = 0;
  for (auto _ : state) {
    const sim::SimScenario scenario = sim::MakeScenario(config, SeedHallMap(), "depart-return", 1);
    sim::SimStream stream(config, scenario, 1);
    sim::SimMessage msg;
    while (stream.Next(&msg)) scans += msg.kind == sim::SimMessage::Kind::kRadarScan;
    metres += scenario.trajectory.length_m();
  }
  state.counters["s_per_metre"] =
      benchmark::Counter(metres, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["scans_per_s"] =
      benchmark::Counter(static_cast<double>(scans), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SimulateSeedHallDepartReturn)->Unit(benchmark::kSecond)->Iterations(2);

// One radar scan in the middle of the room (ray casting + echoes + noise).
void BM_SimulateOneScan(benchmark::State& state) {
  const Config config;
  const sim::SimScenario scenario = sim::MakeScenario(config, SeedHallMap(), "depart-return", 1);
  const SensorGeometry sensor = SensorGeometry::FromConfig(config.radars[0], config.pulse);
  sim::RadarSimulator radar(*scenario.environment, config.pulse, sensor, config.simulator.radar);
  std::mt19937_64 rng(1);
  const Pose2 T_world_sensor = Pose2{3.0, 0.0, 0.0} * sensor.T_robot_sensor;
  for (auto _ : state) benchmark::DoNotOptimize(radar.Simulate(T_world_sensor, &rng));
  state.counters["lit_cells"] = static_cast<double>(radar.lit_cells().size());
}
BENCHMARK(BM_SimulateOneScan)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace uwbsar
