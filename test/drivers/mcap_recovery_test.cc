// MCAP files cut short (a crashed recording, kill -9, power loss): read like
// `mcap recover`, up to the last complete chunk, with a warning; a cut before the
// Header is complete is a clear error.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>

#include "test/drivers/mcap_test_util.h"

namespace uwbsar::rosbag::testing {
namespace {

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
  const std::size_t second = FindRecord(f, mcap::kChunk, 2);
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

// --skip-damaged: one flipped bit in one chunk of a finished file costs that chunk only,
// and the warning names its offset and how many messages it held.
TEST(McapRecoveryTest, SkipDamagedChunkLosesOnlyThatChunkAndNamesIt) {
  TempDir tmp;
  McapWriteOptions o;
  o.compression = "";
  o.chunk_size_bytes = 200;
  Bytes f = WriteMcap(tmp.path, o, Ramp(30));
  const Read whole = ReadAll(f);
  const std::size_t second = FindRecord(f, mcap::kChunk, 2);
  f[second + 9 + 40 + 9 + 22] ^= 0x10;  // a payload byte of the second chunk's first message
  EXPECT_NE(ErrorOf(f).find("chunk CRC mismatch"), std::string::npos);  // default: an error

  BagReadOptions skip;
  skip.skip_damaged_chunks = true;
  ::testing::internal::CaptureStderr();
  auto reader = OpenMcapStorage(MakeMemorySource("mem.mcap", f), nullptr, skip);
  Read r;
  StorageMessage m;
  while (reader->Next(&m)) r.times.push_back(m.log_time_ns);
  const std::string log = ::testing::internal::GetCapturedStderr();
  ASSERT_LT(r.times.size(), whole.times.size());
  const std::size_t lost = whole.times.size() - r.times.size();
  EXPECT_NE(log.find("skipping the damaged chunk at offset " + std::to_string(second) + " (" +
                     std::to_string(lost) + " messages"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("chunk CRC mismatch"), std::string::npos) << log;
  // Every message outside the damaged chunk is there, in order.
  std::size_t k = 0;
  for (const TimestampNs t : r.times) {
    while (k < whole.times.size() && whole.times[k] != t) ++k;
    ASSERT_LT(k, whole.times.size()) << "message at " << t << " is not one of the file's";
  }
  std::printf("skip-damaged: %zu of %zu messages kept, 1 chunk of %zu messages skipped\n",
              r.times.size(), whole.times.size(), lost);
}

}  // namespace
}  // namespace uwbsar::rosbag::testing
