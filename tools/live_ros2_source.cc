// A ROS 2 robot as a live source, over DDS without ROS (drivers/dds): the radar and
// odometry topics are subscribed, put back into stamp order and dispatched with the
// publisher's stamps; the map, pose, path and loop closures are published for RViz2.
#include <chrono>
#include <filesystem>

#include "drivers/dds/participant.h"
#include "drivers/dds/ros2_publisher.h"
#include "drivers/dds/ros2_subscriber.h"
#include "slam/log.h"
#include "slam/occupancy_grid.h"
#include "tools/live_source.h"
#include "tools/stamp_order_buffer.h"

namespace uwbsar::tools {
namespace {

std::int64_t SteadyNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

/// The accepted loops as lines between the two keyframes' corrected anchors (caller holds
/// the SLAM state lock).
std::vector<dds::LoopSegment> LoopSegments(const SlamSystem& slam) {
  const std::map<int, Pose2> poses = slam.KeyframePoses();
  std::vector<dds::LoopSegment> segments;
  for (const LoopRecord& l : slam.loops()) {
    if (!l.accepted()) continue;
    const auto a = poses.find(l.match_id), b = poses.find(l.query_id);
    if (a == poses.end() || b == poses.end()) continue;
    segments.push_back(
        {Point2{a->second.x_m, a->second.y_m}, Point2{b->second.x_m, b->second.y_m}});
  }
  return segments;
}

class Ros2Source : public LiveSource {
 public:
  Ros2Source(const Config& config, Dispatcher* dispatcher, live::FaultLog* faults,
             Processor* processor)
      : config_(config),
        dispatcher_(dispatcher),
        faults_(faults),
        order_(static_cast<std::int64_t>(config.dds.reorder_window_s * 1e9),
               [this](LiveMessage&& m, bool late) { Release(std::move(m), late); }),
        participant_(config.dds),
        publisher_(participant_, config.dds) {
    processor->set_hooks(
        {[this](const MapRun& view, const MapOutputs& outputs) { PublishSnapshot(view, outputs); },
         [this, processor] { PublishPose(processor); }});
  }

  void Start() override {
    std::vector<std::string> radar_topics;
    for (const RadarConfig& r : config_.radars) radar_topics.push_back(r.topic);
    dds::Ros2Subscriber::Callbacks callbacks;
    callbacks.on_radar = [this](dds::RadarMessage&& r) {
      ++scans_;
      LiveMessage m;
      m.kind = LiveMessage::Kind::kScan;
      m.stamp_ns = r.scan.stamp_ns;
      m.scan = std::move(r.scan);
      m.for_slam = r.in_order;  // a repeated or older stamp is recorded, not imaged
      order_.Push(m.stamp_ns, SteadyNs(), std::move(m));
    };
    callbacks.on_odometry = [this](dds::OdometryMessage&& o) {
      LiveMessage m;
      m.kind = LiveMessage::Kind::kOdometry;
      m.odometry = o.sample;
      if (m.odometry.stamp_ns == 0) m.odometry.stamp_ns = o.source_stamp_ns;
      m.stamp_ns = m.odometry.stamp_ns;
      m.for_slam = o.in_order;
      order_.Push(m.stamp_ns, SteadyNs(), std::move(m));
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

  // Snapshot thread, state lock held: what was just written to disk, to RViz2.
  void PublishSnapshot(const MapRun& view, const MapOutputs& outputs) {
    try {
      const TimestampNs stamp = view.last_stamp_ns;
      for (const std::string& file : outputs.files) {  // map.yaml, as written
        if (std::filesystem::path(file).filename() == "map.yaml") {
          publisher_.PublishMap(LoadOccupancyGrid(file), stamp);
        }
      }
      publisher_.PublishPath(stamp, view.slam->CorrectedTrajectory());
      publisher_.PublishLoops(stamp, LoopSegments(*view.slam));
    } catch (const std::exception& e) {
      faults_->Report("ros2: publishing failed", e.what());
    }
  }

  // Snapshot thread: the corrected robot pose, at most every dds.publish_pose_period_s.
  void PublishPose(Processor* processor) {
    const std::optional<OdometrySample> odom = processor->LatestOdometry();
    if (!odom || odom->stamp_ns == last_pose_stamp_ns_) return;
    last_pose_stamp_ns_ = odom->stamp_ns;
    Pose2 correction;
    {
      const auto state = processor->slam().LockState();
      correction = processor->slam().CorrectionAt(odom->stamp_ns);
    }
    try {
      if (publisher_.PublishPose(odom->stamp_ns, correction * odom->T_world_robot)) {
        publisher_.PublishMapToOdom(odom->stamp_ns, correction);
      }
    } catch (const std::exception& e) {
      faults_->Report("ros2: publishing failed", e.what());
    }
  }

  const Config& config_;
  Dispatcher* dispatcher_;
  live::FaultLog* faults_;
  StampOrderBuffer<LiveMessage> order_;
  dds::Participant participant_;
  dds::Ros2Publisher publisher_;
  std::unique_ptr<dds::Ros2Subscriber> subscriber_;
  std::atomic<long long> scans_{0};
  TimestampNs last_pose_stamp_ns_ = 0;
};

}  // namespace

std::unique_ptr<LiveSource> MakeRos2Source(const Config& config, Dispatcher* dispatcher,
                                           live::FaultLog* faults, Processor* processor) {
  return std::make_unique<Ros2Source>(config, dispatcher, faults, processor);
}

}  // namespace uwbsar::tools
