// BagWriter: our bags read back exactly by our reader and by the independent
// Python readers (rosbags, mcap with CRC checks); incremental writing with flushes,
// the temporary name and the rename on close.
#include "drivers/rosbag/bag_writer.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

#include "core/errors.h"
#include "drivers/rosbag/bag_reader.h"
#include "drivers/rosbag/ros_codecs.h"
#include "test/drivers/bag_test_util.h"

namespace uwbsar::rosbag::testing {
namespace {
namespace fs = std::filesystem;

struct WriterCase {
  const char* name;
  const char* storage;
  const char* compression;
};

class BagWriterRoundTripTest : public ::testing::TestWithParam<WriterCase> {
 protected:
  BagWriterOptions Options() const {
    BagWriterOptions o;
    o.storage = GetParam().storage;
    o.mcap.compression = GetParam().compression;
    o.mcap.chunk_size_bytes = 2048;  // several chunks
    return o;
  }
};

TEST_P(BagWriterRoundTripTest, OurReaderReadsBackExactly) {
  TempDir tmp;
  const std::string bag = tmp.path + "/run";
  WriteFixtureBag(bag, Options());
  EXPECT_FALSE(fs::exists(bag + ".partial"));
  const BagReader reader(bag);
  EXPECT_EQ(reader.Info().metadata_version, 5);
  EXPECT_EQ(reader.Info().storage_identifier, GetParam().storage);
  EXPECT_EQ(reader.Info().message_count, static_cast<std::uint64_t>(kNumMessages));
  ExpectFixtureContent(bag);
}

TEST_P(BagWriterRoundTripTest, RosbagsReadsBackExactly) {
  const std::string python = VenvPython();
  if (python.empty()) GTEST_SKIP() << "UWBSAR_VENV is unset: cannot run verify_bag.py";
  TempDir tmp;
  const std::string bag = tmp.path + "/run";
  WriteFixtureBag(bag, Options());
  std::string out;
  EXPECT_EQ(RunCommand(python + " " + FixtureDir() + "/verify_bag.py " + bag, &out), 0) << out;
  EXPECT_NE(out.find("OK 38 messages"), std::string::npos) << out;
}

INSTANTIATE_TEST_SUITE_P(Storages, BagWriterRoundTripTest,
                         ::testing::Values(WriterCase{"sqlite3", "sqlite3", ""},
                                           WriterCase{"mcap_none", "mcap", ""},
                                           WriterCase{"mcap_zstd", "mcap", "zstd"},
                                           WriterCase{"mcap_lz4", "mcap", "lz4"}),
                         [](const auto& p) { return std::string(p.param.name); });

TEST(BagWriterTest, SameInputGivesSameBytes) {
  for (const char* storage : {"sqlite3", "mcap"}) {
    TempDir a, b;
    BagWriterOptions o;
    o.storage = storage;
    WriteFixtureBag(a.path + "/bag", o);
    WriteFixtureBag(b.path + "/bag", o);
    const std::string file = std::string("/bag/bag_0.") + (o.storage == "mcap" ? "mcap" : "db3");
    std::string out;
    EXPECT_EQ(RunCommand("cmp " + a.path + file + " " + b.path + file, &out), 0) << out;
    EXPECT_EQ(
        RunCommand("cmp " + a.path + "/bag/metadata.yaml " + b.path + "/bag/metadata.yaml", &out),
        0)
        << out;
  }
}

TEST(BagWriterTest, FlushedMessagesAreReadableBeforeClose) {
  for (const char* storage : {"sqlite3", "mcap"}) {
    SCOPED_TRACE(storage);
    TempDir tmp;
    BagWriterOptions o;
    o.storage = storage;
    o.flush_period_s = 1.0;
    o.mcap.compression = "";
    BagWriter w(tmp.path + "/live", o);
    const int topic = w.AddTopic("/odom", kOdometryType);
    Odometry m;
    // 2.5 s of odometry at 10 Hz: flushes after 1 s and 2 s of message time.
    for (int i = 0; i < 25; ++i) w.WriteMessage(topic, kT0 + i * 100000000LL, m);
    const std::string partial =
        tmp.path + "/live.partial/live_0." + (std::string(storage) == "mcap" ? "mcap" : "db3");
    ASSERT_TRUE(fs::exists(partial));
    EXPECT_FALSE(fs::exists(tmp.path + "/live"));
    if (std::string(storage) == "sqlite3") {
      // The committed transaction is visible to another reader of the live file.
      BagReader reader(partial);
      EXPECT_EQ(reader.Info().message_count, 21u);
    } else {
      EXPECT_GT(fs::file_size(partial), 21u * 700u);  // 21 messages in flushed chunks
    }
    w.Close();
    EXPECT_TRUE(fs::exists(tmp.path + "/live/metadata.yaml"));
    EXPECT_EQ(BagReader(tmp.path + "/live").Info().message_count, 25u);
  }
}

// kill -9 of a live recording between two flushes, after the open transaction has spilled
// pages into the file, leaves a hot rollback journal; the bag must still read (sqlite
// refuses that read-only) and hold exactly what was flushed.
TEST(BagWriterTest, ARecordingKilledInsideATransactionReadsUpToItsLastFlush) {
  TempDir tmp;
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    BagWriterOptions o;
    o.flush_period_s = 1.0;
    BagWriter w(tmp.path + "/live", o);
    const int topic = w.AddTopic("/blob", "std_msgs/msg/UInt8MultiArray");
    const std::vector<std::uint8_t> blob(64 * 1024, 0x5a);
    for (int i = 0; i <= 10; ++i) w.Write(topic, kT0 + i * 100000000LL, blob);  // flushed
    // 16 MiB more within the flush period: far past sqlite's 2 MiB page cache, so the
    // transaction spills into the file and journals the pages it overwrites.
    for (int i = 1; i <= 256; ++i) w.Write(topic, kT0 + 1000000000LL + i * 1000000LL, blob);
    ::_exit(0);  // no destructor, no commit: what SIGKILL leaves
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  const std::string file = tmp.path + "/live.partial/live_0.db3";
  ASSERT_TRUE(fs::exists(file + "-journal"));  // else this test no longer tests a crash
  ASSERT_GT(fs::file_size(file + "-journal"), 0u);
  BagReader reader(file);
  EXPECT_EQ(reader.Info().message_count, 11u);
  BagMessage msg;
  int n = 0;
  while (reader.Next(&msg)) ++n;
  EXPECT_EQ(n, 11);
}

TEST(BagWriterTest, RefusesToOverwrite) {
  TempDir tmp;
  fs::create_directories(tmp.path + "/exists");
  EXPECT_THROW(BagWriter(tmp.path + "/exists"), InputError);
  fs::create_directories(tmp.path + "/crashed.partial");
  EXPECT_THROW(BagWriter(tmp.path + "/crashed"), InputError);
  BagWriterOptions o;
  o.storage = "rosbag_v2";
  EXPECT_THROW(BagWriter(tmp.path + "/new", o), InputError);
}

}  // namespace
}  // namespace uwbsar::rosbag::testing
