// MCAP record layout shared by the reader and the writer (https://mcap.dev/spec):
// magic `89 4D 43 41 50 30 0D 0A`, then records of u8 opcode, u64 content length,
// content. Integers are little-endian; strings and byte arrays carry a u32 (u64 for
// chunk records) length prefix; maps a u32 byte length.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace uwbsar::rosbag::mcap {

inline constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
inline constexpr std::size_t kRecordHeaderBytes = 9;  // opcode + length
inline constexpr std::size_t kFooterContentBytes = 20;

enum Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

/// Human name of an opcode for error messages ("Chunk", "opcode 0x42").
std::string OpcodeName(std::uint8_t op);

/// Bounds-checked little-endian reading of one record's content. Errors throw
/// InputError("<file>: corrupt MCAP <Record> record at offset N: <what>").
class Cursor {
 public:
  Cursor(const std::uint8_t* data, std::size_t size, const std::string& file,
         std::uint64_t record_offset, std::uint8_t opcode)
      : data_(data), size_(size), file_(file), offset_(record_offset), opcode_(opcode) {}

  std::uint8_t U8();
  std::uint16_t U16();
  std::uint32_t U32();
  std::uint64_t U64();
  std::string String();
  /// A byte array with a u32 (or u64) length prefix; returns a view into the record.
  std::pair<const std::uint8_t*, std::size_t> Bytes32();
  std::pair<const std::uint8_t*, std::size_t> Bytes64();
  /// map<string, string> with a u32 byte-length prefix.
  std::vector<std::pair<std::string, std::string>> StringMap();
  /// map<u16, u64> with a u32 byte-length prefix.
  std::vector<std::pair<std::uint16_t, std::uint64_t>> U16U64Map();

  const std::uint8_t* Here() const { return data_ + pos_; }
  std::size_t Remaining() const { return size_ - pos_; }
  [[noreturn]] void Fail(const std::string& what) const;

 private:
  const std::uint8_t* Take(std::size_t n, const char* what);

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  const std::string& file_;
  std::uint64_t offset_;
  std::uint8_t opcode_;
};

/// Appends little-endian values to a byte buffer (the writer's records).
class Builder {
 public:
  explicit Builder(std::vector<std::uint8_t>* out) : out_(out) {}
  void U8(std::uint8_t v) { out_->push_back(v); }
  void U16(std::uint16_t v) { Raw(&v, 2); }
  void U32(std::uint32_t v) { Raw(&v, 4); }
  void U64(std::uint64_t v) { Raw(&v, 8); }
  void String(const std::string& s);
  void Raw(const void* p, std::size_t n);
  /// Starts a record; returns the position of its length field for EndRecord().
  std::size_t BeginRecord(Opcode op);
  void EndRecord(std::size_t length_at);
  std::size_t Size() const { return out_->size(); }

 private:
  std::vector<std::uint8_t>* out_;
};

/// Decompresses a chunk ("", "zstd" or "lz4" frame) into `out`, which ends up exactly
/// `uncompressed_size` bytes; output grows as data is produced, so a lying size
/// cannot make us allocate more than the data yields. Throws InputError(`context`: ...).
void Decompress(const std::string& compression, const std::uint8_t* data, std::size_t size,
                std::uint64_t uncompressed_size, const std::string& context,
                std::vector<std::uint8_t>* out);
/// Compresses `data` for a chunk with "", "zstd" or "lz4" into `out`.
void Compress(const std::string& compression, const std::vector<std::uint8_t>& data,
              std::vector<std::uint8_t>* out);

}  // namespace uwbsar::rosbag::mcap
