#include "slam/live/live_runner.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>
#include <variant>

#include "core/errors.h"
#include "core/log.h"
#include "drivers/live/fault_log.h"
#include "drivers/live/host_clock.h"
#include "imaging/image_io.h"
#include "slam/app_config.h"
#include "slam/jobs/saved_session.h"
#include "slam/live/live_processor.h"
#include "slam/live/live_recorder.h"
#include "slam/live/live_ros2_results.h"
#include "slam/live/live_source.h"
#include "slam/outputs/map_outputs.h"
#include "slam/outputs/output_folder.h"
#include "slam/session/session_file.h"

namespace uwbsar::slam {
namespace {

nlohmann::json StatValueJson(const live::RadarStatValue& value) {
  return std::visit([](const auto& v) { return nlohmann::json(v); }, value);
}

/// One radar of live.json: the generic counts, then the model's own ("group.key" nested).
nlohmann::json RadarJson(const live::RadarStats& s) {
  nlohmann::json radar = {
      {"startups", s.startups},
      {"startup_failures", s.startup_failures},
      {"config_errors", s.config_errors},
      {"frame_rate_fps", s.setup.frame_rate_fps},
      {"frame_rate_requested_fps", s.setup.frame_rate_requested_fps},
      {"frames_delivered", s.frames_delivered},
      {"frames_repeated", s.frames_repeated},
      {"frames_missed", s.frames_missed},
      {"frames_lost", s.frames_lost},
      {"stamp_reanchors", s.stamp_reanchors},
      {"invalid_frames", s.invalid_frames},
      {"configured", s.configured},
      {"setup", s.configured ? s.setup.description : std::string()},
      {"range_min_m", s.setup.range_min_m},
      {"range_max_m", s.setup.range_max_m},
      {"samples_per_scan", s.setup.samples_per_scan},
  };
  for (const auto& [key, value] : s.extra) {
    const std::size_t dot = key.find('.');
    if (dot == std::string::npos) {
      radar[key] = StatValueJson(value);
    } else {
      radar[key.substr(0, dot)][key.substr(dot + 1)] = StatValueJson(value);
    }
  }
  return radar;
}

void WriteLiveJson(const LiveRunResult& result, const std::string& source,
                   const std::string& out_dir) {
  nlohmann::json live;
  live["source"] = source;
  live["recording"] = result.recording_path;
  live["scans_received"] = result.scans_received;
  live["odometry_received"] = result.odometry_received;
  live["recorded_messages"] = result.recorded_messages;
  live["dropped_from_processing"] = result.dropped_from_processing;
  live["scan_latency_ms"] = {{"samples", result.latency_samples},
                             {"p50", result.latency_p50_ms},
                             {"p99", result.latency_p99_ms},
                             {"max", result.latency_max_ms}};
  live["snapshots"] = result.snapshots;
  live["snapshot_max_s"] = result.snapshot_max_s;
  live["snapshot_p50_s"] = result.snapshot_p50_s;
  live["snapshot_lock_max_ms"] = result.snapshot_lock_max_s * 1e3;
  live["keyframe_lock_wait_max_ms"] = result.keyframe_lock_wait_max_s * 1e3;
  live["faults"] = result.faults;
  live["mode"] = result.localized ? "localize" : "map";
  if (result.localized) live["localize"] = result.localize_summary;
  nlohmann::json radars = nlohmann::json::object();
  for (const auto& [name, s] : result.radars) radars[name] = RadarJson(s);
  live["radars"] = radars;
  WriteTextAtomic((std::filesystem::path(out_dir) / "live.json").string(), live.dump(2) + "\n");
}

/// Runs the SLAM and snapshot threads and polls the source until options.stop; then
/// stops the source, drains SLAM, stops snapshots and shuts the source down, also when
/// the loop throws.
void RunUntilStopped(const LiveRunOptions& options, const std::string& recording,
                     LiveSource* source, Dispatcher* dispatcher, Processor* processor,
                     bool start_source) {
  std::atomic<bool> processing_stop{false}, snapshot_stop{false};
  std::thread slam_thread([&] { processor->Loop(processing_stop); });
  std::thread snapshot_thread([&] { processor->SnapshotLoop(snapshot_stop); });
  // Shutdown order: the source first (no new input), then drain SLAM, then snapshots.
  auto stop_all = [&] {
    source->Stop();
    dispatcher->Event("run stopping");
    processing_stop = true;
    if (slam_thread.joinable()) slam_thread.join();
    snapshot_stop = true;
    if (snapshot_thread.joinable()) snapshot_thread.join();
    source->ShutDown();
  };
  try {
    if (start_source) source->Start();
    dispatcher->Event("run started (" + options.source + ")");
    if (!options.quiet) {
      Log(LogLevel::kInfo, "live run (" + options.source + "): recording to " + recording +
                               ".partial, outputs in " + options.out_dir + "; Ctrl-C to finish");
    }
    while (!(options.stop && options.stop->load())) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      source->Poll();
    }
  } catch (...) {
    stop_all();  // threads joined and the recording closed before the error leaves
    throw;
  }
  stop_all();
}

/// After the threads stopped: finishes SLAM, closes the recording, writes the final
/// outputs and live.json, and gathers the run's figures.
LiveRunResult FinishRun(const LiveRunOptions& options, const live::FaultLog& faults,
                        const Dispatcher& dispatcher, const LiveSource& source,
                        Processor* processor_ptr, Recorder* recorder_ptr) {
  Processor& processor = *processor_ptr;
  Recorder& recorder = *recorder_ptr;
  LiveRunResult result;
  processor.Finish();
  result.faults = faults.Counts();
  result.dropped_from_processing = dispatcher.dropped();
  auto& lat = processor.latencies_ms();
  result.latency_samples = static_cast<long long>(lat.size());
  result.latency_p50_ms = Percentile(lat, 50);
  result.latency_p99_ms = Percentile(lat, 99);
  result.latency_max_ms = lat.empty() ? 0.0 : *std::max_element(lat.begin(), lat.end());
  result.scans_received = source.scans_received();
  result.radars = source.radar_stats();
  result.odometry_received = processor.odometry_messages();
  recorder.Close();
  result.recorded_messages = recorder.written();
  result.recording_path = recorder.path();

  processor.Snapshot();  // the final outputs (after Finish); published too with ros2
  processor.PublishFinalPose();
  result.snapshots = processor.snapshots();
  result.snapshot_max_s = processor.snapshot_max_s();
  result.snapshot_p50_s = Percentile(processor.snapshot_s(), 50);
  result.snapshot_lock_max_s = processor.snapshot_lock_max_s();
  result.keyframe_lock_wait_max_s = processor.keyframe_lock_wait_max_s();
  result.localized = processor.localizing();
  if (result.localized) {
    result.localize = processor.LocalizeResult();
    result.localize_summary = processor.last_localize_summary();
  }
  WriteLiveJson(result, options.source, options.out_dir);
  if (!options.quiet) {
    for (const auto& [name, s] : result.radars) {
      char line[320];
      std::snprintf(line, sizeof(line),
                    "%s: %lld frames at %d frames/s, %lld repeated answers dropped, %lld frames "
                    "missed, %lld frames lost",
                    name.c_str(), s.frames_delivered, s.setup.frame_rate_fps, s.frames_repeated,
                    s.frames_missed, s.frames_lost);
      Log(LogLevel::kInfo, line);
    }
  }
  result.outputs = processor.last_outputs();
  result.run = processor.FinalRun();
  return result;
}

}  // namespace

