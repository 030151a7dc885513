#include "drivers/dds/ros2_publisher.h"

#include "drivers/dds/dds_check.h"
#include "drivers/dds/ros2_convert.h"
#include "drivers/dds/ros2_qos.h"
#include "drivers/dds/ros2_types.h"

namespace uwbsar::dds {
namespace {

constexpr int kResultDepth = 10;

// Generated types hold `char*` strings; DDS only reads them while writing.
char* Str(const std::string& s) { return const_cast<char*>(s.c_str()); }

std_msgs_msg_dds__Header_ Header(TimestampNs stamp, const std::string& frame) {
  std_msgs_msg_dds__Header_ header;
  header.stamp_ = NsToStamp(stamp);
  header.frame_id_ = Str(frame);
  return header;
}

template <class Seq, class T>
void View(Seq* seq, T* data, std::size_t n) {
  seq->_maximum = static_cast<std::uint32_t>(n);
  seq->_length = static_cast<std::uint32_t>(n);
  seq->_buffer = n == 0 ? nullptr : data;
  seq->_release = false;
}

void Write(dds_entity_t writer, const void* sample, const std::string& topic) {
  Check(dds_write(writer, sample), ("dds_write(" + topic + ")").c_str());
}

}  // namespace

Ros2Publisher::Ros2Publisher(Participant& participant, const DdsConfig& config)
    : frame_(config.map_frame),
      pose_period_s_(config.publish_pose_period_s),
      odom_frame_(config.odom_frame),
      publish_tf_(config.publish_tf) {
  const dds_entity_t pp = participant.handle();
  Qos latched, results;
  SetRos2Qos(latched.get(), "reliable", 1, Durability::kTransientLocal);
  SetRos2Qos(results.get(), "reliable", kResultDepth, Durability::kVolatile);
  try {
    map_ = Create(pp, &nav_msgs_msg_dds__OccupancyGrid__desc, config.map_topic, latched.get());
    pose_ = Create(pp, &geometry_msgs_msg_dds__PoseStamped__desc, config.pose_topic, results.get());
    path_ = Create(pp, &nav_msgs_msg_dds__Path__desc, config.path_topic, results.get());
    loops_ = Create(pp, &visualization_msgs_msg_dds__MarkerArray__desc, config.loops_topic,
                    results.get());
    if (publish_tf_) {  // tf2_ros's QoS: reliable, volatile, keep-last 100
      Qos tf;
      SetRos2Qos(tf.get(), "reliable", 100, Durability::kVolatile);
      tf_ = Create(pp, &tf2_msgs_msg_dds__TFMessage__desc, "/tf", tf.get());
    }
  } catch (...) {
    for (const Writer* w : {&tf_, &loops_, &path_, &pose_, &map_}) {
      if (w->writer > 0) dds_delete(w->writer);
      if (w->topic > 0) dds_delete(w->topic);
    }
    throw;
  }
}

Ros2Publisher::~Ros2Publisher() {
  for (const Writer* w : {&tf_, &loops_, &path_, &pose_, &map_}) {
    if (w->writer > 0) dds_delete(w->writer);
    if (w->topic > 0) dds_delete(w->topic);
  }
}

void Ros2Publisher::PublishMapToOdom(TimestampNs stamp, const Pose2& T_map_odom) {
  if (!publish_tf_) return;
  geometry_msgs_msg_dds__TransformStamped_ t;
  t.header_ = Header(stamp, frame_);
  t.child_frame_id_ = Str(odom_frame_);
  const geometry_msgs_msg_dds__Pose_ pose = PoseToDds(T_map_odom);
  t.transform_.translation_.x_ = pose.position_.x_;
  t.transform_.translation_.y_ = pose.position_.y_;
  t.transform_.translation_.z_ = pose.position_.z_;
  t.transform_.rotation_.x_ = pose.orientation_.x_;
  t.transform_.rotation_.y_ = pose.orientation_.y_;
  t.transform_.rotation_.z_ = pose.orientation_.z_;
  t.transform_.rotation_.w_ = pose.orientation_.w_;
  tf2_msgs_msg_dds__TFMessage_ msg;
  View(&msg.transforms_, &t, 1);
  std::lock_guard<std::mutex> lock(mutex_);
  Write(tf_.writer, &msg, tf_.ros_topic);
}

Ros2Publisher::Writer Ros2Publisher::Create(dds_entity_t participant,
                                            const dds_topic_descriptor_t* desc,
                                            const std::string& ros_topic, const dds_qos_t* qos) {
  Writer w;
  w.ros_topic = ros_topic;
  const std::string dds_name = RosTopicToDds(ros_topic);
  w.topic = Check(dds_create_topic(participant, desc, dds_name.c_str(), nullptr, nullptr),
                  ("dds_create_topic(" + dds_name + ")").c_str());
  const dds_entity_t writer = dds_create_writer(participant, w.topic, qos, nullptr);
  if (writer < 0) {
    dds_delete(w.topic);
    throw DdsError("dds_create_writer(" + dds_name + ")", writer);
  }
  w.writer = writer;
  return w;
}

void Ros2Publisher::PublishMap(const OccupancyGrid& grid, TimestampNs stamp) {
  std::vector<std::int8_t> cells = GridCellsBottomUp(grid);
  nav_msgs_msg_dds__OccupancyGrid_ msg;
  msg.header_ = Header(stamp, frame_);
  msg.info_.map_load_time_ = NsToStamp(stamp);
  msg.info_.resolution_ = static_cast<float>(grid.resolution_m);
  msg.info_.width_ = static_cast<std::uint32_t>(grid.cols);
  msg.info_.height_ = static_cast<std::uint32_t>(grid.rows);
  msg.info_.origin_ = PoseToDds(grid.origin);
  View(&msg.data_, cells.data(), cells.size());
  std::lock_guard<std::mutex> lock(mutex_);
  Write(map_.writer, &msg, map_.ros_topic);
}

bool Ros2Publisher::PublishPose(TimestampNs stamp, const Pose2& T_map_robot, bool final) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!final && has_last_pose_ && pose_period_s_ > 0.0 && stamp >= last_pose_ns_ &&
      NsToSeconds(stamp - last_pose_ns_) < pose_period_s_) {
    return false;
  }
  geometry_msgs_msg_dds__PoseStamped_ msg;
  msg.header_ = Header(stamp, frame_);
  msg.pose_ = PoseToDds(T_map_robot);
  Write(pose_.writer, &msg, pose_.ros_topic);
  has_last_pose_ = true;
  last_pose_ns_ = stamp;
  return true;
}

