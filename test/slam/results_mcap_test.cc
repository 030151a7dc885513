// slam::ResultsMcapWriter and MakeSarPreview: the file reads back with the project's own MCAP
// reader with the ROS schemas named and defined (the Python readers check the content end to
// end in test/tools/contract_run_cli_test.cc), grids go out bottom row first, and the preview
// keeps the mosaic's corner and averages observed pixels only.
#include "slam/outputs/results_mcap.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "drivers/rosbag/bag_storage.h"

namespace uwbsar::slam {
namespace {

namespace fs = std::filesystem;

std::string TempFile(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("uwbsar_results_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return (dir / name).string();
}

TEST(ResultsMcapWriterTest, WritesEachTopicWithItsRosSchemaInLogTimeOrder) {
  const std::string path = TempFile("results.mcap");
  {
    ResultsMcapWriter out(path);
    OccupancyGrid grid;
    grid.rows = 2;
    grid.cols = 3;
    grid.cells = {1, 2, 3, 4, 5, 6};  // top row first
    out.WriteTf(100, Pose2{1, 2, 0.5}, Pose2{0, 0, 0});
    out.WriteMap(200, grid);
    out.WritePath(kResultsPathTopic, 200, {{150, Pose2{}}, {200, Pose2{1, 0, 0}}});
    out.WriteLoops(200, {{{0, 0}, {1, 1}}}, {{0, 0}});
    SarPreview sar;
    sar.grey = cv::Mat(2, 2, CV_8U, cv::Scalar(255));
    sar.observed = cv::Mat(2, 2, CV_8U, cv::Scalar(255));
    sar.grid.rows = sar.grid.cols = 2;
    sar.grid.resolution_m = 0.1;
    out.WriteSar(300, sar);
    out.WriteTf(400, Pose2{}, Pose2{});
    EXPECT_EQ(out.messages(), 7u);
  }
  auto reader = rosbag::OpenMcapStorage(path);
  std::map<std::string, std::string> types;
  for (const rosbag::TopicInfo& t : reader->Topics()) {
    types[t.name] = t.type;
    EXPECT_FALSE(t.message_definition.empty()) << t.name;
    EXPECT_EQ(t.definition_encoding, "ros2msg") << t.name;
  }
  EXPECT_EQ(types.at("/map"), "nav_msgs/msg/OccupancyGrid");
  EXPECT_EQ(types.at("/uwbsar/sar"), "nav_msgs/msg/OccupancyGrid");
  EXPECT_EQ(types.at("/uwbsar/sar_image"), "sensor_msgs/msg/Image");
  EXPECT_EQ(types.at("/path"), "nav_msgs/msg/Path");
  EXPECT_EQ(types.at("/uwbsar/loops"), "visualization_msgs/msg/MarkerArray");
  EXPECT_EQ(types.at("/tf"), "tf2_msgs/msg/TFMessage");
  rosbag::StorageMessage msg;
  TimestampNs previous = 0;
  int count = 0;
  while (reader->Next(&msg)) {
    EXPECT_GE(msg.log_time_ns, previous);
    previous = msg.log_time_ns;
    ++count;
    if (reader->Topics()[static_cast<std::size_t>(msg.topic)].name != "/map") continue;
    // The last 6 bytes are the cells, the bottom row (4 5 6) first.
    ASSERT_GE(msg.size, 6u);
    const std::uint8_t* cells = msg.data + msg.size - 6;
    EXPECT_EQ(std::vector<int>(cells, cells + 6), (std::vector<int>{4, 5, 6, 1, 2, 3}));
  }
  EXPECT_EQ(count, 7);
  fs::remove_all(fs::path(path).parent_path());
}

TEST(ResultsMcapWriterTest, AnUnwritableFileIsAnInputErrorNamingIt) {
  try {
    ResultsMcapWriter out("/nonexistent-folder/results.mcap");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/results.mcap"), std::string::npos)
        << e.what();
  }
}

TEST(SarPreviewTest, AveragesObservedPixelsInBlocksAndKeepsTheTopLeftCorner) {
  SarMosaic sar;
  sar.map = cv::Mat(5, 5, CV_32F, cv::Scalar(4));
  sar.observed = cv::Mat(5, 5, CV_8U, cv::Scalar(255));
  // The first 2 x 2 block: one observed pixel of 4, three unobserved (zero) ones.
  sar.map(cv::Rect(0, 0, 2, 2)) = 0.0f;
  sar.observed(cv::Rect(0, 0, 2, 2)) = 0;
  sar.map.at<float>(0, 0) = 4.0f;
  sar.observed.at<unsigned char>(0, 0) = 255;
  // The last block is pixel (4, 4) and padding: 1.
  sar.map.at<float>(4, 4) = 1.0f;
  sar.grid.rows = sar.grid.cols = 5;
  sar.grid.resolution_m = 0.01;
  sar.grid.x0_m = 10.005;                         // the left edge at x = 10 m
  sar.grid.y0_m = 4.995;                          // the top edge at y = 5 m
  const SarPreview p = MakeSarPreview(sar, 9.0);  // 25 pixels -> blocks of 2 -> 3 x 3
  ASSERT_EQ(p.grey.rows, 3);
  ASSERT_EQ(p.grey.cols, 3);
  EXPECT_DOUBLE_EQ(p.grid.resolution_m, 0.02);
  EXPECT_NEAR(p.grid.x0_m - 0.5 * p.grid.resolution_m, 10.0, 1e-12);
  EXPECT_NEAR(p.grid.y0_m + 0.5 * p.grid.resolution_m, 5.0, 1e-12);
  // Unobserved pixels dilute no block: the first is 4 (full scale), padding does not make the
  // last 1/4 of it; it is 1 (a quarter of full scale).
  EXPECT_EQ(p.grey.at<unsigned char>(0, 0), 255);
  EXPECT_EQ(p.grey.at<unsigned char>(0, 2), 255);
  EXPECT_NEAR(p.grey.at<unsigned char>(2, 2), 64, 1);
  EXPECT_EQ(cv::countNonZero(p.observed), 9);
  // Small mosaics pass unchanged.
  const SarPreview same = MakeSarPreview(sar, 25.0);
  EXPECT_EQ(same.grey.rows, 5);
  EXPECT_DOUBLE_EQ(same.grid.x0_m, sar.grid.x0_m);
  EXPECT_EQ(same.observed.at<unsigned char>(0, 1), 0);
}

// The Foxglove layout and the RViz config in config/ name the topics the writer writes: a
// renamed topic would leave users an empty view.
TEST(ResultsViewerConfigTest, FoxgloveLayoutAndRvizConfigShowTheTopicsWritten) {
  const std::set<std::string> written = {
      kResultsMapTopic,         kResultsSarTopic,   kResultsSarImageTopic, kResultsPathTopic,
      kResultsGroundTruthTopic, kResultsLoopsTopic, kResultsTfTopic};
  std::set<std::string> foxglove;
  std::ifstream layout_file(std::string(UWBSAR_SOURCE_DIR) + "/config/foxglove_layout.json");
  const nlohmann::json layout = nlohmann::json::parse(layout_file);
  for (const auto& [id, panel] : layout.at("configById").items()) {
    if (panel.contains("topics")) {
      for (const auto& [topic, settings] : panel.at("topics").items()) foxglove.insert(topic);
    }
    if (panel.contains("imageMode")) foxglove.insert(panel["imageMode"].at("imageTopic"));
  }
  std::set<std::string> rviz;
  const YAML::Node config = YAML::LoadFile(std::string(UWBSAR_SOURCE_DIR) + "/config/uwbsar.rviz");
  for (const YAML::Node& display : config["Visualization Manager"]["Displays"]) {
    if (display["Topic"]) rviz.insert(display["Topic"]["Value"].as<std::string>());
  }
  EXPECT_EQ(config["Visualization Manager"]["Global Options"]["Fixed Frame"].as<std::string>(),
            "map");
  for (const std::set<std::string>* shown : {&foxglove, &rviz}) {
    for (const std::string& topic : *shown) EXPECT_EQ(written.count(topic), 1u) << topic;
    for (const char* topic : {kResultsMapTopic, kResultsSarTopic, kResultsPathTopic,
                              kResultsLoopsTopic, kResultsSarImageTopic}) {
      EXPECT_EQ(shown->count(topic), 1u) << topic;
    }
  }
}

}  // namespace
}  // namespace uwbsar::slam
