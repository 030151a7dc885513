// BagReader: bag directories and bare files, split bags, and every kind of bad
// input (missing metadata, unknown storage id, corrupt or truncated .db3, wrong
// topic types) giving one clear InputError that names the file.
#include "drivers/rosbag/bag_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "core/errors.h"
#include "drivers/rosbag/bag_info_text.h"
#include "drivers/rosbag/robot_bag.h"
#include "drivers/rosbag/sqlite_util.h"
#include "test/drivers/bag_test_util.h"

namespace uwbsar::rosbag::testing {
namespace {
namespace fs = std::filesystem;

std::string ErrorOpening(const std::string& path) {
  try {
    BagReader reader(path);
    BagMessage m;
    while (reader.Next(&m)) {
    }
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// A copy of a committed fixture that a test may damage.
std::string CopyFixture(const TempDir& tmp, const std::string& name) {
  const fs::path dst = fs::path(tmp.path) / name;
  fs::copy(FixtureDir() + "/" + name, dst, fs::copy_options::recursive);
  return dst.string();
}

void Replace(const std::string& path, const std::string& from, const std::string& to) {
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  std::ofstream(path, std::ios::trunc) << text;
}

void ExpectError(const std::string& error, const std::string& file, const std::string& what) {
  EXPECT_EQ(error.rfind(file, 0), 0u) << error;
  EXPECT_NE(error.find(what), std::string::npos) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
}

TEST(BagReaderTest, SplitBagIsMergedInTimeOrder) {
  BagReader reader(FixtureDir() + "/split_sqlite3");
  BagMessage m;
  std::vector<TimestampNs> times;
  std::set<int> files;
  while (reader.Next(&m)) {
    times.push_back(m.log_time_ns);
    files.insert(m.file);
  }
  EXPECT_EQ(times.size(), static_cast<std::size_t>(kNumMessages));
  EXPECT_TRUE(std::is_sorted(times.begin(), times.end()));
  EXPECT_EQ(files.size(), 2u);
}

TEST(BagReaderTest, MissingMetadataIsNamed) {
  TempDir tmp;
  const std::string bag = CopyFixture(tmp, "humble_sqlite3");
  fs::remove(bag + "/metadata.yaml");
  ExpectError(ErrorOpening(bag), bag + "/metadata.yaml", "missing");
}

TEST(BagReaderTest, UnknownStorageIdIsNamed) {
  TempDir tmp;
  const std::string bag = CopyFixture(tmp, "humble_sqlite3");
  Replace(bag + "/metadata.yaml", "storage_identifier: sqlite3", "storage_identifier: rosbag_v2");
  ExpectError(ErrorOpening(bag), bag + "/metadata.yaml", "unknown storage id 'rosbag_v2'");
}

TEST(BagReaderTest, MalformedMetadataNamesLineAndField) {
  TempDir tmp;
  const std::string bag = CopyFixture(tmp, "humble_sqlite3");
  Replace(bag + "/metadata.yaml", "message_count: 38", "message_count: lots");
  ExpectError(ErrorOpening(bag), bag + "/metadata.yaml:", "message_count': has the wrong type");
}

TEST(BagReaderTest, MissingStorageFileIsNamed) {
  TempDir tmp;
  const std::string bag = CopyFixture(tmp, "humble_sqlite3");
  fs::remove(bag + "/humble_sqlite3_0.db3");
  ExpectError(ErrorOpening(bag), bag + "/metadata.yaml",
              "'humble_sqlite3_0.db3' which does not exist");
}

TEST(BagReaderTest, CorruptDb3IsNamed) {
  TempDir tmp;
  const std::string bag = CopyFixture(tmp, "humble_sqlite3");
  const std::string db = bag + "/humble_sqlite3_0.db3";
  {
    std::fstream f(db, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(0);
    f.write("garbage garbage garbage", 23);
  }
  ExpectError(ErrorOpening(bag), db, "sqlite3");
  ExpectError(ErrorOpening(db), db, "unknown storage");
}

TEST(BagReaderTest, TruncatedDb3IsNamed) {
  TempDir tmp;
  const std::string bag = CopyFixture(tmp, "humble_sqlite3");
  const std::string db = bag + "/humble_sqlite3_0.db3";
  fs::resize_file(db, fs::file_size(db) / 2);
  ExpectError(ErrorOpening(bag), db, "malformed");
}

TEST(BagReaderTest, SqliteFileThatIsNotABagIsNamed) {
  TempDir tmp;
  const std::string db = tmp.path + "/other.db3";
  {
    SqliteDb d(db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
    d.Exec(
        "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT, type TEXT, "
        "serialization_format TEXT)");
  }
  ExpectError(ErrorOpening(db), db, "not a rosbag2 sqlite3 file: no 'messages' table");
}

TEST(BagReaderTest, NonexistentPathIsNamed) {
  ExpectError(ErrorOpening("/nonexistent/bag"), "/nonexistent/bag", "no such bag");
}

TEST(BagReaderTest, TopicOfTheWrongTypeIsNamed) {
  RobotBagOptions options;
  options.radar_topics = {"/UWBradar0/readings", "/odom"};  // /odom is not a radar
  options.odometry_topic = "/ground_truth/odom";
  options.ground_truth_topic.clear();
  RobotBagVisitor ignore;
  const std::string bag = FixtureDir() + "/mcap_zstd";
  try {
    ReadRobotBag(bag, options, ignore);
    FAIL() << "no error";
  } catch (const InputError& e) {
    ExpectError(e.what(), bag,
                "topic /odom has type nav_msgs/msg/Odometry, but radars[right].topic expects "
                "std_msgs/msg/Float32MultiArray");
  }
}

TEST(BagReaderTest, BadCdrInABagNamesFileTopicAndTime) {
  TempDir tmp;
  BagWriterOptions o;
  o.storage = "mcap";
  {
    BagWriter w(tmp.path + "/bag", o);
    const int odom = w.AddTopic("/odom", kOdometryType);
    w.Write(odom, kT0, std::vector<std::uint8_t>{0, 1, 0, 0, 1, 2});
    w.Close();
  }
  RobotBagVisitor ignore;
  try {
    ReadRobotBag(tmp.path + "/bag", RobotBagOptions{}, ignore);
    FAIL() << "no error";
  } catch (const InputError& e) {
    ExpectError(e.what(), tmp.path + "/bag/bag_0.mcap",
                "message at 1700000000000000000 ns on /odom (nav_msgs/msg/Odometry): CDR");
  }
}

/// The InputError ReadRobotBag gives `path` ("no error" if none).
std::string RobotBagError(const std::string& path) {
  RobotBagVisitor ignore;
  try {
    ReadRobotBag(path, RobotBagOptions{}, ignore);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// Issue 45 item 8: a bag in 2150 was mapped with exit 0, its results.mcap header stamps
// wrapped to 2014; stamps crossing 0 made /tf log times run backwards. uwbsar's outputs hold
// ROS 2 times (int32 seconds) and MCAP log times (from 1970): 1970 .. 2038-01-19 03:14:07 UTC.
TEST(BagReaderTest, StampsTheOutputsCannotHoldAreRefusedNamingMessageTopicAndStamp) {
  TempDir tmp;
  const auto write = [&tmp](const std::string& name, const std::string& storage,
                            std::vector<TimestampNs> odometry_stamps) {
    BagWriterOptions o;
    o.storage = storage;
    BagWriter w(tmp.path + "/" + name, o);
    const int chatter = w.AddTopic("/chatter", "std_msgs/msg/String");
    const int odom = w.AddTopic("/odom", kOdometryType);
    w.Write(chatter, odometry_stamps.front(), std::vector<std::uint8_t>{0, 1, 0, 0, 0, 0, 0, 0});
    Odometry msg;
    msg.orientation.w = 1.0;
    for (const TimestampNs t : odometry_stamps) w.WriteMessage(odom, t, msg);
    w.Close();
  };
  const TimestampNs k2150 = 5680281600LL * 1000000000LL;  // 2150-01-01
  write("future", "mcap", {k2150, k2150 + 10000000});
  ExpectError(RobotBagError(tmp.path + "/future"), tmp.path + "/future/future_0.mcap",
              ": message 1 on /odom (nav_msgs/msg/Odometry): log time stamp 5680281600.000000000 s "
              "(2150-01-01 00:00:00 UTC) is outside 1970-01-01 00:00:00 .. 2038-01-19 03:14:07 "
              "UTC, the times ROS 2 messages (int32 seconds) can hold");
  // Crossing 0 (a bare .db3: a bag folder's metadata refuses a negative start itself).
  write("zero", "sqlite3", {-500000000, 500000000});
  ExpectError(RobotBagError(tmp.path + "/zero/zero_0.db3"), tmp.path + "/zero/zero_0.db3",
              ": message 1 on /odom (nav_msgs/msg/Odometry): log time stamp -0.500000000 s "
              "(1969-12-31 23:59:59 UTC) is outside");
  // The last second a ROS 2 time holds is a time.
  write("last", "mcap", {2147483647LL * 1000000000LL});
  EXPECT_EQ(RobotBagError(tmp.path + "/last"), "no error");
}

TEST(BagInfoTextTest, LooksLikeRos2BagInfo) {
  const BagReader reader(FixtureDir() + "/humble_sqlite3");
  const std::string text = FormatBagInfo(reader.Info());
  EXPECT_NE(text.find("Files:             humble_sqlite3_0.db3\n"), std::string::npos) << text;
  EXPECT_NE(text.find("Storage id:        sqlite3\n"), std::string::npos) << text;
  EXPECT_NE(text.find("Duration:          0.181000000s\n"), std::string::npos) << text;
  EXPECT_NE(text.find("(1700000000.000000000)"), std::string::npos) << text;
  EXPECT_NE(text.find("Messages:          38\n"), std::string::npos) << text;
  EXPECT_NE(text.find("Topic: /odom | Type: nav_msgs/msg/Odometry | Count: 10 | "
                      "Serialization Format: cdr"),
            std::string::npos)
      << text;
  EXPECT_EQ(HumanBytes(1536), "1.5 KiB");
}

}  // namespace
}  // namespace uwbsar::rosbag::testing