void Ros2Publisher::PublishPath(TimestampNs stamp,
                                const std::vector<std::pair<TimestampNs, Pose2>>& poses) {
  std::vector<geometry_msgs_msg_dds__PoseStamped_> stamped(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    stamped[i].header_ = Header(poses[i].first, frame_);
    stamped[i].pose_ = PoseToDds(poses[i].second);
  }
  nav_msgs_msg_dds__Path_ msg;
  msg.header_ = Header(stamp, frame_);
  View(&msg.poses_, stamped.data(), stamped.size());
  std::lock_guard<std::mutex> lock(mutex_);
  Write(path_.writer, &msg, path_.ros_topic);
}

void Ros2Publisher::PublishLoops(TimestampNs stamp, const std::vector<LoopSegment>& segments) {
  static const std::string kNamespace = "loops";
  static const std::string kEmpty;
  visualization_msgs_msg_dds__Marker_ markers[2] = {};
  for (auto& m : markers) {
    m.header_ = Header(stamp, frame_);
    m.ns_ = Str(kNamespace);
    m.pose_ = PoseToDds(Pose2{});
    m.texture_resource_ = Str(kEmpty);
    m.texture_.header_ = Header(stamp, frame_);
    m.texture_.format_ = Str(kEmpty);
    m.text_ = Str(kEmpty);
    m.mesh_resource_ = Str(kEmpty);
    m.mesh_file_.filename_ = Str(kEmpty);
  }
  markers[0].action_ = kMarkerDeleteAll;
  std::vector<geometry_msgs_msg_dds__Point_> points;
  points.reserve(2 * segments.size());
  for (const LoopSegment& s : segments) {
    points.push_back({s.first.x_m, s.first.y_m, 0.0});
    points.push_back({s.second.x_m, s.second.y_m, 0.0});
  }
  visualization_msgs_msg_dds__Marker_& lines = markers[1];
  lines.id_ = 0;
  lines.type_ = kMarkerLineList;
  lines.action_ = kMarkerAdd;
  lines.scale_.x_ = 0.02;  // line width in metres
  lines.color_ = {1.0f, 0.5f, 0.0f, 1.0f};
  View(&lines.points_, points.data(), points.size());
  visualization_msgs_msg_dds__MarkerArray_ msg;
  View(&msg.markers_, markers, 2);
  std::lock_guard<std::mutex> lock(mutex_);
  Write(loops_.writer, &msg, loops_.ros_topic);
}

int Ros2Publisher::MatchedSubscribers(const std::string& ros_topic) const {
  for (const Writer* w : {&map_, &pose_, &path_, &loops_}) {
    if (w->ros_topic != ros_topic) continue;
    dds_publication_matched_status_t status;
    if (dds_get_publication_matched_status(w->writer, &status) != DDS_RETCODE_OK) return 0;
    return static_cast<int>(status.current_count);
  }
  return 0;
}

}  // namespace uwbsar::dds
