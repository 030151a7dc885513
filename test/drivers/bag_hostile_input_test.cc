// Bags made to break the reader: metadata of the wrong shape or with times that
// overflow, and file-compressed storage that decompresses to far more than it can hold or
// into a temporary folder that cannot take it. Each is one clear error naming the cause.
#include <gtest/gtest.h>
#include <zstd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/errors.h"
#include "drivers/rosbag/bag_info_text.h"
#include "drivers/rosbag/bag_metadata.h"
#include "drivers/rosbag/bag_reader.h"
#include "test/drivers/bag_test_util.h"

namespace uwbsar::rosbag::testing {
namespace {
namespace fs = std::filesystem;

const char* kGoodMetadata =
    "rosbag2_bagfile_information:\n"
    "  version: 5\n"
    "  storage_identifier: sqlite3\n"
    "  duration:\n"
    "    nanoseconds: 1000\n"
    "  starting_time:\n"
    "    nanoseconds_since_epoch: 1700000000000000000\n"
    "  message_count: 1\n"
    "  topics_with_message_count:\n"
    "    - topic_metadata:\n"
    "        name: /odom\n"
    "        type: nav_msgs/msg/Odometry\n"
    "      message_count: 1\n"
    "  relative_file_paths:\n"
    "    - bag_0.db3\n";

std::string ParseError(const std::string& text) {
  try {
    ParseBagMetadata(text, "meta.yaml");
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("not an InputError: ") + e.what();
  }
  return "no error";
}

std::string Replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(BagMetadataTest, WrongShapeIsBadInputNamingFileLineAndKey) {
  ASSERT_EQ(ParseError(kGoodMetadata), "no error");
  struct Case {
    std::string from, to, expect;
  } cases[] = {
      // A scalar where a mapping belongs.
      {"  duration:\n    nanoseconds: 1000\n", "  duration: 1000\n",
       "meta.yaml:4: field 'duration'"},
      {"    - topic_metadata:\n        name: /odom\n        type: nav_msgs/msg/Odometry\n"
       "      message_count: 1\n",
       "    - 5\n", "meta.yaml:10: field 'topics_with_message_count'"},
      {"    - topic_metadata:\n        name: /odom\n        type: nav_msgs/msg/Odometry\n",
       "    - topic_metadata: x\n", "field 'topics_with_message_count.topic_metadata'"},
      // A complex key (a mapping as a key) beside the fields.
      {"  version: 5\n", "  version: 5\n  ? {a: 1}\n  : 2\n", "no error"},
      // The whole document a scalar.
      {kGoodMetadata, "just text\n", "meta.yaml:1: field 'rosbag2_bagfile_information'"},
  };
  for (const Case& c : cases) {
    const std::string error = ParseError(Replaced(kGoodMetadata, c.from, c.to));
    if (c.expect == "no error") {
      EXPECT_EQ(error.find("not an InputError"), std::string::npos) << error;
    } else {
      EXPECT_NE(error.find(c.expect), std::string::npos) << c.to << " -> " << error;
      EXPECT_EQ(error.find('\n'), std::string::npos) << error;
    }
  }
}

TEST(BagMetadataTest, TimesThatWouldOverflowAreRefused) {
  const std::string max = std::to_string(std::numeric_limits<std::int64_t>::max());
  const std::string at_max = Replaced(Replaced(kGoodMetadata, "1700000000000000000", max),
                                      "nanoseconds: 1000", "nanoseconds: 0");
  EXPECT_EQ(ParseError(at_max), "no error");  // the last representable instant is a time
  const std::string past = Replaced(kGoodMetadata, "1700000000000000000", max);
  EXPECT_NE(ParseError(past).find("field 'duration': starting_time + duration is past"),
            std::string::npos)
      << ParseError(past);
  EXPECT_NE(ParseError(Replaced(kGoodMetadata, "nanoseconds: 1000", "nanoseconds: -5"))
                .find("field 'duration': is negative"),
            std::string::npos);
}

TEST(BagInfoTextTest, LatestRepresentableTimePrintsItsRealDate) {
  BagInfo info;
  info.start_ns = std::numeric_limits<std::int64_t>::max();
  info.end_ns = info.start_ns;
  const std::string text = FormatBagInfo(info);
  EXPECT_NE(text.find("2262"), std::string::npos) << text;  // not 1677 (signed overflow)
  EXPECT_NE(text.find("Duration:          0.000000000s"), std::string::npos) << text;
  info.start_ns = std::numeric_limits<std::int64_t>::min();
  EXPECT_NE(FormatBagInfo(info).find("Duration:"), std::string::npos);  // saturates, no UB
}

/// The sqlite3_file_zstd fixture, its storage replaced by `zeros` bytes of zeros
/// compressed with zstd, its metadata claiming one message.
std::string ZeroBombBag(const TempDir& tmp, std::size_t zeros) {
  const fs::path dir = fs::path(tmp.path) / "bomb";
  fs::copy(FixtureDir() + "/sqlite3_file_zstd", dir, fs::copy_options::recursive);
  fs::path storage;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() == ".zstd") storage = e.path();
  }
  EXPECT_FALSE(storage.empty());
  const std::vector<char> raw(zeros, 0);
  std::vector<char> packed(ZSTD_compressBound(raw.size()));
  const std::size_t n = ZSTD_compress(packed.data(), packed.size(), raw.data(), raw.size(), 1);
  EXPECT_FALSE(ZSTD_isError(n));
  std::ofstream(storage, std::ios::binary | std::ios::trunc)
      .write(packed.data(), static_cast<long>(n));
  const fs::path meta = dir / "metadata.yaml";
  std::ifstream in(meta);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  for (std::size_t at = 0; (at = text.find("message_count: ", at)) != std::string::npos;) {
    at += 15;
    text.replace(at, text.find('\n', at) - at, "1");
  }
  std::ofstream(meta, std::ios::trunc) << text;
  return dir.string();
}

