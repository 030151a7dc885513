// `uwbsar check`'s job (slam/jobs/check_job.h) on small bags written here: one as the robot records
// it, and six each broken in one way, whose problem the check must name.
#include "slam/jobs/check_job.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <vector>

#include "drivers/rosbag/bag_writer.h"
#include "drivers/rosbag/ros_codecs.h"

namespace uwbsar::slam {
namespace {

namespace fs = std::filesystem;

/// A recording of the robot driving straight at 0.5 m/s for 4 s: both radars at 100 Hz,
/// odometry at 50 Hz, header stamps equal to the receive times, as `uwbsar simulate` writes.
struct TestBag {
  int samples = 1000;
  double odometry_hz = 50.0;
  std::string right_topic = "/UWBradar1/readings";
  bool right_messages = true;              ///< false: the topic is declared but holds nothing
  std::optional<double> header_back_at_s;  ///< odometry header stamps step back 1 s from here
  std::optional<double> jump_at_s;         ///< odometry x jumps 5 m from here on
  bool ground_truth = true;
};

std::string WriteBag(const std::string& name, const TestBag& spec) {
  const fs::path dir =
      fs::temp_directory_path() / ("uwbsar_check_job_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string bag = (dir / "bag").string();
  rosbag::BagWriter writer(bag);
  const int left = writer.AddTopic("/UWBradar0/readings", rosbag::kFloat32MultiArrayType);
  const int right = writer.AddTopic(spec.right_topic, rosbag::kFloat32MultiArrayType);
  const int odom = writer.AddTopic("/odom", rosbag::kOdometryType);
  const int truth =
      spec.ground_truth ? writer.AddTopic("/ground_truth/odom", rosbag::kOdometryType) : -1;
  const TimestampNs start = SecondsToNs(1700000000.0);
  const TimestampNs scan_step = SecondsToNs(0.01);
  const TimestampNs odom_step = SecondsToNs(1.0 / spec.odometry_hz);
  rosbag::Float32MultiArray scan;
  scan.data.assign(static_cast<std::size_t>(spec.samples), 0.0f);
  scan.data[static_cast<std::size_t>(spec.samples / 2)] = 0.5f;  // an echo: not a silent radar
  TimestampNs next_scan = start, next_odom = start;
  const TimestampNs end = start + SecondsToNs(4.0);
  while (next_scan <= end || next_odom <= end) {
    if (next_odom <= next_scan) {
      const double t = NsToSeconds(next_odom - start);
      rosbag::Odometry msg;
      msg.position = {0.5 * t + (spec.jump_at_s && t >= *spec.jump_at_s ? 5.0 : 0.0), 0.0, 0.0};
      msg.orientation = rosbag::QuaternionFromYaw(0.0);
      const TimestampNs header =
          next_odom - (spec.header_back_at_s && t >= *spec.header_back_at_s ? SecondsToNs(1) : 0);
      msg.header.stamp.sec = static_cast<std::int32_t>(header / 1000000000);
      msg.header.stamp.nanosec = static_cast<std::uint32_t>(header % 1000000000);
      writer.WriteMessage(odom, next_odom, msg);
      if (truth >= 0) writer.WriteMessage(truth, next_odom, msg);
      next_odom += odom_step;
    } else {
      writer.WriteMessage(left, next_scan, scan);
      if (spec.right_messages) writer.WriteMessage(right, next_scan, scan);
      next_scan += scan_step;
    }
  }
  writer.Close();
  return bag;
}

/// The texts of the lines of `level`, one a line.
std::string LinesOf(const BagCheck& check, CheckLevel level) {
  std::string text;
  for (const CheckLine& line : check.lines) {
    if (line.level == level) text += line.text + "\n";
  }
  return text;
}

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(CheckJobTest, RecordingAsTheRobotMakesItIsAllOk) {
  const BagCheck check = CheckBag(Config{}, WriteBag("ok", {}));
  EXPECT_EQ(check.Count(CheckLevel::kError), 0) << LinesOf(check, CheckLevel::kError);
  EXPECT_EQ(check.Count(CheckLevel::kWarning), 0) << LinesOf(check, CheckLevel::kWarning);
  const std::string ok = LinesOf(check, CheckLevel::kOk);
  EXPECT_TRUE(Has(ok, "radar right: /UWBradar1/readings, 401 scans at 100.0 Hz")) << ok;
  EXPECT_TRUE(Has(ok, "every scan has 1000 samples (radars[left].num_samples)")) << ok;
  EXPECT_TRUE(Has(ok, "odometry: /odom, 201 messages at 50.0 Hz")) << ok;
  EXPECT_TRUE(Has(ok, "odometry covers all 802 scans")) << ok;
  EXPECT_TRUE(Has(LinesOf(check, CheckLevel::kInfo), "ground truth: /ground_truth/odom, 201 poses"))
      << LinesOf(check, CheckLevel::kInfo);
}

TEST(CheckJobTest, MissingTopicIsAnErrorNamingTheKeyAndTheClosestTopic) {
  TestBag spec;
  spec.right_topic = "/UWBradar1/reading";
  const BagCheck check = CheckBag(Config{}, WriteBag("missing", spec));
  ASSERT_EQ(check.Count(CheckLevel::kError), 1) << LinesOf(check, CheckLevel::kError);
  EXPECT_EQ(LinesOf(check, CheckLevel::kError),
            "radar right: no topic /UWBradar1/readings (radars[right].topic) in the bag (did "
            "you mean '/UWBradar1/reading'?)\n");
}

TEST(CheckJobTest, WrongSampleCountIsAnErrorNamingBothCounts) {
  TestBag spec;
  spec.samples = 500;
  const BagCheck check = CheckBag(Config{}, WriteBag("samples", spec));
  const std::string errors = LinesOf(check, CheckLevel::kError);
  EXPECT_EQ(check.Count(CheckLevel::kError), 2) << errors;  // each radar
  EXPECT_TRUE(Has(errors,
                  "radar left: 401 of 401 scans do not have 1000 samples "
                  "(radars[left].num_samples); the first has 500, 0.00 s into the bag: map drops"))
      << errors;
}

TEST(CheckJobTest, RadarTopicWithoutMessagesIsAnError) {
  TestBag spec;
  spec.right_messages = false;
  const BagCheck check = CheckBag(Config{}, WriteBag("empty", spec));
  EXPECT_EQ(LinesOf(check, CheckLevel::kError),
            "radar right: /UWBradar1/readings holds no messages: map images nothing from "
            "this radar\n");
}

TEST(CheckJobTest, OdometryTenTimesSlowerThanTheScansIsAWarning) {
  TestBag spec;
  spec.odometry_hz = 10.0;
  const BagCheck check = CheckBag(Config{}, WriteBag("slow", spec));
  EXPECT_EQ(check.Count(CheckLevel::kError), 0) << LinesOf(check, CheckLevel::kError);
  EXPECT_TRUE(Has(LinesOf(check, CheckLevel::kWarning),
                  "odometry at 10.0 Hz is 10.0 times slower than the scans (100.0 Hz)"))
      << LinesOf(check, CheckLevel::kWarning);
}

TEST(CheckJobTest, OdometryStampsGoingBackAreAnError) {
  TestBag spec;
  spec.header_back_at_s = 2.0;
  const BagCheck check = CheckBag(Config{}, WriteBag("back", spec));
  EXPECT_EQ(LinesOf(check, CheckLevel::kError),
            "odometry header stamps go back once, by up to 0.980 s; the first at message 100, "
            "2.00 s into the bag: the order received (which map follows) is not the order "
            "stamped (two publishers on /odom, or a clock stepped back?)\n");
}

TEST(CheckJobTest, FiveMetreOdometryJumpIsAWarningNamingWhere) {
  TestBag spec;
  spec.jump_at_s = 3.0;
  const BagCheck check = CheckBag(Config{}, WriteBag("jump", spec));
  EXPECT_EQ(check.Count(CheckLevel::kError), 0) << LinesOf(check, CheckLevel::kError);
  EXPECT_EQ(LinesOf(check, CheckLevel::kWarning),
            "odometry jumps once (largest 5.010 m, message 150, 3.00 s into the bag; "
            "gating.max_odom_jump_m 0.5 m): map takes each jump as no motion\n");
}

}  // namespace
}  // namespace uwbsar::slam
