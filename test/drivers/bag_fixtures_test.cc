// Bags written by independent writers (Python rosbags, mcap +
// mcap-ros2-support; see test/data/bags/make_fixtures.py) decode to exactly the
// floats and poses that were written, in every storage layout and compression.
#include <gtest/gtest.h>

#include "drivers/rosbag/bag_reader.h"
#include "test/drivers/bag_test_util.h"

namespace uwbsar::rosbag::testing {
namespace {

struct Fixture {
  const char* name;
  const char* storage;
  int metadata_version;  // 0: bare file
};

class CommittedFixtureTest : public ::testing::TestWithParam<Fixture> {};

TEST_P(CommittedFixtureTest, DecodesExactlyWhatWasWritten) {
  const Fixture f = GetParam();
  const std::string path = FixtureDir() + "/" + f.name;
  const BagReader reader(path);
  const BagInfo& info = reader.Info();
  EXPECT_EQ(info.storage_identifier, f.storage);
  EXPECT_EQ(info.metadata_version, f.metadata_version);
  EXPECT_EQ(info.message_count, static_cast<std::uint64_t>(kNumMessages));
  EXPECT_EQ(info.start_ns, RadarTime(0, 0));
  ASSERT_EQ(info.topics.size(), 7u);
  const int odom = reader.FindTopic("/odom");
  ASSERT_GE(odom, 0);
  EXPECT_EQ(info.topics[static_cast<std::size_t>(odom)].type, "nav_msgs/msg/Odometry");
  EXPECT_EQ(info.topics[static_cast<std::size_t>(odom)].message_count,
            static_cast<std::uint64_t>(kNumOdom));
  ExpectFixtureContent(path);
}

INSTANTIATE_TEST_SUITE_P(
    Rosbags, CommittedFixtureTest,
    ::testing::Values(Fixture{"jazzy_sqlite3", "sqlite3", 9},   // schema 4
                      Fixture{"humble_sqlite3", "sqlite3", 5},  // schema 3
                      Fixture{"foxy_sqlite3", "sqlite3", 4},    // schema 1, parent-relative path
                      Fixture{"split_sqlite3", "sqlite3", 9},   // two interleaved files
                      Fixture{"sqlite3_file_zstd", "sqlite3", 9},
                      Fixture{"sqlite3_message_zstd", "sqlite3", 9},
                      Fixture{"mcap_none", "mcap", 8},           // chunks without compression
                      Fixture{"mcap_zstd", "mcap", 9},           // zstd chunks
                      Fixture{"mcap_lz4.mcap", "mcap", 0},       // lz4 chunks, bare file
                      Fixture{"mcap_unchunked.mcap", "mcap", 0}  // no chunks, no summary
                      ),
    [](const ::testing::TestParamInfo<Fixture>& p) {
      std::string n = p.param.name;
      for (char& c : n) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return n;
    });

TEST(CommittedFixtureTest, BareDb3FileReadsWithCountsFromTheFile) {
  const std::string path = FixtureDir() + "/humble_sqlite3/humble_sqlite3_0.db3";
  const BagReader reader(path);
  EXPECT_EQ(reader.Info().metadata_version, 0);
  EXPECT_EQ(reader.Info().message_count, static_cast<std::uint64_t>(kNumMessages));
  EXPECT_EQ(reader.Info().end_ns, OdomTime(kNumOdom - 1));
  ExpectFixtureContent(path);
}

TEST(CommittedFixtureTest, SplitBagListsBothFiles) {
  const BagReader reader(FixtureDir() + "/split_sqlite3");
  EXPECT_EQ(reader.Info().files.size(), 2u);
}

TEST(CommittedFixtureTest, McapSchemasCarryMessageDefinitions) {
  const BagReader reader(FixtureDir() + "/mcap_lz4.mcap");
  const auto& t = reader.Info().topics[static_cast<std::size_t>(reader.FindTopic("/odom"))];
  EXPECT_EQ(t.definition_encoding, "ros2msg");
  EXPECT_NE(t.message_definition.find("geometry_msgs/PoseWithCovariance pose"), std::string::npos);
}

// The same writers run now, from the venv, so a newer rosbags release is covered too.
TEST(FreshFixtureTest, FixturesGeneratedNowDecodeExactly) {
  const std::string python = VenvPython();
  if (python.empty()) GTEST_SKIP() << "UWBSAR_VENV is unset: cannot run make_fixtures.py";
  TempDir tmp;
  std::string out;
  ASSERT_EQ(RunCommand(python + " " + FixtureDir() + "/make_fixtures.py --out " + tmp.path, &out),
            0)
      << out;
  for (const char* name :
       {"jazzy_sqlite3", "humble_sqlite3", "foxy_sqlite3", "split_sqlite3", "sqlite3_file_zstd",
        "sqlite3_message_zstd", "mcap_none", "mcap_zstd", "mcap_lz4.mcap", "mcap_unchunked.mcap"}) {
    SCOPED_TRACE(name);
    ExpectFixtureContent(tmp.path + "/" + name);
  }
}

}  // namespace
}  // namespace uwbsar::rosbag::testing
