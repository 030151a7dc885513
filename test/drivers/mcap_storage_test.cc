// MCAP storage: our writer read back by our reader (none/zstd/lz4, chunk merge,
// summary optional), every kind of damage to a finished file giving one clear
// InputError, and files cut short (a crashed recording) recovered up to the cut.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "drivers/rosbag/bag_storage.h"
#include "drivers/rosbag/crc32.h"
#include "drivers/rosbag/mcap_format.h"
#include "drivers/rosbag/mcap_storage_reader.h"
#include "slam/errors.h"
#include "slam/log.h"
#include "test/drivers/bag_test_util.h"

namespace uwbsar::rosbag::testing {
namespace {

using Bytes = std::vector<std::uint8_t>;
using mcap::Builder;

Bytes Payload(int i) {
  Bytes b(4 + static_cast<std::size_t>(i % 50));
  for (std::size_t k = 0; k < b.size(); ++k) b[k] = static_cast<std::uint8_t>(i * 7 + k);
  return b;
}

// Writes `times.size()` messages alternating over two topics.
Bytes WriteMcap(const std::string& dir, const McapWriteOptions& options,
                const std::vector<TimestampNs>& times) {
  const std::string path = dir + "/test.mcap";
  auto w = CreateMcapStorage(path, options);
  TopicInfo a, b;
  a.name = "/a";
  a.type = "std_msgs/msg/Float32MultiArray";
  b.name = "/b";
  b.type = "nav_msgs/msg/Odometry";
  w->AddTopic(a);
  w->AddTopic(b);
  for (std::size_t i = 0; i < times.size(); ++i) {
    const Bytes p = Payload(static_cast<int>(i));
    w->Write(static_cast<int>(i % 2), times[i], p.data(), p.size());
  }
  w->Close("rosbag2_bagfile_information: {}");
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), {});
}

std::vector<TimestampNs> Ramp(int n) {
  std::vector<TimestampNs> t;
  for (int i = 0; i < n; ++i) t.push_back(kT0 + i * 1000);
  return t;
}

struct Read {
  std::vector<TimestampNs> times;
  std::vector<int> topics;
  std::vector<Bytes> payloads;
};

Read ReadAll(const Bytes& file, McapOpenReport* report = nullptr) {
  auto r = OpenMcapStorage(MakeMemorySource("mem.mcap", file), report);
  Read out;
  StorageMessage m;
  while (r->Next(&m)) {
    out.times.push_back(m.log_time_ns);
    out.topics.push_back(m.topic);
    out.payloads.emplace_back(m.data, m.data + m.size);
  }
  return out;
}

// Offset of the first record with `opcode` in the data section.
std::size_t FindRecord(const Bytes& f, std::uint8_t opcode) {
  for (std::size_t off = 8; off + 9 <= f.size();) {
    std::uint64_t len;
    std::memcpy(&len, f.data() + off + 1, 8);
    if (f[off] == opcode) return off;
    off += 9 + len;
  }
  return 0;
}

