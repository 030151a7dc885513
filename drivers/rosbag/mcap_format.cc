#include "drivers/rosbag/mcap_format.h"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/errors.h"

namespace uwbsar::rosbag::mcap {

std::string OpcodeName(std::uint8_t op) {
  static const char* const kNames[] = {
      nullptr,    "Header",        "Footer",        "Schema",     "Channel",         "Message",
      "Chunk",    "MessageIndex",  "ChunkIndex",    "Attachment", "AttachmentIndex", "Statistics",
      "Metadata", "MetadataIndex", "SummaryOffset", "DataEnd"};
  if (op >= 1 && op <= 0x0F) return kNames[op];
  char buf[16];
  std::snprintf(buf, sizeof(buf), "opcode 0x%02x", op);
  return buf;
}

void Cursor::Fail(const std::string& what) const {
  throw InputError(file_ + ": corrupt MCAP " + OpcodeName(opcode_) + " record at offset " +
                   std::to_string(offset_) + ": " + what);
}

const std::uint8_t* Cursor::Take(std::size_t n, const char* what) {
  if (n > Remaining()) {
    Fail(std::string(what) + " of " + std::to_string(n) + " bytes overruns the record (" +
         std::to_string(Remaining()) + " bytes left)");
  }
  const std::uint8_t* p = data_ + pos_;
  pos_ += n;
  return p;
}

std::uint8_t Cursor::U8() { return *Take(1, "u8"); }

std::uint16_t Cursor::U16() {
  std::uint16_t v;
  std::memcpy(&v, Take(2, "u16"), 2);
  return v;
}

std::uint32_t Cursor::U32() {
  std::uint32_t v;
  std::memcpy(&v, Take(4, "u32"), 4);
  return v;
}

std::uint64_t Cursor::U64() {
  std::uint64_t v;
  std::memcpy(&v, Take(8, "u64"), 8);
  return v;
}

std::string Cursor::String() {
  const std::uint32_t n = U32();
  const auto* p = Take(n, "string");
  return std::string(reinterpret_cast<const char*>(p), n);
}

std::pair<const std::uint8_t*, std::size_t> Cursor::Bytes32() {
  const std::uint32_t n = U32();
  return {Take(n, "byte array"), n};
}

std::pair<const std::uint8_t*, std::size_t> Cursor::Bytes64() {
  const std::uint64_t n = U64();
  if (n > Remaining()) Fail("byte array of " + std::to_string(n) + " bytes overruns the record");
  return {Take(static_cast<std::size_t>(n), "byte array"), static_cast<std::size_t>(n)};
}

std::vector<std::pair<std::string, std::string>> Cursor::StringMap() {
  const std::uint32_t n = U32();
  Cursor sub(Take(n, "map"), n, file_, offset_, opcode_);
  std::vector<std::pair<std::string, std::string>> out;
  while (sub.Remaining() > 0) {
    std::string key = sub.String();
    out.emplace_back(std::move(key), sub.String());
  }
  return out;
}

std::vector<std::pair<std::uint16_t, std::uint64_t>> Cursor::U16U64Map() {
  const std::uint32_t n = U32();
  Cursor sub(Take(n, "map"), n, file_, offset_, opcode_);
  std::vector<std::pair<std::uint16_t, std::uint64_t>> out;
  while (sub.Remaining() > 0) {
    const std::uint16_t key = sub.U16();
    out.emplace_back(key, sub.U64());
  }
  return out;
}

void Builder::String(const std::string& s) {
  U32(static_cast<std::uint32_t>(s.size()));
  Raw(s.data(), s.size());
}

void Builder::Raw(const void* p, std::size_t n) {
  const auto* b = static_cast<const std::uint8_t*>(p);
  out_->insert(out_->end(), b, b + n);
}

std::size_t Builder::BeginRecord(Opcode op) {
  U8(op);
  const std::size_t at = out_->size();
  U64(0);
  return at;
}

void Builder::EndRecord(std::size_t length_at) {
  const std::uint64_t length = out_->size() - length_at - 8;
  std::memcpy(out_->data() + length_at, &length, 8);
}

namespace {

constexpr std::size_t kGrowStep = std::size_t{1} << 20;

[[noreturn]] void Bad(const std::string& context, const std::string& what) {
  throw InputError(context + ": " + what);
}

// Grows `out` by up to kGrowStep, never beyond `limit` + 1 (one byte more than the
// claimed size is enough to detect a lie).
void Grow(std::vector<std::uint8_t>* out, std::size_t used, std::uint64_t limit) {
  const std::uint64_t target = std::min<std::uint64_t>(used + kGrowStep, limit + 1);
  out->resize(static_cast<std::size_t>(target));
}

void DecompressZstd(const std::uint8_t* data, std::size_t size, std::uint64_t expected,
                    const std::string& context, std::vector<std::uint8_t>* out) {
  // Fast path: a single frame that states the claimed size, and a size that real data
  // can have (zstd's best ratio on radar data is far below 64:1): decompress in one call.
  if (ZSTD_getFrameContentSize(data, size) == expected &&
      expected <= 64 * std::uint64_t{size} + kGrowStep) {
    out->resize(static_cast<std::size_t>(expected));
    const std::size_t n = ZSTD_decompress(out->data(), out->size(), data, size);
    if (ZSTD_isError(n)) Bad(context, std::string("zstd: ") + ZSTD_getErrorName(n));
    out->resize(n);
    return;
  }
  std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> ctx(ZSTD_createDCtx(), &ZSTD_freeDCtx);
  ZSTD_inBuffer in{data, size, 0};
  std::size_t used = 0;
  std::size_t last = 1;
  while (true) {
    if (used == out->size()) {
      if (used > expected) break;
      Grow(out, used, expected);
    }
    ZSTD_outBuffer o{out->data(), out->size(), used};
    const std::size_t in_before = in.pos;
    const std::size_t hint = ZSTD_decompressStream(ctx.get(), &o, &in);
    if (ZSTD_isError(hint)) Bad(context, std::string("zstd: ") + ZSTD_getErrorName(hint));
    const bool progressed = o.pos > used || in.pos > in_before;
    used = o.pos;
    // A call that moved nothing only asks for the next frame's header: keep the state
    // of the last frame (0 = complete).
    if (!progressed && used < out->size()) break;
    last = hint;
  }
  if (last != 0 && used <= expected) Bad(context, "zstd data is truncated");
  out->resize(used);
}

void DecompressLz4(const std::uint8_t* data, std::size_t size, std::uint64_t expected,
                   const std::string& context, std::vector<std::uint8_t>* out) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) {
    Bad(context, "lz4: cannot create a decompression context");
  }
  std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> ctx(
      raw, &LZ4F_freeDecompressionContext);
  std::size_t in_pos = 0, used = 0, hint = 1;
  while (hint != 0) {
    if (used == out->size()) {
      if (used > expected) break;
      Grow(out, used, expected);
    }
    std::size_t dst_size = out->size() - used;
    std::size_t src_size = size - in_pos;
    hint = LZ4F_decompress(ctx.get(), out->data() + used, &dst_size, data + in_pos, &src_size,
                           nullptr);
    if (LZ4F_isError(hint)) Bad(context, std::string("lz4: ") + LZ4F_getErrorName(hint));
    in_pos += src_size;
    used += dst_size;
    if (src_size == 0 && dst_size == 0 && used < out->size()) break;
  }
  if (hint != 0 && used <= expected) Bad(context, "lz4 frame is truncated");
  out->resize(used);
}

}  // namespace

