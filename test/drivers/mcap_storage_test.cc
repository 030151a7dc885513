// MCAP storage: our writer read back by our reader (none/zstd/lz4, chunk merge,
// summary optional), and every kind of damage to a finished file giving one clear
// InputError. Files cut short are mcap_recovery_test.cc.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <random>

#include "drivers/rosbag/crc32.h"
#include "test/drivers/mcap_test_util.h"

namespace uwbsar::rosbag::testing {
namespace {

TEST(Crc32Test, MatchesTheStandardCheckValue) {
  EXPECT_EQ(Crc32(0, "123456789", 9), 0xCBF43926u);
  EXPECT_EQ(Crc32(Crc32(0, "1234", 4), "56789", 5), 0xCBF43926u);
}

class McapRoundTripTest : public ::testing::TestWithParam<std::string> {};

TEST_P(McapRoundTripTest, ReadsBackEveryMessageInOrder) {
  TempDir tmp;
  McapWriteOptions o;
  o.compression = GetParam();
  o.chunk_size_bytes = 700;  // many chunks
  const Bytes file = WriteMcap(tmp.path, o, Ramp(300));
  const Read r = ReadAll(file);
  ASSERT_EQ(r.times.size(), 300u);
  for (int i = 0; i < 300; ++i) {
    EXPECT_EQ(r.times[static_cast<std::size_t>(i)], kT0 + i * 1000);
    EXPECT_EQ(r.topics[static_cast<std::size_t>(i)], i % 2);
    EXPECT_EQ(r.payloads[static_cast<std::size_t>(i)], Payload(i));
  }
  auto storage = OpenMcapStorage(MakeMemorySource("mem.mcap", file));
  EXPECT_EQ(storage->Stats().message_count, 300u);
  EXPECT_EQ(storage->Stats().end_ns, kT0 + 299 * 1000);
  EXPECT_EQ(storage->Topics()[1].message_count, 150u);
  EXPECT_EQ(storage->Topics()[0].type, "std_msgs/msg/Float32MultiArray");
}

INSTANTIATE_TEST_SUITE_P(Compression, McapRoundTripTest, ::testing::Values("", "zstd", "lz4"),
                         [](const auto& p) { return p.param.empty() ? "none" : p.param; });

TEST(McapStorageTest, MergesOverlappingChunksIntoTimeOrder) {
  TempDir tmp;
  McapWriteOptions o;
  o.chunk_size_bytes = 300;
  std::vector<TimestampNs> t;
  std::mt19937 rng(3);
  for (int i = 0; i < 200; ++i) t.push_back(kT0 + static_cast<TimestampNs>(rng() % 5000));
  const Read r = ReadAll(WriteMcap(tmp.path, o, t));
  ASSERT_EQ(r.times.size(), 200u);
  EXPECT_TRUE(std::is_sorted(r.times.begin(), r.times.end()));
  std::sort(t.begin(), t.end());
  EXPECT_EQ(r.times, t);
}

TEST(McapStorageTest, WorksWithoutSummaryByScanningRecords) {
  TempDir tmp;
  McapWriteOptions o;
  o.chunk_size_bytes = 500;
  Bytes f = WriteMcap(tmp.path, o, Ramp(120));
  // Footer: summary_start = 0, summary_offset_start = 0, summary_crc = 0.
  std::memset(f.data() + f.size() - 8 - 20, 0, 20);
  const Read r = ReadAll(f);
  EXPECT_EQ(r.times.size(), 120u);
  auto storage = OpenMcapStorage(MakeMemorySource("mem.mcap", f));
  EXPECT_EQ(storage->Stats().message_count, 120u);
  EXPECT_EQ(storage->Topics()[0].message_count, 60u);
}

TEST(McapStorageTest, BadMagicIsNamed) {
  TempDir tmp;
  Bytes f = WriteMcap(tmp.path, {}, Ramp(10));
  f[1] = 'X';
  EXPECT_NE(ErrorOf(f).find("mem.mcap: bad magic"), std::string::npos) << ErrorOf(f);
  EXPECT_NE(ErrorOf(Bytes{1, 2, 3}).find("bad magic"), std::string::npos);
}

TEST(McapStorageTest, WrongChunkCrcIsNamed) {
  TempDir tmp;
  McapWriteOptions o;
  o.compression = "";
  Bytes f = WriteMcap(tmp.path, o, Ramp(10));
  const std::size_t chunk = FindRecord(f, mcap::kChunk);
  ASSERT_GT(chunk, 0u);
  f[chunk + 9 + 24] ^= 0xFF;  // uncompressed_crc field
  const std::string e = ErrorOf(f);
  EXPECT_NE(e.find("chunk CRC mismatch in the Chunk record at offset " + std::to_string(chunk)),
            std::string::npos)
      << e;
}

TEST(McapStorageTest, CorruptCompressedDataIsNamed) {
  TempDir tmp;
  for (const char* compression : {"zstd", "lz4"}) {
    McapWriteOptions o;
    o.compression = compression;
    const std::string dir = tmp.path + "/" + compression;
    std::filesystem::create_directories(dir);
    Bytes f = WriteMcap(dir, o, Ramp(40));
    const std::size_t chunk = FindRecord(f, mcap::kChunk);
    std::uint64_t len;
    std::memcpy(&len, f.data() + chunk + 1, 8);
    f[chunk + 9 + len - 8] ^= 0x5A;  // inside the compressed bytes
    const std::string e = ErrorOf(f);
    EXPECT_NE(e.find("Chunk record at offset " + std::to_string(chunk)), std::string::npos) << e;
  }
}

TEST(McapStorageTest, WrongSummaryCrcIgnoresTheSummaryWithAWarning) {
  TempDir tmp;
  McapWriteOptions o;
  o.chunk_size_bytes = 200;
  Bytes f = WriteMcap(tmp.path, o, Ramp(30));
  f[f.size() - 8 - 4] ^= 0x01;  // footer summary_crc
  McapOpenReport report;
  ::testing::internal::CaptureStderr();
  const Read r = ReadAll(f, &report);
  const std::string log = ::testing::internal::GetCapturedStderr();
  EXPECT_TRUE(report.summary_ignored);
  EXPECT_FALSE(report.recovered);
  EXPECT_NE(log.find("mem.mcap: summary CRC mismatch"), std::string::npos) << log;
  EXPECT_EQ(r.times, Ramp(30));
}

TEST(McapStorageTest, MessageOutsideItsChunkRangeIsNamed) {
  TempDir tmp;
  McapWriteOptions o;
  o.compression = "";
  Bytes f = WriteMcap(tmp.path, o, Ramp(10));
  const std::size_t chunk = FindRecord(f, mcap::kChunk);
  const std::uint64_t later = kT0 + 5000;  // message_start_time after the first messages
  std::memcpy(f.data() + chunk + 9, &later, 8);
  EXPECT_NE(ErrorOf(f).find("outside the chunk's declared range"), std::string::npos) << ErrorOf(f);
}

TEST(McapStorageTest, RecordLengthOverrunIsNamed) {
  TempDir tmp;
  McapWriteOptions o;
  o.compression = "";
  Bytes f = WriteMcap(tmp.path, o, Ramp(10));
  const std::size_t chunk = FindRecord(f, mcap::kChunk);
  const std::uint64_t huge = 1ull << 40;
  std::memcpy(f.data() + chunk + 1, &huge, 8);
  const std::string e = ErrorOf(f);
  EXPECT_NE(e.find("Chunk record at offset " + std::to_string(chunk) + " claims 1099511627776"),
            std::string::npos)
      << e;
}

// Every prefix and many single-byte corruptions: an error or a result, never a crash
// (the libFuzzer target fuzz/mcap_fuzz.cc goes further).
TEST(McapStorageTest, DamagedFilesNeverCrash) {
  TempDir tmp;
  McapWriteOptions o;
  o.chunk_size_bytes = 200;
  o.compression = "lz4";
  const Bytes f = WriteMcap(tmp.path, o, Ramp(12));
  QuietLog quiet;
  int errors = 0;
  for (std::size_t n = 0; n < f.size(); n += 3) {
    errors += ErrorOf(Bytes(f.begin(), f.begin() + static_cast<long>(n))) != "no error";
  }
  EXPECT_GT(errors, 0);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 400; ++trial) {
    Bytes g = f;
    g[rng() % g.size()] ^= static_cast<std::uint8_t>(1 + rng() % 255);
    ErrorOf(g);
  }
}

}  // namespace
}  // namespace uwbsar::rosbag::testing