/// Points $TMPDIR at `dir` while it lives.
struct ScopedTmpDir {
  explicit ScopedTmpDir(const std::string& dir) {
    const char* old = std::getenv("TMPDIR");
    had_ = old != nullptr;
    if (had_) old_ = old;
    ::setenv("TMPDIR", dir.c_str(), 1);
  }
  ~ScopedTmpDir() { had_ ? (void)::setenv("TMPDIR", old_.c_str(), 1) : (void)::unsetenv("TMPDIR"); }
  bool had_ = false;
  std::string old_;
};

TEST(BagReaderTest, FileCompressedStorageDecompressesWithinTheMetadataCap) {
  TempDir tmp;
  const std::string bag = ZeroBombBag(tmp, (DecompressedSizeCap(1) + (1u << 20)));
  const std::string tmpdir = tmp.path + "/tmpdir";
  fs::create_directories(tmpdir);
  std::string error = "no error";
  {
    const ScopedTmpDir scoped(tmpdir);
    try {
      BagReader reader(bag);
    } catch (const InputError& e) {
      error = e.what();
    }
  }
  EXPECT_NE(
      error.find("decompresses to more than " + std::to_string(DecompressedSizeCap(1)) + " bytes"),
      std::string::npos)
      << error;
  EXPECT_TRUE(fs::is_empty(tmpdir)) << "the partial copy is left in $TMPDIR";
}

TEST(BagReaderTest, FileCompressedStorageNamesTheTemporaryFolderWhenItCannotWrite) {
  TempDir tmp;
  const std::string bag = FixtureDir() + "/sqlite3_file_zstd";
  const std::string missing = tmp.path + "/no_such_tmpdir";
  std::string error = "no error";
  {
    const ScopedTmpDir scoped(missing);
    try {
      BagReader reader(bag);
    } catch (const InputError& e) {
      error = std::string("InputError: ") + e.what();  // would blame the bag
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  EXPECT_EQ(error.rfind(missing, 0), 0u) << error;
  EXPECT_NE(error.find("No such file or directory"), std::string::npos) << error;
  EXPECT_EQ(error.find("truncated"), std::string::npos) << error;
}

TEST(BagReaderTest, FileCompressedStorageLeavesNoTemporaryFile) {
  TempDir tmp;
  const std::string tmpdir = tmp.path + "/tmpdir";
  fs::create_directories(tmpdir);
  const ScopedTmpDir scoped(tmpdir);
  {
    BagReader reader(FixtureDir() + "/sqlite3_file_zstd");
    BagMessage m;
    int n = 0;
    while (reader.Next(&m)) ++n;
    EXPECT_GT(n, 0);
    EXPECT_FALSE(fs::is_empty(tmpdir));  // the decompressed copy, while the reader is open
  }
  EXPECT_TRUE(fs::is_empty(tmpdir));
}

}  // namespace
}  // namespace uwbsar::rosbag::testing
