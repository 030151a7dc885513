// Decoding throughput of radar scans (Float32MultiArray of
// 1000 floats) from a bag on disk, >= 100k messages/s. The bag (10 000 scans of
// noise-like samples, plus odometry at 1/20 of the rate) is written once per storage
// into the temp folder; each iteration reads and decodes all of it through
// ReadRobotBag, as the SLAM pipeline does. items_per_second = radar scans per second.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <random>

#include "drivers/rosbag/bag_writer.h"
#include "drivers/rosbag/robot_bag.h"

namespace {

namespace fs = std::filesystem;
using namespace uwbsar;
using namespace uwbsar::rosbag;

constexpr int kScans = 10000;
constexpr int kSamples = 1000;

// The bench bags live in one temp folder, removed when the program exits.
struct BenchFolder {
  fs::path dir = fs::temp_directory_path() / ("uwbsar_bag_bench_" + std::to_string(::getpid()));
  BenchFolder() { fs::create_directories(dir); }
  ~BenchFolder() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

std::string BenchBag(const std::string& storage, const std::string& compression) {
  static BenchFolder folder;
  static std::map<std::string, std::string> made;
  const std::string key = storage + "_" + (compression.empty() ? "none" : compression);
  if (made.count(key)) return made[key];
  const fs::path& dir = folder.dir;
  const std::string path = (dir / key).string();
  fs::remove_all(path);
  BagWriterOptions o;
  o.storage = storage;
  o.mcap.compression = compression;
  BagWriter w(path, o);
  const int radar = w.AddTopic("/UWBradar0/readings", kFloat32MultiArrayType);
  const int odom = w.AddTopic("/odom", kOdometryType);
  std::mt19937 rng(1);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  Float32MultiArray scan;
  scan.dim = {{"samples", kSamples, kSamples}};
  scan.data.resize(kSamples);
  Odometry od;
  for (int i = 0; i < kScans; ++i) {
    for (auto& v : scan.data) v = noise(rng);
    const TimestampNs t = 1700000000000000000 + i * 5000000LL;  // 200 Hz
    w.WriteMessage(radar, t, scan);
    if (i % 20 == 0) {
      od.position.x = i * 1e-3;
      w.WriteMessage(odom, t + 1, od);
    }
  }
  w.Close();
  made[key] = path;
  return path;
}

void BM_DecodeRadarBag(benchmark::State& state, const std::string& storage,
                       const std::string& compression) {
  const std::string bag = BenchBag(storage, compression);
  struct Sink : RobotBagVisitor {
    double sum = 0;
    void OnRadarScan(const RadarScan& s) override { sum += s.samples[s.samples.size() / 2]; }
  } sink;
  RobotBagOptions options;
  options.radar_topics = {"/UWBradar0/readings"};
  std::uint64_t scans = 0;
  for (auto _ : state) {
    const RobotBagStats stats = ReadRobotBag(bag, options, sink);
    scans += stats.radar_scans;
    benchmark::DoNotOptimize(sink.sum);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(scans));
  state.SetBytesProcessed(static_cast<std::int64_t>(scans) * kSamples * 4);
  state.counters["file_MiB"] =
      static_cast<double>(fs::file_size(bag + "/" + fs::path(bag).filename().string() + "_0." +
                                        (storage == "mcap" ? "mcap" : "db3"))) /
      (1 << 20);
}

BENCHMARK_CAPTURE(BM_DecodeRadarBag, sqlite3, std::string("sqlite3"), std::string(""))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_DecodeRadarBag, mcap_none, std::string("mcap"), std::string(""))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_DecodeRadarBag, mcap_zstd, std::string("mcap"), std::string("zstd"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_DecodeRadarBag, mcap_lz4, std::string("mcap"), std::string("lz4"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
