#include "tools/live_runner.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <ctime>
#include <deque>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "drivers/live/device_link.h"
#include "drivers/live/host_clock.h"
#include "drivers/live/kobuki_driver.h"
#include "drivers/live/lt102_driver.h"
#include "drivers/live/radar_power.h"
#include "drivers/rosbag/bag_writer.h"
#include "drivers/rosbag/cdr_writer.h"
#include "drivers/sim/sim_bag_writer.h"
#include "frontend/image_io.h"
#include "slam/errors.h"
#include "slam/log.h"
#include "tools/commands.h"

namespace uwbsar::tools {
namespace {

using SteadyClock = std::chrono::steady_clock;
constexpr const char* kEventTopic = "/uwbsar/events";

struct LiveMessage {
  enum class Kind { kScan, kOdometry, kEvent };
  Kind kind = Kind::kEvent;
  TimestampNs stamp_ns = 0;
  RadarScan scan;
  OdometrySample odometry;
  std::string text;
  SteadyClock::time_point arrival;
};

/// Writes every message it is given to the bag, in arrival order; never drops.
class Recorder {
 public:
  Recorder(const Config& config, const std::string& dir)
      : period_s_(config.live.recording_flush_period_s) {
    rosbag::BagWriterOptions options;
    options.storage = config.live.recording_storage;
    options.flush_period_s = period_s_;
    writer_ = std::make_unique<rosbag::BagWriter>(dir, options);
    for (const RadarConfig& r : config.radars) {
      radar_topics_.push_back(writer_->AddTopic(r.topic, "std_msgs/msg/Float32MultiArray"));
    }
    odometry_topic_ = writer_->AddTopic(config.slam.odometry_topic, "nav_msgs/msg/Odometry");
    event_topic_ = writer_->AddTopic(kEventTopic, "std_msgs/msg/String", "string data\n");
    writer_->Flush();
    thread_ = std::thread([this] { Loop(); });
  }
  ~Recorder() { Close(); }

  void Push(const LiveMessage& msg) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      queue_.push_back(msg);
    }
    wake_.notify_one();
  }
  void Close() {
    if (!thread_.joinable()) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_one();
    thread_.join();
    writer_->Close();
  }
  long long written() const { return written_; }
  std::string path() const { return writer_->path(); }

 private:
  void Loop() {
    auto last_flush = SteadyClock::now();
    std::deque<LiveMessage> batch;
    while (true) {
      bool stopping = false;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait_for(lock, std::chrono::duration<double>(period_s_ / 2),
                       [this] { return stop_ || !queue_.empty(); });
        batch.swap(queue_);
        stopping = stop_;
      }
      for (const LiveMessage& m : batch) Write(m);
      batch.clear();
      if (SteadyClock::now() - last_flush >= std::chrono::duration<double>(period_s_)) {
        writer_->Flush();
        last_flush = SteadyClock::now();
      }
      if (stopping) break;
    }
  }
  void Write(const LiveMessage& m) {
    switch (m.kind) {
      case LiveMessage::Kind::kScan: {
        array_.data = m.scan.samples;
        writer_->WriteMessage(radar_topics_[static_cast<std::size_t>(m.scan.sensor_id)], m.stamp_ns,
                              array_);
        break;
      }
      case LiveMessage::Kind::kOdometry:
        writer_->WriteMessage(odometry_topic_, m.stamp_ns,
                              sim::ToRosOdometry(m.odometry, "odom", "base_link", true));
        break;
      case LiveMessage::Kind::kEvent: {
        rosbag::CdrWriter cdr(&cdr_);
        cdr.WriteString(m.text);
        writer_->Write(event_topic_, m.stamp_ns, cdr_);
        break;
      }
    }
    ++written_;
  }

  double period_s_;
  std::unique_ptr<rosbag::BagWriter> writer_;
  std::vector<int> radar_topics_;
  int odometry_topic_ = 0, event_topic_ = 0;
  rosbag::Float32MultiArray array_;
  std::vector<std::uint8_t> cdr_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<LiveMessage> queue_;
  bool stop_ = false;
  std::atomic<long long> written_{0};
};

/// Stamps messages in one order and fans them out to the recorder and the SLAM queue.
class Dispatcher {
 public:
  Dispatcher(live::HostClock* clock, Recorder* recorder, std::size_t capacity)
      : clock_(clock), recorder_(recorder), capacity_(capacity) {}