std::string ErrorOf(const Bytes& file) {
  try {
    ReadAll(file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// Silences the recovery warnings of tests that open thousands of damaged files.
struct QuietLog {
  QuietLog() : saved(GetLogLevel()) { SetLogLevel(LogLevel::kSilent); }
  ~QuietLog() { SetLogLevel(saved); }
  LogLevel saved;
};

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

TEST(McapStorageTest, FileCutInTheSummaryIsRecoveredWhole) {
  TempDir tmp;
  const Bytes f = WriteMcap(tmp.path, {}, Ramp(10));
  McapOpenReport report;
  const Read r = ReadAll(Bytes(f.begin(), f.end() - 30), &report);
  EXPECT_TRUE(report.recovered);
  EXPECT_EQ(report.recovered_messages, 10u);
  EXPECT_EQ(r.times, Ramp(10));
}

TEST(McapStorageTest, FileCutInTheHeaderIsNamed) {
  TempDir tmp;
  const Bytes f = WriteMcap(tmp.path, {}, Ramp(10));
  const std::string e = ErrorOf(Bytes(f.begin(), f.begin() + 20));
  EXPECT_NE(e.find("mem.mcap: truncated"), std::string::npos) << e;
  EXPECT_NE(e.find("Header record at offset 8"), std::string::npos) << e;
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

// A recording as a crash sees it: after each Flush(), the bytes on disk and the number
// of messages written so far (the writer is never closed until the end).
struct Recording {
  Bytes file;
  std::vector<std::pair<std::size_t, std::size_t>> flushes;  // (file size, messages)
};

Recording RecordWithFlushes(const std::string& dir, const McapWriteOptions& options, int n,
                            int flush_every) {
  const std::string path = dir + "/rec.mcap";
  auto w = CreateMcapStorage(path, options);
  TopicInfo a, b;
  a.name = "/a";
  a.type = "std_msgs/msg/Float32MultiArray";
  b.name = "/b";
  w->AddTopic(a);
  w->AddTopic(b);
  Recording rec;
  for (int i = 0; i < n; ++i) {
    const Bytes p = Payload(i);
    w->Write(i % 2, kT0 + i * 1000, p.data(), p.size());
    if ((i + 1) % flush_every == 0) {
      w->Flush();
      rec.flushes.emplace_back(std::filesystem::file_size(path), i + 1);
    }
  }
  w->Close("rosbag2_bagfile_information: {}");
  std::ifstream in(path, std::ios::binary);
  rec.file.assign(std::istreambuf_iterator<char>(in), {});
  return rec;
}

// The data section of `f` followed by a Footer without summary, as a writer that
// writes no summary leaves it.
Bytes WithoutSummary(const Bytes& f) {
  std::uint64_t summary_start = 0;
  std::memcpy(&summary_start, f.data() + f.size() - 8 - 20, 8);
  Bytes g(f.begin(), f.begin() + static_cast<long>(summary_start));
  Builder b(&g);
  b.U8(mcap::kFooter);
  b.U64(20);
  b.U64(0);
  b.U64(0);
  b.U32(0);
  b.Raw(mcap::kMagic, 8);
  return g;
}

struct CutCase {
  std::string compression;
  bool summary;
  friend std::ostream& operator<<(std::ostream& os, const CutCase& c) {
    return os << "'" << c.compression << "'" << (c.summary ? " with summary" : " without summary");
  }
};

class McapCutTest : public ::testing::TestWithParam<CutCase> {};

// Every byte offset of a multi-chunk file: a clear error before the Header is complete,
// else exactly a prefix of the written messages that includes every message written
// before the last Flush() that reached the disk before the cut.
TEST_P(McapCutTest, FileCutAtAnyOffsetYieldsTheFlushedPrefix) {
  TempDir tmp;
  McapWriteOptions o;
  o.compression = GetParam().compression;
  o.chunk_size_bytes = 250;  // chunks closed by size between the flushes too
  const int n = 40;
  const Recording rec = RecordWithFlushes(tmp.path, o, n, 7);
  const Bytes f = GetParam().summary ? rec.file : WithoutSummary(rec.file);
  ASSERT_GE(rec.flushes.size(), 5u);
  std::uint64_t header_length = 0;
  std::memcpy(&header_length, f.data() + 9, 8);
  const std::size_t header_end = 8 + 9 + static_cast<std::size_t>(header_length);
  QuietLog quiet;
  std::size_t errors = 0, partial = 0;
  for (std::size_t cut = 0; cut <= f.size(); ++cut) {
    const Bytes g(f.begin(), f.begin() + static_cast<long>(cut));
    McapOpenReport report;
    Read r;
    try {
      r = ReadAll(g, &report);
    } catch (const InputError& e) {
      ++errors;
      EXPECT_LT(cut, header_end) << "cut at " << cut << ": " << e.what();
      continue;
    }
    EXPECT_EQ(report.recovered, cut < f.size()) << cut;
    std::size_t flushed = 0;
    for (const auto& [bytes, messages] : rec.flushes) {
      if (bytes <= cut) flushed = messages;
    }
    ASSERT_GE(r.times.size(), flushed) << "cut at " << cut;
    ASSERT_LE(r.times.size(), static_cast<std::size_t>(n));
    partial += r.times.size() < static_cast<std::size_t>(n);
    for (std::size_t i = 0; i < r.times.size(); ++i) {
      ASSERT_EQ(r.times[i], kT0 + static_cast<TimestampNs>(i) * 1000) << cut;
      ASSERT_EQ(r.topics[i], static_cast<int>(i % 2)) << cut;
      ASSERT_EQ(r.payloads[i], Payload(static_cast<int>(i))) << cut;
    }
    if (report.recovered) {
      EXPECT_EQ(report.recovered_messages, r.times.size());
    }
  }
  EXPECT_EQ(errors, header_end);  // cuts 0 .. header_end-1
  EXPECT_GT(partial, f.size() / 2);
}

INSTANTIATE_TEST_SUITE_P(Compression, McapCutTest,
                         ::testing::Values(CutCase{"", true}, CutCase{"", false},
                                           CutCase{"zstd", true}, CutCase{"zstd", false},
                                           CutCase{"lz4", true}, CutCase{"lz4", false}),
                         [](const auto& p) {
                           return (p.param.compression.empty() ? "none" : p.param.compression) +
                                  (p.param.summary ? "_summary" : "_no_summary");
                         });

// What kill -9 leaves: the file as the running writer left it, never closed.
TEST(McapRecoveryTest, FlushMakesEverythingWrittenSoFarRecoverable) {
  TempDir tmp;
  const std::string path = tmp.path + "/live.mcap";
  auto w = CreateMcapStorage(path, {});  // zstd, 1 MiB chunks: nothing closes by size
  TopicInfo a;
  a.name = "/a";
  w->AddTopic(a);
  for (int i = 0; i < 50; ++i) {
    const Bytes p = Payload(i);
    w->Write(0, kT0 + i * 1000, p.data(), p.size());
  }
  w->Flush();
  for (int i = 50; i < 60; ++i) {  // still in the open chunk
    const Bytes p = Payload(i);
    w->Write(0, kT0 + i * 1000, p.data(), p.size());
  }
  std::ifstream in(path, std::ios::binary);
  const Bytes on_disk(std::istreambuf_iterator<char>(in), {});
  McapOpenReport report;
  ::testing::internal::CaptureStderr();
  const Read r = ReadAll(on_disk, &report);
  const std::string log = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(r.times, Ramp(50));
  EXPECT_TRUE(report.recovered);
  EXPECT_EQ(report.readable_end, on_disk.size());
  EXPECT_NE(log.find("warning: mem.mcap: MCAP file has no footer"), std::string::npos) << log;
  EXPECT_NE(log.find("recovered 50 messages from the first " + std::to_string(on_disk.size())),
            std::string::npos)
      << log;
}

// A cut file whose last complete chunk fails its CRC: that chunk and what follows are
// lost, the chunks before it kept, and the warning says where the readable part ends.
TEST(McapRecoveryTest, ChunkFailingItsCrcEndsTheRecoveredPart) {
  TempDir tmp;
  McapWriteOptions o;
  o.compression = "";
  o.chunk_size_bytes = 1 << 20;
  const Recording rec = RecordWithFlushes(tmp.path, o, 30, 10);  // 3 chunks
  Bytes f(rec.file.begin(), rec.file.begin() + static_cast<long>(rec.flushes[2].first) - 5);
  // Cut in the third chunk's message indexes; damage the second chunk's first payload.
  std::size_t second = 8;
  for (int chunks = 0; chunks < 2;) {
    std::uint64_t len;
    std::memcpy(&len, f.data() + second + 1, 8);
    if (f[second] == mcap::kChunk && ++chunks == 2) break;
    second += 9 + len;
  }
  f[second + 9 + 40 + 9 + 22] ^= 0x10;
  McapOpenReport report;
  ::testing::internal::CaptureStderr();
  const Read r = ReadAll(f, &report);
  const std::string log = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(r.times, Ramp(10));
  EXPECT_EQ(report.readable_end, second);
  EXPECT_NE(log.find("recovered 10 messages from the first " + std::to_string(second) + " of " +
                     std::to_string(f.size()) + " bytes; unreadable from offset " +
                     std::to_string(second) + ": chunk CRC mismatch"),
            std::string::npos)
      << log;
}

// Damage in the middle of a finished file is not a crash: still an error, no guessing.
TEST(McapRecoveryTest, DamageBeforeAnIntactFooterIsStillAnError) {
  TempDir tmp;
  McapWriteOptions o;
  o.compression = "";
  o.chunk_size_bytes = 200;
  Bytes f = WriteMcap(tmp.path, o, Ramp(30));
  const std::size_t chunk = FindRecord(f, mcap::kChunk);
  f[chunk + 9 + 40 + 9 + 22] ^= 0x10;
  const std::string e = ErrorOf(f);
  EXPECT_NE(e.find("chunk CRC mismatch in the Chunk record at offset " + std::to_string(chunk)),
            std::string::npos)
      << e;
}

}  // namespace
}  // namespace uwbsar::rosbag::testing
