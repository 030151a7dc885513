#include "test/drivers/bag_test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <random>

#include "drivers/rosbag/robot_bag.h"
#include "drivers/rosbag/ros_codecs.h"

namespace uwbsar::rosbag::testing {
namespace fs = std::filesystem;

TimestampNs RadarTime(int sensor, int k) { return kT0 + k * 25000000LL + sensor * 5000000LL; }

std::vector<float> RadarSamples(int sensor, int k) {
  std::vector<float> v(kNumSamples);
  for (int i = 0; i < kNumSamples; ++i) {
    v[static_cast<std::size_t>(i)] =
        static_cast<float>(((k * 37 + i * 11 + sensor * 101) % 1000) / 64.0 - 7.5);
  }
  return v;
}

TimestampNs OdomTime(int i) { return kT0 + i * 20000000LL + 1000000LL; }
Pose2 OdomPose(int i) { return Pose2{i * 0.125, -i * 0.0625, (i - 3) * 0.1}; }
TimestampNs GroundTruthTime(int j) { return kT0 + j * 40000000LL + 2000000LL; }
Pose2 GroundTruthPose(int j) { return Pose2{j * 0.25, j * 0.0625, -j * 0.05}; }
static TimestampNs LaserTime(int j) { return kT0 + j * 50000000LL + 3000000LL; }
static TimestampNs TfTime(int j) { return kT0 + j * 60000000LL + 4000000LL; }
static TimestampNs ChatterTime(int j) { return kT0 + j * 70000000LL + 6000000LL; }

static std::array<double, 36> OdomCovariance(int i) {
  std::array<double, 36> c{};
  for (int r = 0; r < 36; r += 7) c[static_cast<std::size_t>(r)] = 0.01 * (i + 1);
  return c;
}

std::string SourceDir() { return UWBSAR_SOURCE_DIR; }
std::string FixtureDir() { return SourceDir() + "/test/data/bags"; }

TempDir::TempDir() {
  std::random_device rd;
  path = (fs::temp_directory_path() / ("uwbsar_bag_test_" + std::to_string(rd()))).string();
  fs::create_directories(path);
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path, ec);
}

namespace {

struct Checker : RobotBagVisitor {
  std::vector<RadarScan> scans;
  std::vector<OdometrySample> odom, gt;
  std::vector<Odometry> odom_msgs;
  std::vector<LaserScan> lasers;
  std::vector<TfMessage> tfs;
  std::vector<TimestampNs> times;
  void OnRadarScan(const RadarScan& s) override { scans.push_back(s); }
  void OnOdometry(const OdometrySample& o) override { odom.push_back(o); }
  void OnGroundTruth(const OdometrySample& o) override { gt.push_back(o); }
  void OnOdometryMessage(const MessageContext& c, const Odometry& m) override {
    if (c.topic == "/odom") odom_msgs.push_back(m);
  }
  void OnLaserScan(const MessageContext&, const LaserScan& m) override { lasers.push_back(m); }
  void OnTf(const MessageContext&, const TfMessage& m) override { tfs.push_back(m); }
  void OnFloat32MultiArray(const MessageContext& c, const Float32MultiArray&) override {
    times.push_back(c.log_time_ns);
  }
};

}  // namespace

