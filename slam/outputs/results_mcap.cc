#include "slam/outputs/results_mcap.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "core/errors.h"
#include "core/log.h"
#include "drivers/rosbag/bag_writer.h"
#include "drivers/rosbag/ros_codecs.h"

namespace uwbsar::slam {
namespace {

constexpr const char* kMapFrame = "map";
constexpr const char* kOdomFrame = "odom";
constexpr const char* kBaseFrame = "base_link";

rosbag::RosHeader Header(TimestampNs stamp_ns, const char* frame) {
  return {rosbag::ToRosTime(stamp_ns), frame};
}

rosbag::RosPose ToRosPose(const Pose2& p) {
  rosbag::RosPose out;
  out.position = {p.x_m, p.y_m, 0.0};
  out.orientation = rosbag::QuaternionFromYaw(p.yaw_rad);
  return out;
}

rosbag::TransformStamped Transform(TimestampNs stamp, const char* parent, const char* child,
                                   const Pose2& T_parent_child) {
  rosbag::TransformStamped t;
  t.header = Header(stamp, parent);
  t.child_frame_id = child;
  t.translation = {T_parent_child.x_m, T_parent_child.y_m, 0.0};
  t.rotation = rosbag::QuaternionFromYaw(T_parent_child.yaw_rad);
  return t;
}

rosbag::OccupancyGridMessage GridMessage(TimestampNs stamp, const OccupancyGrid& grid) {
  rosbag::OccupancyGridMessage msg;
  msg.header = Header(stamp, kMapFrame);
  msg.map_load_time = msg.header.stamp;
  msg.resolution = static_cast<float>(grid.resolution_m);
  msg.width = static_cast<std::uint32_t>(grid.cols);
  msg.height = static_cast<std::uint32_t>(grid.rows);
  msg.origin = ToRosPose(grid.origin);
  msg.data = GridCellsBottomUp(grid);
  return msg;
}

/// QoS rosbag2 stores for a transient-local publisher (map_server's /map); otherwise as
/// DefaultQosProfileYaml (volatile).
std::string LatchedQosProfileYaml() {
  std::string yaml = rosbag::DefaultQosProfileYaml();
  const std::string volatile_durability = "durability: 2";
  yaml.replace(yaml.find(volatile_durability), volatile_durability.size(), "durability: 1");
  return yaml;
}

}  // namespace

SarPreview MakeSarPreview(const SarMosaic& sar, double max_pixels) {
  SarPreview out;
  if (sar.map.empty()) return out;
  const double pixels = static_cast<double>(sar.map.rows) * sar.map.cols;
  const int factor = std::max(1, static_cast<int>(std::ceil(std::sqrt(pixels / max_pixels))));
  cv::Mat weight;
  sar.observed.convertTo(weight, CV_32F, 1.0 / 255.0);
  cv::Mat weighted = sar.map.mul(weight);
  if (factor > 1) {
    // Pad to whole blocks (unobserved), then average each block: its top-left corner stays.
    const int pad_rows = (factor - sar.map.rows % factor) % factor;
    const int pad_cols = (factor - sar.map.cols % factor) % factor;
    cv::copyMakeBorder(weighted, weighted, 0, pad_rows, 0, pad_cols, cv::BORDER_CONSTANT, 0);
    cv::copyMakeBorder(weight, weight, 0, pad_rows, 0, pad_cols, cv::BORDER_CONSTANT, 0);
    const cv::Size size(weighted.cols / factor, weighted.rows / factor);
    cv::resize(weighted, weighted, size, 0, 0, cv::INTER_AREA);
    cv::resize(weight, weight, size, 0, 0, cv::INTER_AREA);
  }
  cv::Mat mean;
  cv::divide(weighted, cv::max(weight, 1e-12), mean);
  out.observed = weight > 0;
  std::vector<float> values;
  for (int r = 0; r < mean.rows; ++r) {
    for (int c = 0; c < mean.cols; ++c) {
      if (out.observed.at<unsigned char>(r, c)) values.push_back(mean.at<float>(r, c));
    }
  }
  float top = 1.0f;
  if (!values.empty()) {
    const auto k = static_cast<std::ptrdiff_t>(0.995 * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + k, values.end());
    top = std::max(values[static_cast<std::size_t>(k)], 1e-12f);
  }
  mean.convertTo(out.grey, CV_8U, 255.0 / top);
  out.grey.setTo(0, ~out.observed);
  out.grid = sar.grid;
  out.grid.resolution_m = sar.grid.resolution_m * factor;
  out.grid.rows = mean.rows;
  out.grid.cols = mean.cols;
  // Same top-left corner: the first block's centre is (factor - 1) / 2 pixels further in.
  out.grid.x0_m = sar.grid.x0_m + 0.5 * (factor - 1) * sar.grid.resolution_m;
  out.grid.y0_m = sar.grid.y0_m - 0.5 * (factor - 1) * sar.grid.resolution_m;
  return out;
}

ResultsMcapWriter::ResultsMcapWriter(const std::string& path) : path_(path) {
  rosbag::McapWriteOptions options;
  storage_ = rosbag::CreateMcapStorage(path, options);
}

ResultsMcapWriter::~ResultsMcapWriter() {
  if (!storage_) return;
  try {
    Close();
  } catch (const std::exception& e) {
    Log(LogLevel::kWarning, path_ + ": " + e.what());
  }
}

void ResultsMcapWriter::Close() {
  if (!storage_) return;
  auto storage = std::move(storage_);
  storage->Close("");
}

int ResultsMcapWriter::Topic(const std::string& name, const char* type, bool latched) {
  const auto it = topics_.find(name);
  if (it != topics_.end()) return it->second;
  rosbag::TopicInfo topic;
  topic.name = name;
  topic.type = type;
  topic.offered_qos_profiles = latched ? LatchedQosProfileYaml() : rosbag::DefaultQosProfileYaml();
  topic.message_definition = rosbag::RosMessageDefinition(type);
  topic.definition_encoding = "ros2msg";
  storage_->AddTopic(topic);
  const int id = static_cast<int>(topics_.size());
  topics_.emplace(name, id);
  return id;
}

template <class Message>
void ResultsMcapWriter::Write(int topic, TimestampNs stamp, const Message& msg) {
  if (!storage_) throw std::logic_error(path_ + ": written after Close()");
  rosbag::EncodeCdr(msg, &buffer_);
  storage_->Write(topic, stamp, buffer_.data(), buffer_.size());
  ++messages_;
}

void ResultsMcapWriter::WriteMap(TimestampNs stamp, const OccupancyGrid& grid) {
  Write(Topic(kResultsMapTopic, rosbag::kOccupancyGridType, true), stamp, GridMessage(stamp, grid));
}

void ResultsMcapWriter::WriteSar(TimestampNs stamp, const SarPreview& sar) {
  if (sar.grey.empty()) return;
  OccupancyGrid grid;
  grid.rows = sar.grey.rows;
  grid.cols = sar.grey.cols;
  grid.resolution_m = sar.grid.resolution_m;
  grid.origin = Pose2{sar.grid.x0_m - 0.5 * sar.grid.resolution_m,
                      sar.grid.y0_m - (sar.grid.rows - 0.5) * sar.grid.resolution_m, 0.0};
  grid.cells.resize(static_cast<std::size_t>(grid.rows) * grid.cols);
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      grid.cells[static_cast<std::size_t>(r) * grid.cols + c] =
          sar.observed.at<unsigned char>(r, c)
              ? static_cast<std::int8_t>(
                    std::lround(sar.grey.at<unsigned char>(r, c) * 100.0 / 255))
              : OccupancyGrid::kUnknown;
    }
  }
  Write(Topic(kResultsSarTopic, rosbag::kOccupancyGridType, true), stamp, GridMessage(stamp, grid));

  rosbag::ImageMessage image;
  image.header = Header(stamp, kMapFrame);
  image.height = static_cast<std::uint32_t>(sar.grey.rows);
  image.width = static_cast<std::uint32_t>(sar.grey.cols);
  image.encoding = "mono8";
  image.step = image.width;
  const cv::Mat grey = sar.grey.isContinuous() ? sar.grey : sar.grey.clone();
  image.data.assign(grey.data, grey.data + grey.total());
  Write(Topic(kResultsSarImageTopic, rosbag::kImageType, true), stamp, image);
}

