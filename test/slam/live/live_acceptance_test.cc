// Live acceptance on the full simulated seed_lab run played by emulated devices:
// A (1x live run vs `uwbsar map`), B (p99 scan-to-tile latency, reported), C (faults:
// radar unplugged 5 s, 1 % corrupted frames, odometry stall 2 s) and D (kill -9 of
// `uwbsar run --emulate`: the recording opens and holds everything up to 1 s before
// the kill; the last snapshot is complete). Minutes of wall time: integration only.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <set>

#include "drivers/rosbag/bag_reader.h"
#include "live_test_util.h"
#include "slam/app_config.h"
#include "test/shared_data.h"

namespace uwbsar::live {
namespace {

namespace fs = std::filesystem;

/// `uwbsar demo`'s pipeline on the same simulated run, without devices.
slam::MapRun MapSimulated(const Config& config) {
  return slam::MapSimulation(config, SeedLabMapPath(), "depart-return", 1);
}

int AcceptedLoops(const slam::SlamSystem& slam) {
  int n = 0;
  for (const slam::LoopRecord& l : slam.loops()) n += l.accepted() ? 1 : 0;
  return n;
}

/// Loops accepted by one run and not the other that are not weak: a weak loop had at most
/// twice the paper's min_good_matches for one detector where it was accepted, so a
/// different noise draw in its tiles can move it across the threshold.
std::vector<std::pair<int, int>> NonMarginalDifferences(const slam::SlamSystem& a,
                                                        const slam::SlamSystem& b) {
  const int marginal = 2 * a.config().place_recognition.validation.min_good_matches;
  std::vector<std::pair<int, int>> out;
  for (const auto& pair : {std::make_pair(&a, &b), std::make_pair(&b, &a)}) {
    const std::set<std::pair<int, int>> other = AcceptedPairs(*pair.second);
    for (const slam::LoopRecord& l : pair.first->loops()) {
      if (!l.accepted() || other.count({l.match_id, l.query_id})) continue;
      std::printf("A: loop %d-%d only in one run (good matches AKAZE %d, ORB %d)\n", l.match_id,
                  l.query_id, l.Match(DetectorKind::kAkaze).good_matches,
                  l.Match(DetectorKind::kOrb).good_matches);
      if (std::min(l.Match(DetectorKind::kAkaze).good_matches,
                   l.Match(DetectorKind::kOrb).good_matches) > marginal) {
        out.push_back({l.match_id, l.query_id});
      }
    }
  }
  return out;
}

TEST(LiveAcceptanceTest, A_B_RealTimeRunMatchesOfflineMappingAndReportsLatency) {
  UWBSAR_NEED_SEED_LAB_MAP();
  Config config;
  const EmulatedRun live = RunEmulated(config, "accept_a", 1.0, 0.0);
  const slam::LiveRunResult& r = live.result;
  const slam::MapRun offline = MapSimulated(config);
  const AteResult offline_ate =
      slam::TrajectoryError(offline.slam->CorrectedTrajectory(), offline.ground_truth);
  const slam::MapRun replay = slam::MapBag(config, r.recording_path, false);
  const auto a = r.run.slam->CorrectedTrajectory();
  const auto b = replay.slam->CorrectedTrajectory();
  std::printf(
      "A: live %d loops, ATE %.2f cm over %d poses; uwbsar map of the simulated run %d "
      "loops, ATE %.2f cm; recording replayed %d loops\n",
      AcceptedLoops(*r.run.slam), 100 * r.outputs.ate.rmse_m, r.outputs.ate.num_poses,
      AcceptedLoops(*offline.slam), 100 * offline_ate.rmse_m, AcceptedLoops(*replay.slam));
  std::printf(
      "B: scan-to-tile latency p50 %.1f ms, p99 %.1f ms, max %.1f ms over %lld scans; "
      "%lld dropped from processing; snapshot p50 %.2f s, max %.2f s, lock held max %.3f ms, "
      "keyframe thread's longest lock wait %.3f ms%s\n",
      r.latency_p50_ms, r.latency_p99_ms, r.latency_max_ms, r.latency_samples,
      r.dropped_from_processing, r.snapshot_p50_s, r.snapshot_max_s, 1e3 * r.snapshot_lock_max_s,
      1e3 * r.keyframe_lock_wait_max_s, std::getenv("UWBSAR_UNDER_LOAD") ? " (under load)" : "");
  long long repeated = 0, delivered = 0, lost = 0;
  for (const auto& [name, s] : r.radars) {
    std::printf(
        "A: %s polled at %d frames/s: %lld requests (%.1f/s), %lld answers, %lld frames, %lld "
        "repeated (dropped), %lld missed, %lld lost; request-to-answer p50 %.2f ms, p99 %.2f ms\n",
        name.c_str(), s.setup.frame_rate_fps, RadarCount(s, "frame_requests"),
        RadarCount<double>(s, "requests_per_s"), RadarCount(s, "frame_answers"), s.frames_delivered,
        s.frames_repeated, s.frames_missed, s.frames_lost,
        RadarCount<double>(s, "request_to_answer_ms.p50"),
        RadarCount<double>(s, "request_to_answer_ms.p99"));
    repeated += s.frames_repeated;
    delivered += s.frames_delivered;
    lost += s.frames_lost;
  }
  std::printf(
      "A: emulator acquired %lld frames, answered %lld, repeated %lld, missed %lld, %lld "
      "overwritten before a request\n",
      live.emulator.frames_acquired, live.emulator.scans_sent, live.emulator.frames_repeated,
      live.emulator.frames_missed, live.emulator.frames_overwritten);
  // The emulator answers `d` at once with its latest frame: no frame is recorded twice. (A
  // frame lost on the wire, when the machine is too busy to read, is asked for again and
  // counted repeated by the emulator only.)
  if (lost == 0) {
    EXPECT_EQ(repeated, live.emulator.frames_repeated);
  }
  EXPECT_LE(repeated, live.emulator.frames_repeated);
  EXPECT_EQ(delivered, r.scans_received);
  EXPECT_EQ(r.dropped_from_processing, 0);
  // B: keyframe work runs on the SlamSystem's own thread and snapshots on another, so
  // the feeding thread only images (measured p99 20.5 ms; it was 71 ms with both on it).
  // Margin measured under load: p99 20 ms idle, 44 ms with uwbsar_load --memory-mib 256 on
  // the 2-core machine (busy thread per core); the limit is over 3x the loaded figure.
  EXPECT_LE(r.latency_p99_ms, 150.0);
  // A: the recording replays the live run exactly. Against `uwbsar map` of the simulated
  // run the inputs are the same except for the host's sub-millisecond arrival jitter
  // (p50 0.2 ms), which changes which scans the 3 mm travel gate keeps now and then and
  // so the noise in a tile: every strong loop must agree; a weak one may flip (measured
  // over 5 runs: identical once, else one loop differs: 5-9 with 12/12 good matches, or
  // 0-14 with 17/40).
  EXPECT_TRUE(NonMarginalDifferences(*r.run.slam, *offline.slam).empty());
  EXPECT_LE(std::abs(AcceptedLoops(*r.run.slam) - AcceptedLoops(*offline.slam)), 2);
  EXPECT_EQ(AcceptedPairs(*r.run.slam), AcceptedPairs(*replay.slam));
  // The ATE follows: the one weak loop that may flip moves it by up to about 0.1 cm
  // (0.00-0.10 cm over 5 runs; 0.101 cm once in CI under uwbsar_load: 1.37 against 1.27 cm),
  // so the limit is 0.3 cm, 3x the measured spread; the strong loops themselves are checked
  // one by one above (NonMarginalDifferences).
  EXPECT_LT(std::abs(r.outputs.ate.rmse_m - offline_ate.rmse_m), 0.003);
  // No scan dropped at start-up: the radars are polled once odometry flows.
  EXPECT_EQ(r.run.slam->frontend_stats().scans_rejected_no_odometry, 0);
  ASSERT_EQ(a.size(), b.size());
  double max_diff = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    max_diff = std::max({max_diff, std::abs(a[k].second.x_m - b[k].second.x_m),
                         std::abs(a[k].second.y_m - b[k].second.y_m)});
  }
  EXPECT_LT(max_diff, 1e-6);
  EXPECT_GT(r.latency_samples, 10000);
}

TEST(LiveAcceptanceTest, C_FaultsAreReportedAndTheRunCompletesWithoutFalseLoops) {
  UWBSAR_NEED_SEED_LAB_MAP();
  Config config;
  EmulatorFaults faults;
  faults.unplug_radar = 1;
  faults.unplug_at_s = 20.0;
  faults.unplug_for_s = 5.0;
  faults.corrupt_fraction = 0.01;
  faults.stall_at_s = 45.0;
  faults.stall_for_s = 2.0;
  faults.encoder_jump_at_s = 60.0;
  const EmulatedRun live = RunEmulated(config, "accept_c", 1.0, 0.0, faults);
  const slam::LiveRunResult& r = live.result;
  for (const auto& [kind, count] : r.faults)
    std::printf("C: fault %s: %lld\n", kind.c_str(), count);
  std::printf("C: emulator corrupted %lld frames and %lld packets; %d loops, ATE %.2f cm\n",
              live.emulator.frames_corrupted, live.emulator.packets_corrupted,
              AcceptedLoops(*r.run.slam), 100 * r.outputs.ate.rmse_m);
  auto count = [&](const std::string& k) {
    auto it = r.faults.find(k);
    return it == r.faults.end() ? 0LL : it->second;
  };
  EXPECT_GE(count("radar right: unplugged"), 1);
  EXPECT_GE(count("radar left: broken frames") + count("radar right: broken frames"),
            live.emulator.frames_corrupted / 2);
  EXPECT_GE(count("kobuki: checksum errors"), 1);
  EXPECT_GE(count("kobuki: odometry stalls"), 1);
  EXPECT_GE(count("kobuki: odometry jumps"), 1);
  ASSERT_FALSE(r.run.slam->keyframes().empty());
  // No false loop: a wrong accepted loop would bend the trajectory by decimetres.
  EXPECT_LT(r.outputs.ate.rmse_m, 0.05);
}

TEST(LiveAcceptanceTest, D_KillMinus9LeavesAReadableRecordingAndACompleteSnapshot) {
  const std::string exe = (fs::read_symlink("/proc/self/exe").parent_path() / "uwbsar").string();
  ASSERT_TRUE(fs::exists(exe)) << exe;
  const std::string out =
      (fs::temp_directory_path() / ("uwbsar_live_kill_" + std::to_string(::getpid()))).string();
  fs::remove_all(out);
  const std::string recording = out + "/recording";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::execl(exe.c_str(), exe.c_str(), "--quiet", "run", "--emulate", "--out", out.c_str(),
            "--recording", recording.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  std::this_thread::sleep_for(std::chrono::seconds(35));  // snapshots every 10 s
  const std::int64_t kill_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                   std::chrono::system_clock::now().time_since_epoch())
                                   .count();
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  rosbag::BagReader reader(recording + ".partial/recording_0.db3");
  rosbag::BagMessage msg;
  std::int64_t last = 0;
  long long n = 0;
  while (reader.Next(&msg)) last = msg.log_time_ns, ++n;
  std::printf("D: %lld messages recorded, the last %.3f s before the kill\n", n,
              NsToSeconds(kill_ns - last));
  EXPECT_GT(n, 1000);
  EXPECT_GT(last, kill_ns - 1000000000LL);
  // The last snapshot: summary.json is renamed last, so its presence means a whole set.
  std::ifstream in(out + "/summary.json");
  ASSERT_TRUE(in.good());
  const nlohmann::json summary = nlohmann::json::parse(in);
  EXPECT_GT(summary["keyframes"].get<int>(), 0);
  EXPECT_FALSE(cv::imread(out + "/map.png").empty());
  EXPECT_GT(fs::file_size(out + "/trajectory.tum"), 0u);
}

}  // namespace
}  // namespace uwbsar::live