  void Publish(LiveMessage&& msg) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      // Stamped under the lock: stamp order = queue order = recording order.
      msg.stamp_ns = clock_->Now();
      msg.arrival = SteadyClock::now();
      if (msg.kind == LiveMessage::Kind::kScan) msg.scan.stamp_ns = msg.stamp_ns;
      if (msg.kind == LiveMessage::Kind::kOdometry) msg.odometry.stamp_ns = msg.stamp_ns;
      recorder_->Push(msg);
      if (msg.kind != LiveMessage::Kind::kEvent) {
        if (queue_.size() >= capacity_) {
          queue_.pop_front();
          ++dropped_;
        }
        queue_.push_back(std::move(msg));
      }
    }
    wake_.notify_one();
  }
  void Event(const std::string& text) {
    LiveMessage m;
    m.kind = LiveMessage::Kind::kEvent;
    m.text = text;
    Publish(std::move(m));
  }
  /// Waits up to `timeout` for a message; false when none came.
  bool Pop(LiveMessage* out, std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!wake_.wait_for(lock, timeout, [this] { return !queue_.empty(); })) return false;
    *out = std::move(queue_.front());
    queue_.pop_front();
    return true;
  }
  long long dropped() const { return dropped_; }

 private:
  live::HostClock* clock_;
  Recorder* recorder_;
  std::size_t capacity_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<LiveMessage> queue_;
  std::atomic<long long> dropped_{0};
};

std::string DefaultRecordingName() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  ::localtime_r(&t, &tm);
  char buffer[64];
  std::strftime(buffer, sizeof(buffer), "rosbag2_%Y_%m_%d-%H_%M_%S", &tm);
  return buffer;
}

double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto k = static_cast<std::size_t>(std::ceil(p / 100.0 * static_cast<double>(v.size()))) - 1;
  return v[std::min(k, v.size() - 1)];
}

/// The SLAM feeding thread (imaging only: keyframe work runs on the SlamSystem's own
/// thread) and the snapshot thread, which rewrites the outputs without ever making the
/// feeding thread wait.
class Processor {
 public:
  Processor(const Config& config, const LiveRunOptions& options, Dispatcher* dispatcher)
      : config_(config), options_(options), dispatcher_(dispatcher) {
    run_.input = "live run";
    run_.slam = std::make_shared<SlamSystem>(config);
    start_ = SteadyClock::now();
  }
  /// Feeds SLAM until `stop` and the queue is empty.
  void Loop(const std::atomic<bool>& stop) {
    LiveMessage msg;
    while (true) {
      if (dispatcher_->Pop(&msg, std::chrono::milliseconds(20))) {
        Process(msg);
      } else if (stop) {
        break;
      }
    }
  }
  /// Writes a snapshot every live.snapshot_period_s until `stop`.
  void SnapshotLoop(const std::atomic<bool>& stop) {
    if (config_.live.snapshot_period_s <= 0) return;
    const auto period = std::chrono::duration<double>(config_.live.snapshot_period_s);
    auto next = SteadyClock::now() + period;
    while (!stop) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      if (SteadyClock::now() < next) continue;
      Snapshot();
      next = SteadyClock::now() + period;
    }
  }
  MapRun& run() { return run_; }
  std::vector<double>& latencies_ms() { return latencies_ms_; }
  int snapshots() const { return snapshots_; }
  const MapOutputs& last_outputs() const { return last_outputs_; }
  double snapshot_max_s() const { return snapshot_max_s_; }
  /// Writes the outputs of the state so far (any thread but the feeding one's callers').
  void Snapshot() {
    const auto t0 = SteadyClock::now();
    MapRun view;  // the counters as of now, the same SlamSystem
    {
      std::lock_guard<std::mutex> lock(run_mutex_);
      view.slam = run_.slam;
      view.input = run_.input;
      view.first_stamp_ns = run_.first_stamp_ns;
      view.last_stamp_ns = run_.last_stamp_ns;
      view.messages = run_.messages;
      view.radar_messages = run_.radar_messages;
      view.odometry_messages = run_.odometry_messages;
    }
    view.processing_s = std::chrono::duration<double>(t0 - start_).count();
    if (options_.ground_truth) view.ground_truth = options_.ground_truth();
    try {
      const auto state = view.slam->LockState();
      if (view.slam->keyframes().empty()) return;
      last_outputs_ = WriteMapOutputs(view, options_.out_dir);
      ++snapshots_;
    } catch (const std::exception& e) {
      Log(LogLevel::kWarning, std::string("snapshot not written: ") + e.what());
    }
    snapshot_max_s_ =
        std::max(snapshot_max_s_, std::chrono::duration<double>(SteadyClock::now() - t0).count());
  }
  /// After the threads stopped: the run with the last counters and the ground truth.
  MapRun FinalRun() {
    run_.processing_s = std::chrono::duration<double>(SteadyClock::now() - start_).count();
    if (options_.ground_truth) run_.ground_truth = options_.ground_truth();
    return std::move(run_);
  }

 private:
  void Process(const LiveMessage& msg) {
    {
      std::lock_guard<std::mutex> lock(run_mutex_);
      if (run_.messages++ == 0) run_.first_stamp_ns = msg.stamp_ns;
      run_.last_stamp_ns = msg.stamp_ns;
      if (msg.kind == LiveMessage::Kind::kScan) {
        ++run_.radar_messages;
      } else {
        ++run_.odometry_messages;
      }
    }
    if (msg.kind == LiveMessage::Kind::kScan) {
      pending_.push_back(msg.arrival);
      run_.slam->AddScan(msg.scan);
    } else {
      run_.slam->AddOdometry(msg.odometry);
    }
    // A scan is resolved once the frontend imaged, gated or rejected it (it may wait for
    // the odometry after it); resolution is in arrival order.
    const FrontendStats s = run_.slam->frontend_stats();
    const long long resolved = s.scans_imaged + s.scans_gated + s.scans_rejected();
    const auto now = SteadyClock::now();
    while (resolved_ < resolved && !pending_.empty()) {
      latencies_ms_.push_back(
          std::chrono::duration<double, std::milli>(now - pending_.front()).count());
      pending_.pop_front();
      ++resolved_;
    }
  }

  const Config& config_;
  const LiveRunOptions& options_;
  Dispatcher* dispatcher_;
  std::mutex run_mutex_;  ///< run_'s counters, read by the snapshot thread
  MapRun run_;
  std::deque<SteadyClock::time_point> pending_;
  long long resolved_ = 0;
  std::vector<double> latencies_ms_;
  SteadyClock::time_point start_;
  int snapshots_ = 0;
  double snapshot_max_s_ = 0.0;
  MapOutputs last_outputs_;
};

}  // namespace