void ResultsMcapWriter::WritePath(const std::string& topic, TimestampNs stamp,
                                  const std::vector<std::pair<TimestampNs, Pose2>>& poses) {
  rosbag::PathMessage msg;
  msg.header = Header(stamp, kMapFrame);
  msg.poses.reserve(poses.size());
  for (const auto& [t, pose] : poses) msg.poses.push_back({Header(t, kMapFrame), ToRosPose(pose)});
  Write(Topic(topic, rosbag::kPathType), stamp, msg);
}

void ResultsMcapWriter::WriteLoops(TimestampNs stamp,
                                   const std::vector<std::pair<Point2, Point2>>& loops,
                                   const std::vector<Point2>& keyframes) {
  rosbag::MarkerArray msg;
  rosbag::Marker clear;
  clear.header = Header(stamp, kMapFrame);
  clear.action = rosbag::Marker::kDeleteAll;
  msg.markers.push_back(clear);
  rosbag::Marker lines;
  lines.header = Header(stamp, kMapFrame);
  lines.ns = "loops";
  lines.type = rosbag::Marker::kLineList;
  lines.scale = {0.03, 0.0, 0.0};              // line width, m
  lines.color = {0.835f, 0.369f, 0.0f, 1.0f};  // vermillion (Okabe-Ito)
  for (const auto& [a, b] : loops) {
    lines.points.push_back({a.x_m, a.y_m, 0.05});
    lines.points.push_back({b.x_m, b.y_m, 0.05});
  }
  if (!lines.points.empty()) msg.markers.push_back(lines);
  rosbag::Marker anchors;
  anchors.header = Header(stamp, kMapFrame);
  anchors.ns = "keyframes";
  anchors.id = 1;
  anchors.type = rosbag::Marker::kSphereList;
  anchors.scale = {0.08, 0.08, 0.08};
  anchors.color = {0.0f, 0.447f, 0.698f, 1.0f};  // blue (Okabe-Ito)
  for (const Point2& p : keyframes) anchors.points.push_back({p.x_m, p.y_m, 0.05});
  if (!anchors.points.empty()) msg.markers.push_back(anchors);
  Write(Topic(kResultsLoopsTopic, rosbag::kMarkerArrayType), stamp, msg);
}

void ResultsMcapWriter::WriteTf(TimestampNs stamp, const Pose2& T_map_odom,
                                const Pose2& T_odom_base) {
  rosbag::TfMessage msg;
  msg.transforms.push_back(Transform(stamp, kMapFrame, kOdomFrame, T_map_odom));
  msg.transforms.push_back(Transform(stamp, kOdomFrame, kBaseFrame, T_odom_base));
  Write(Topic(kResultsTfTopic, rosbag::kTfMessageType), stamp, msg);
}

}  // namespace uwbsar::slam
