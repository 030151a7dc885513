// A ROS 2 robot as a live source, over DDS without ROS (drivers/dds): the radar and
// odometry topics are subscribed, put back into stamp order and dispatched with the
// publisher's stamps; the results are published for RViz2 (slam/live/live_ros2_results.h).
#include <chrono>

#include "core/log.h"
#include "drivers/dds/participant.h"
#include "drivers/dds/ros2_subscriber.h"
#include "slam/app_config.h"
#include "slam/live/live_ros2_results.h"
#include "slam/live/live_source.h"
#include "slam/live/stamp_order_buffer.h"

namespace uwbsar::slam {
namespace {

std::int64_t SteadyNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

class Ros2Source : public LiveSource {
 public:
  Ros2Source(const Config& config, Dispatcher* dispatcher, live::FaultLog* faults,
             Processor* processor)
      : config_(config),
        dispatcher_(dispatcher),
        faults_(faults),
        order_(
            static_cast<std::int64_t>(config.dds.reorder_window_s * 1e9),
            [this](LiveMessage&& m, bool late) { Release(std::move(m), late); },
            /*streams=*/static_cast<int>(config.radars.size()) + 1,  // radars, odometry
            static_cast<std::int64_t>(config.dds.startup_hold_s * 1e9)),
        participant_(config.dds),
        results_(participant_, config.dds, faults, processor) {}

  void Start() override {
    std::vector<std::string> radar_topics;
    for (const RadarConfig& r : config_.radars) radar_topics.push_back(r.topic);
    dds::Ros2Subscriber::Callbacks callbacks;
    callbacks.on_radar = [this](dds::RadarMessage&& r) {
      ++scans_;
      LiveMessage m;
      m.kind = Message::Kind::kRadarScan;
      m.stamp_ns = r.scan.stamp_ns;
      m.scan = std::move(r.scan);
      m.for_slam = r.in_order;  // a repeated or older stamp is recorded, not imaged
      const int stream = m.scan.sensor_id;
      order_.Push(m.stamp_ns, SteadyNs(), std::move(m), stream);
    };
    callbacks.on_odometry = [this](dds::OdometryMessage&& o) {
      LiveMessage m;
      m.kind = Message::Kind::kOdometry;
      m.odometry = o.sample;
      if (m.odometry.stamp_ns == 0) m.odometry.stamp_ns = o.source_stamp_ns;
      m.stamp_ns = m.odometry.stamp_ns;
      m.for_slam = o.in_order;
      order_.Push(m.stamp_ns, SteadyNs(), std::move(m), static_cast<int>(config_.radars.size()));
    };
    callbacks.on_event = [this](const dds::DdsEvent& e) {
      const bool good_news = e.kind == dds::DdsEventKind::kPublisherMatched ||
                             e.kind == dds::DdsEventKind::kPublisherBack ||
                             e.kind == dds::DdsEventKind::kTopicResumed;
      if (good_news) {  // recorded as an event, not a fault
        Log(LogLevel::kInfo, e.detail);
        dispatcher_->Event("ros2: " + e.detail);
      } else {
        faults_->Report(std::string("ros2 ") + e.topic + ": " + dds::DdsEventKindName(e.kind),
                        e.detail);
      }
    };
    subscriber_ = std::make_unique<dds::Ros2Subscriber>(participant_, config_.dds, radar_topics,
                                                        config_.slam.odometry_topic, callbacks);
  }

  void Poll() override { order_.Poll(SteadyNs()); }

  void Stop() override {
    if (subscriber_) subscriber_->Stop();
    order_.Flush();
  }

  long long scans_received() const override { return scans_; }

 private:
  // A late sample still goes to SLAM: each topic arrives in its own order, the frontend
  // interpolates a scan between the odometry around it and closes a tile only metres
  // later, so a sample overtaken by another topic's changes nothing unless it is very late.
  void Release(LiveMessage&& m, bool late) {
    if (late) {
      faults_->Report("ros2: late samples",
                      "a sample stamped " + std::to_string(m.stamp_ns) +
                          " ns came after later ones of another topic were passed on (more "
                          "than dds.reorder_window_s apart); recorded and used with its own stamp");
    }
    dispatcher_->PublishStamped(std::move(m));
  }

  const Config& config_;
  Dispatcher* dispatcher_;
  live::FaultLog* faults_;
  StampOrderBuffer<LiveMessage> order_;
  dds::Participant participant_;
  LiveResultPublisher results_;
  std::unique_ptr<dds::Ros2Subscriber> subscriber_;
  std::atomic<long long> scans_{0};
};

}  // namespace

std::unique_ptr<LiveSource> MakeRos2Source(const Config& config, Dispatcher* dispatcher,
                                           live::FaultLog* faults, Processor* processor) {
  return std::make_unique<Ros2Source>(config, dispatcher, faults, processor);
}

}  // namespace uwbsar::slam