void Decompress(const std::string& compression, const std::uint8_t* data, std::size_t size,
                std::uint64_t uncompressed_size, const std::string& context,
                std::vector<std::uint8_t>* out) {
  out->clear();
  if (compression.empty()) {
    if (size != uncompressed_size) {
      Bad(context, "uncompressed chunk holds " + std::to_string(size) + " bytes but claims " +
                       std::to_string(uncompressed_size));
    }
    out->assign(data, data + size);
    return;
  }
  if (compression == "zstd") {
    DecompressZstd(data, size, uncompressed_size, context, out);
  } else if (compression == "lz4") {
    DecompressLz4(data, size, uncompressed_size, context, out);
  } else {
    Bad(context, "unknown chunk compression '" + compression + "' (supported: none, zstd, lz4)");
  }
  if (out->size() != uncompressed_size) {
    Bad(context, "chunk decompresses to " +
                     std::string(out->size() > uncompressed_size ? "more than" : "only") + " " +
                     std::to_string(out->size()) + " bytes but claims " +
                     std::to_string(uncompressed_size));
  }
}

void Compress(const std::string& compression, const std::vector<std::uint8_t>& data,
              std::vector<std::uint8_t>* out) {
  if (compression.empty()) {
    *out = data;
  } else if (compression == "zstd") {
    out->resize(ZSTD_compressBound(data.size()));
    const std::size_t n = ZSTD_compress(out->data(), out->size(), data.data(), data.size(), 1);
    if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));
    out->resize(n);
  } else if (compression == "lz4") {
    LZ4F_preferences_t prefs{};
    prefs.frameInfo.contentSize = data.size();
    out->resize(LZ4F_compressFrameBound(data.size(), &prefs));
    const std::size_t n =
        LZ4F_compressFrame(out->data(), out->size(), data.data(), data.size(), &prefs);
    if (LZ4F_isError(n)) throw std::runtime_error(std::string("lz4: ") + LZ4F_getErrorName(n));
    out->resize(n);
  } else {
    throw std::invalid_argument("unknown MCAP chunk compression '" + compression + "'");
  }
}

}  // namespace uwbsar::rosbag::mcap