void ExpectFixtureContent(const std::string& path) {
  Checker c;
  const RobotBagStats stats = ReadRobotBag(path, RobotBagOptions{}, c);
  EXPECT_EQ(stats.messages, static_cast<std::uint64_t>(kNumMessages));
  EXPECT_EQ(stats.skipped, static_cast<std::uint64_t>(kNumChatter));
  EXPECT_EQ(stats.skipped_by_type.count("std_msgs/msg/String"), 1u);
  ASSERT_EQ(c.scans.size(), static_cast<std::size_t>(2 * kNumScans));
  // Scans arrive in time order: sensor 0 at +0 ms, sensor 1 at +5 ms of each 25 ms.
  for (int k = 0; k < kNumScans; ++k) {
    for (int s = 0; s < 2; ++s) {
      const RadarScan& scan = c.scans[static_cast<std::size_t>(2 * k + s)];
      EXPECT_EQ(scan.sensor_id, s);
      EXPECT_EQ(scan.stamp_ns, RadarTime(s, k));
      EXPECT_EQ(scan.samples, RadarSamples(s, k)) << "scan " << k << " sensor " << s;
    }
  }
  ASSERT_EQ(c.odom.size(), static_cast<std::size_t>(kNumOdom));
  for (int i = 0; i < kNumOdom; ++i) {
    const OdometrySample& o = c.odom[static_cast<std::size_t>(i)];
    EXPECT_EQ(o.stamp_ns, OdomTime(i));
    EXPECT_EQ(o.T_world_robot.x_m, OdomPose(i).x_m);
    EXPECT_EQ(o.T_world_robot.y_m, OdomPose(i).y_m);
    EXPECT_NEAR(o.T_world_robot.yaw_rad, OdomPose(i).yaw_rad, 1e-12);
    EXPECT_EQ(o.linear_velocity_mps, 0.25);
    EXPECT_EQ(o.angular_velocity_radps, 0.1 * (i % 3));
    const Odometry& m = c.odom_msgs[static_cast<std::size_t>(i)];
    EXPECT_EQ(m.header.frame_id, "odom");
    EXPECT_EQ(m.child_frame_id, "base_link");
    EXPECT_EQ(static_cast<TimestampNs>(m.header.stamp.sec) * 1000000000 + m.header.stamp.nanosec,
              OdomTime(i));
    EXPECT_EQ(m.pose_covariance, OdomCovariance(i));
    EXPECT_EQ(m.orientation.z, std::sin(0.5 * OdomPose(i).yaw_rad));
    EXPECT_EQ(m.orientation.w, std::cos(0.5 * OdomPose(i).yaw_rad));
  }
  ASSERT_EQ(c.gt.size(), static_cast<std::size_t>(kNumGroundTruth));
  for (int j = 0; j < kNumGroundTruth; ++j) {
    EXPECT_EQ(c.gt[static_cast<std::size_t>(j)].stamp_ns, GroundTruthTime(j));
    EXPECT_EQ(c.gt[static_cast<std::size_t>(j)].T_world_robot.x_m, GroundTruthPose(j).x_m);
    EXPECT_NEAR(c.gt[static_cast<std::size_t>(j)].T_world_robot.yaw_rad, GroundTruthPose(j).yaw_rad,
                1e-12);
  }
  ASSERT_EQ(c.lasers.size(), static_cast<std::size_t>(kNumLaser));
  for (int j = 0; j < kNumLaser; ++j) {
    const LaserScan& l = c.lasers[static_cast<std::size_t>(j)];
    ASSERT_EQ(l.ranges.size(), 16u);
    EXPECT_EQ(l.ranges[3], 1.0f + 0.5f * 3 + static_cast<float>(j));
    EXPECT_EQ(l.intensities.size(), j == 1 ? 16u : 0u);
    EXPECT_EQ(l.angle_increment, 0.1875f);
    EXPECT_EQ(l.range_max, 8.0f);
    EXPECT_EQ(l.header.frame_id, "laser");
  }
  ASSERT_EQ(c.tfs.size(), static_cast<std::size_t>(kNumTf));
  ASSERT_EQ(c.tfs[1].transforms.size(), 2u);
  EXPECT_EQ(c.tfs[1].transforms[1].child_frame_id, "radar_left");
  EXPECT_EQ(c.tfs[1].transforms[1].translation.y, 0.18);
  EXPECT_NEAR(YawFromQuaternion(c.tfs[1].transforms[1].rotation), 1.5, 1e-12);
  EXPECT_TRUE(std::is_sorted(c.times.begin(), c.times.end()));
}