FolderLock LockLiveOutputFolder(const LiveRunOptions& options) {
  FolderLock lock = LockOutputFolder(options.out_dir);
  if (!options.localize_in.empty()) {
    RefuseMapFolderForLocalize(options.out_dir);
  } else {
    RefuseToReplaceSavedMap(options.out_dir, {}, options.overwrite,
                            "give another --out, or --overwrite to replace it");
  }
  return lock;
}

LiveRunResult RunLive(const Config& config, LiveRunOptions options) {
  if (options.source != "serial" && options.source != "ros2") {
    throw InputError("live source '" + options.source + "' is not one of serial, ros2");
  }
  const FolderLock out_lock = LockLiveOutputFolder(options);
  const std::string recording =
      options.recording_dir.empty()
          ? (std::filesystem::path(options.out_dir) / DefaultRecordingName()).string()
          : options.recording_dir;

  live::FaultLog faults;
  live::HostClock clock(options.time_scale);
  Dispatcher dispatcher(&clock, static_cast<std::size_t>(config.live.processing_queue_size));
  faults.set_listener([&](const std::string& kind, const std::string& detail) {
    dispatcher.Event("fault: " + kind + ": " + detail);
  });

  // The source first: a missing GPIO chip or line, a radar refusing its settings, or DDS
  // refusing, stops the run before a recording is created (its start-up events are held
  // and recorded first). Serial radars start before SLAM is built: their echoed range sets
  // the imaging geometry of `run_config`.
  const bool serial = options.source == "serial";
  Config run_config = config;
  std::unique_ptr<LiveSource> source;
  struct StopOnThrow {  // the serial links run from here until stop_all takes over
    LiveSource* source = nullptr;
    ~StopOnThrow() {
      if (source) source->Stop(), source->ShutDown();
    }
  } guard;
  if (serial) {
    source = MakeSerialSource(config, options, &dispatcher, &faults, &clock);
    guard.source = source.get();
    source->Start();
    source->ConfigureImaging(&run_config);
  }
  // The saved map is read (and checked against the imaging geometry) before recording.
  // Its folder stays locked (shared) for the whole run.
  std::unique_ptr<SavedSession> localize_map;
  if (!options.localize_in.empty()) {
    localize_map =
        std::make_unique<SavedSession>(OpenSavedSession(options.localize_in, run_config));
  }
  Processor processor(run_config, options, &dispatcher,
                      localize_map ? &localize_map->data : nullptr);
  if (!serial) source = MakeRos2Source(run_config, &dispatcher, &faults, &processor);
  const SerialModePublishing serial_publishing =
      serial ? MaybePublishInSerialMode(run_config, &faults, &processor) : SerialModePublishing{};
  Recorder recorder(run_config, recording);
  dispatcher.AttachRecorder(&recorder);
  guard.source = nullptr;

  RunUntilStopped(options, recording, source.get(), &dispatcher, &processor,
                  /*start_source=*/!serial);

  LiveRunResult result = FinishRun(options, faults, dispatcher, *source, &processor, &recorder);
  source.reset();  // after the last publication
  return result;
}

}  // namespace uwbsar::slam