LiveRunResult RunLive(const Config& config, LiveRunOptions options) {
  const LiveConfig& lc = config.live;
  if (lc.radar_devices.size() != config.radars.size()) {
    throw InputError("live.radar_devices lists " + std::to_string(lc.radar_devices.size()) +
                     " devices for " + std::to_string(config.radars.size()) +
                     " radars: give one serial device per radars[] entry");
  }
  EnsureDirectory(options.out_dir);
  const std::string recording =
      options.recording_dir.empty()
          ? (std::filesystem::path(options.out_dir) / DefaultRecordingName()).string()
          : options.recording_dir;

  live::FaultLog faults;
  live::HostClock clock(options.time_scale);
  Recorder recorder(config, recording);
  Dispatcher dispatcher(&clock, &recorder, static_cast<std::size_t>(lc.processing_queue_size));
  faults.set_listener([&](const std::string& kind, const std::string& detail) {
    dispatcher.Event("fault: " + kind + ": " + detail);
  });

  // GPIO first: a missing chip or line stops the run before anything moves.
  std::unique_ptr<live::GpioChip> chip =
      options.gpio ? std::move(options.gpio) : live::OpenConfiguredChip(lc);
  live::RadarPower power(std::move(chip), lc,
                         [&](const std::string& e) { dispatcher.Event("gpio: " + e); });
  power.StartUp();

  std::vector<std::unique_ptr<live::Lt102Driver>> radars;
  std::vector<std::unique_ptr<live::DeviceLink>> links;
  live::LinkPolicy policy;
  policy.read_timeout_s = lc.read_timeout_s;
  policy.reconnect_initial_s = lc.reconnect_initial_s;
  policy.reconnect_max_s = lc.reconnect_max_s;
  policy.power_cycle_after_failures = lc.power_cycle_after_failures;
  for (std::size_t i = 0; i < config.radars.size(); ++i) {
    const std::string name = "radar " + config.radars[i].name;
    radars.push_back(std::make_unique<live::Lt102Driver>(name, static_cast<int>(i), lc, &faults,
                                                         [&dispatcher](RadarScan&& scan) {
                                                           LiveMessage m;
                                                           m.kind = LiveMessage::Kind::kScan;
                                                           m.scan = std::move(scan);
                                                           dispatcher.Publish(std::move(m));
                                                         }));
    live::LinkPolicy p = policy;
    p.baud = lc.radar_baud;
    std::function<void()> cycle;
    if (power.can_power_cycle(static_cast<int>(i))) {
      cycle = [&power, i] { power.PowerCycle(static_cast<int>(i)); };
    }
    links.push_back(std::make_unique<live::DeviceLink>(name, lc.radar_devices[i], p,
                                                       radars.back().get(), &faults, cycle));
  }
  std::atomic<long long> last_odometry_ns{0};
  live::KobukiDriver kobuki(
      lc, &faults, [&clock] { return clock.Now(); },
      [&](OdometrySample&& sample) {
        LiveMessage m;
        m.kind = LiveMessage::Kind::kOdometry;
        m.odometry = sample;
        dispatcher.Publish(std::move(m));
        last_odometry_ns = clock.Now();
      });
  {
    live::LinkPolicy p = policy;
    p.baud = lc.kobuki_baud;
    links.push_back(
        std::make_unique<live::DeviceLink>("kobuki", lc.kobuki_device, p, &kobuki, &faults));
  }

  Processor processor(config, options, &dispatcher);
  std::atomic<bool> processing_stop{false}, snapshot_stop{false};
  std::thread slam_thread([&] { processor.Loop(processing_stop); });
  std::thread snapshot_thread([&] { processor.SnapshotLoop(snapshot_stop); });
  for (auto& link : links) link->Start();
  dispatcher.Event("run started");
  if (!options.quiet) {
    Log(LogLevel::kInfo, "live run: recording to " + recording + ".partial, outputs in " +
                             options.out_dir + "; Ctrl-C to finish");
  }

  // Watchdog: odometry stalls, clock steps, status LED (on while every link is up).
  bool stalled = false, led = false;
  while (!(options.stop && options.stop->load())) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const double step_s = clock.CheckStep();
    if (std::abs(step_s) >= lc.clock_step_threshold_s) {
      faults.Report("host clock: steps", "system clock stepped by " + std::to_string(step_s) +
                                             " s; stamps follow the monotonic clock");
    }
    const long long last = last_odometry_ns;
    const double silent_s = last == 0 ? 0.0 : NsToSeconds(clock.Now() - last);
    if (silent_s > lc.odometry_stall_s && !stalled) {
      stalled = true;
      faults.Report("kobuki: odometry stalls",
                    "no odometry for " + std::to_string(lc.odometry_stall_s) +
                        " s; SLAM waits, scans without odometry are not imaged");
    } else if (silent_s <= lc.odometry_stall_s) {
      stalled = false;
    }
    const bool all_up =
        std::all_of(links.begin(), links.end(), [](const auto& l) { return l->connected(); });
    if (all_up != led) {
      power.SetStatusLed(all_up);
      led = all_up;
    }
  }

  // Shutdown: drivers first (no new input), then drain SLAM, then the final outputs.
  for (auto& link : links) link->Stop();
  dispatcher.Event("run stopping");
  processing_stop = true;
  slam_thread.join();
  snapshot_stop = true;
  snapshot_thread.join();
  power.ShutDown();

  LiveRunResult result;
  processor.run().slam->Finish();
  result.faults = faults.Counts();
  result.dropped_from_processing = dispatcher.dropped();
  auto& lat = processor.latencies_ms();
  result.latency_samples = static_cast<long long>(lat.size());
  result.latency_p50_ms = Percentile(lat, 50);
  result.latency_p99_ms = Percentile(lat, 99);
  result.latency_max_ms = lat.empty() ? 0.0 : *std::max_element(lat.begin(), lat.end());
  for (const auto& r : radars) result.scans_received += r->scans();
  result.odometry_received = processor.run().odometry_messages;
  recorder.Close();
  result.recorded_messages = recorder.written();
  result.recording_path = recorder.path();

  processor.Snapshot();  // the final outputs (after Finish)
  result.snapshots = processor.snapshots();
  result.snapshot_max_s = processor.snapshot_max_s();

  nlohmann::json live;
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
  live["faults"] = result.faults;
  WriteTextAtomic((std::filesystem::path(options.out_dir) / "live.json").string(),
                  live.dump(2) + "\n");

  result.outputs = processor.last_outputs();
  result.run = processor.FinalRun();
  return result;
}

}  // namespace uwbsar::tools