void WriteFixtureBag(const std::string& dir, const BagWriterOptions& options) {
  struct Item {
    TimestampNs t;
    std::string topic;
    int kind, a, b;
  };
  std::vector<Item> items;
  const char* radar_topics[] = {"/UWBradar0/readings", "/UWBradar1/readings"};
  for (int s = 0; s < 2; ++s) {
    for (int k = 0; k < kNumScans; ++k)
      items.push_back({RadarTime(s, k), radar_topics[s], 0, s, k});
  }
  for (int i = 0; i < kNumOdom; ++i) items.push_back({OdomTime(i), "/odom", 1, i, 0});
  for (int j = 0; j < kNumGroundTruth; ++j)
    items.push_back({GroundTruthTime(j), "/ground_truth/odom", 2, j, 0});
  for (int j = 0; j < kNumLaser; ++j) items.push_back({LaserTime(j), "/scan", 3, j, 0});
  for (int j = 0; j < kNumTf; ++j) items.push_back({TfTime(j), "/tf", 4, j, 0});
  for (int j = 0; j < kNumChatter; ++j) items.push_back({ChatterTime(j), "/chatter", 5, j, 0});
  std::stable_sort(items.begin(), items.end(), [](const Item& x, const Item& y) {
    return x.t != y.t ? x.t < y.t : x.topic < y.topic;
  });
  BagWriter writer(dir, options);
  std::map<std::string, int> ids;
  const char* types[] = {kFloat32MultiArrayType, kOdometryType,  kOdometryType,
                         kLaserScanType,         kTfMessageType, "std_msgs/msg/String"};
  const auto header = [](TimestampNs t, const char* frame) {
    RosHeader h;
    h.stamp.sec = static_cast<std::int32_t>(t / 1000000000);
    h.stamp.nanosec = static_cast<std::uint32_t>(t % 1000000000);
    h.frame_id = frame;
    return h;
  };
  const auto odometry = [&](TimestampNs t, const Pose2& p, const std::array<double, 36>& cov,
                            double vx, double wz) {
    Odometry m;
    m.header = header(t, "odom");
    m.child_frame_id = "base_link";
    m.position = {p.x_m, p.y_m, 0.0};
    m.orientation = QuaternionFromYaw(p.yaw_rad);
    m.pose_covariance = cov;
    m.linear.x = vx;
    m.angular.z = wz;
    return m;
  };
  for (const Item& it : items) {
    if (!ids.count(it.topic)) {
      ids[it.topic] =
          writer.AddTopic(it.topic, types[it.kind], it.kind == 5 ? "string data\n" : "");
    }
    const int id = ids[it.topic];
    switch (it.kind) {
      case 0: {
        Float32MultiArray m;
        m.dim = {{"samples", kNumSamples, kNumSamples}};
        m.data = RadarSamples(it.a, it.b);
        writer.WriteMessage(id, it.t, m);
        break;
      }
      case 1:
        writer.WriteMessage(
            id, it.t, odometry(it.t, OdomPose(it.a), OdomCovariance(it.a), 0.25, 0.1 * (it.a % 3)));
        break;
      case 2:
        writer.WriteMessage(id, it.t, odometry(it.t, GroundTruthPose(it.a), {}, 0.0, 0.0));
        break;
      case 3: {
        LaserScan m;
        m.header = header(it.t, "laser");
        m.angle_min = -1.5f;
        m.angle_max = 1.5f;
        m.angle_increment = 0.1875f;
        m.scan_time = 0.1f;
        m.range_min = 0.25f;
        m.range_max = 8.0f;
        for (int r = 0; r < 16; ++r) {
          m.ranges.push_back(static_cast<float>(1.0 + 0.5 * r + it.a));
          if (it.a == 1) m.intensities.push_back(static_cast<float>(r * 2.0));
        }
        writer.WriteMessage(id, it.t, m);
        break;
      }
      case 4: {
        TfMessage m;
        const char* children[] = {"base_link", "radar_left"};
        for (int n = 0; n < 2; ++n) {
          TransformStamped tr;
          tr.header = header(it.t, n == 0 ? "odom" : "base_link");
          tr.child_frame_id = children[n];
          tr.translation = {1.0 * it.a, 0.18 * n, 0.0};
          tr.rotation = QuaternionFromYaw(0.5 * n + it.a);
          m.transforms.push_back(tr);
        }
        writer.WriteMessage(id, it.t, m);
        break;
      }
      default: {  // std_msgs/msg/String: u32 length, bytes, NUL
        const std::string text = "hello " + std::to_string(it.a);
        std::vector<std::uint8_t> cdr = {0, 1, 0, 0};
        const auto n = static_cast<std::uint32_t>(text.size() + 1);
        cdr.insert(cdr.end(), reinterpret_cast<const std::uint8_t*>(&n),
                   reinterpret_cast<const std::uint8_t*>(&n) + 4);
        cdr.insert(cdr.end(), text.begin(), text.end());
        cdr.push_back(0);
        writer.Write(id, it.t, cdr);
      }
    }
  }
  writer.Close();
}

std::string VenvPython() {
  const char* venv = std::getenv("UWBSAR_VENV");
  if (!venv || !*venv) return {};
  return std::string(venv) + "/bin/python";
}

int RunCommand(const std::string& command, std::string* output) {
  output->clear();
  FILE* p = ::popen((command + " 2>&1").c_str(), "r");
  if (!p) return -1;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof(buf), p)) > 0) output->append(buf, n);
  const int status = ::pclose(p);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace uwbsar::rosbag::testing
