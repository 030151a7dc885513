// results.mcap: what a run produced, as ROS 2 messages in one MCAP file (ros2 profile, CDR,
// ros2msg schemas), so Foxglove opens it and `ros2 bag play` hands it to RViz2 and Nav2:
//   /map                nav_msgs/OccupancyGrid    the navigation grid (map.pgm), latched
//   /uwbsar/sar         nav_msgs/OccupancyGrid    the SAR mosaic, 0..100 = its grey level
//   /uwbsar/sar_image   sensor_msgs/Image (mono8) the same mosaic as an image, row 0 = top
//   /path, ...          nav_msgs/Path             trajectories (stamped poses)
//   /uwbsar/loops       visualization_msgs/MarkerArray  accepted loops (LINE_LIST) and
//                                                        keyframe anchors (SPHERE_LIST)
//   /tf                 tf2_msgs/TFMessage        map -> odom and odom -> base_link
// Every message is in the frame `map` unless said otherwise. The caller writes in time order
// (a reader plays the file by log time; /tf must not go back). The file is created at `path`
// as given: callers write it into a staging folder that is committed as one set.
#pragma once

#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/pose2.h"
#include "core/types.h"
#include "drivers/rosbag/bag_storage.h"
#include "imaging/image_grid.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar::slam {

inline constexpr const char* kResultsMapTopic = "/map";
inline constexpr const char* kResultsSarTopic = "/uwbsar/sar";
inline constexpr const char* kResultsSarImageTopic = "/uwbsar/sar_image";
inline constexpr const char* kResultsPathTopic = "/path";
inline constexpr const char* kResultsGroundTruthTopic = "/ground_truth/path";
inline constexpr const char* kResultsLoopsTopic = "/uwbsar/loops";
inline constexpr const char* kResultsTfTopic = "/tf";

/// The SAR mosaic as the map writes it: float intensity, observed mask (CV_8U, 255 where a
/// tile covered the pixel), and its pixel geometry in the map frame.
struct SarMosaic {
  cv::Mat map;
  cv::Mat observed;
  ImageGrid grid;
};

/// The mosaic averaged over square blocks (only observed pixels count) so that it has at most
/// `max_pixels` pixels; its top-left corner stays where it was. `grey` (CV_8U) is the
/// intensity clipped at the 99.5th percentile of the observed pixels; `observed` as above.
struct SarPreview {
  cv::Mat grey;
  cv::Mat observed;
  ImageGrid grid;
};
SarPreview MakeSarPreview(const SarMosaic& sar, double max_pixels);

class ResultsMcapWriter {
 public:
  /// Creates the file; throws InputError naming it when it cannot.
  explicit ResultsMcapWriter(const std::string& path);
  ~ResultsMcapWriter();
  ResultsMcapWriter(const ResultsMcapWriter&) = delete;
  ResultsMcapWriter& operator=(const ResultsMcapWriter&) = delete;

  /// /map: `grid` with its rows in ROS order (bottom row first).
  void WriteMap(TimestampNs stamp, const OccupancyGrid& grid);
  /// /uwbsar/sar (unobserved -1, else grey * 100 / 255) and /uwbsar/sar_image.
  void WriteSar(TimestampNs stamp, const SarPreview& sar);
  /// A nav_msgs/Path on `topic`, one PoseStamped per sample.
  void WritePath(const std::string& topic, TimestampNs stamp,
                 const std::vector<std::pair<TimestampNs, Pose2>>& poses);
  /// /uwbsar/loops: DELETEALL, the loops as one LINE_LIST (ns "loops") and the keyframe
  /// anchors as one SPHERE_LIST (ns "keyframes").
  void WriteLoops(TimestampNs stamp, const std::vector<std::pair<Point2, Point2>>& loops,
                  const std::vector<Point2>& keyframes);
  /// /tf: map -> odom and odom -> base_link at `stamp`.
  void WriteTf(TimestampNs stamp, const Pose2& T_map_odom, const Pose2& T_odom_base);
  /// Finishes the file (the destructor does it too, logging instead of throwing).
  void Close();

  const std::string& path() const { return path_; }
  std::uint64_t messages() const { return messages_; }

 private:
  /// The topic's id, registering it on first use (`latched`: transient local, as
  /// map_server offers /map, so RViz2's map display receives it from `ros2 bag play`).
  int Topic(const std::string& name, const char* type, bool latched = false);
  template <class Message>
  void Write(int topic, TimestampNs stamp, const Message& msg);

  std::string path_;
  std::unique_ptr<rosbag::StorageWriter> storage_;
  std::map<std::string, int> topics_;
  std::vector<std::uint8_t> buffer_;
  std::uint64_t messages_ = 0;
};

}  // namespace uwbsar::slam
