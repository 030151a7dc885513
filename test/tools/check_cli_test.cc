// `uwbsar check BAG` as a user meets it before mapping: the demo's recording is all ok, a bag
// that map cannot use exits 3 naming the problem, warnings alone exit 0. The checks one by one
// are test/slam/check_job_test.cc.
#include <gtest/gtest.h>

#include <string>

#include "test/cli_runner.h"
#include "test/tools/map_test_bag.h"

namespace uwbsar {
namespace {

using map_test::BagEdits;
using map_test::TempDir;
using map_test::WriteRunBag;
using testing::CliRun;
using testing::Uwbsar;

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(CheckCliTest, DemoRecordingIsAllOk) {
  const std::string dir = TempDir("check_demo");
  // The demo's run (route depart-return in seed_hall, seed 1), as a bag.
  const CliRun sim = Uwbsar("simulate -q --map " + std::string(UWBSAR_SOURCE_DIR) +
                            "/config/maps/seed_hall/seed_hall.yaml --out " + dir + "/bag");
  ASSERT_EQ(sim.exit_code, 0) << sim.output;
  const CliRun r = Uwbsar("check " + dir + "/bag");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(Has(r.output, "\nall ok\n")) << r.output;
  EXPECT_FALSE(Has(r.output, "\nwarning ")) << r.output;
  EXPECT_FALSE(Has(r.output, "\nerror ")) << r.output;
  EXPECT_TRUE(Has(r.output, "ok      odometry: /odom, 4141 messages at 50.0 Hz\n")) << r.output;
  EXPECT_TRUE(Has(r.output, "info    ground truth: /ground_truth/odom, 16561 poses")) << r.output;
}

TEST(CheckCliTest, BagMapCannotUseExitsThreeNamingTheTopicAndKey) {
  const std::string dir = TempDir("check_topic");
  BagEdits edits;
  edits.odometry_topic = "/wheel_odom";
  const std::string bag = WriteRunBag(dir, edits);
  const CliRun r = Uwbsar("check " + bag);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_TRUE(Has(r.output,
                  "error   odometry: no topic /odom (slam.odometry_topic) in the bag; its "
                  "nav_msgs/msg/Odometry topics: /wheel_odom: map cannot place any scan\n"))
      << r.output;
  EXPECT_TRUE(Has(r.output, "uwbsar: error: " + bag +
                                ": 1 check failed (the error lines above): map would fail or "
                                "lose data\n"))
      << r.output;
  // The configuration names the topic: all ok.
  testing::WriteTextFile(dir + "/robot.yaml", "slam:\n  odometry_topic: /wheel_odom\n");
  const CliRun fixed = Uwbsar("check " + bag + " --config " + dir + "/robot.yaml");
  EXPECT_EQ(fixed.exit_code, 0) << fixed.output;
}

TEST(CheckCliTest, WarningsAloneExitZeroAndArePrinted) {
  const std::string dir = TempDir("check_jump");
  BagEdits edits;
  edits.odometry_reset_at_s = 3.0;  // the base's odometry restarts from zero: a 1.5 m jump
  const CliRun r = Uwbsar("check " + WriteRunBag(dir, edits));
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(Has(r.output, "warning odometry jumps once (largest 1.490 m, message 150, 3.00 s"))
      << r.output;
  EXPECT_TRUE(Has(r.output, "\n1 warning, no error\n")) << r.output;
}

}  // namespace
}  // namespace uwbsar
