#include "slam/session/blob_codec.h"

#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>

#include "core/errors.h"

namespace uwbsar::session {
namespace {

constexpr std::size_t kKeypointBytes = 28;  // x, y, size, angle, response, octave, class_id
constexpr std::size_t kMaxBlobBytes = std::size_t{1} << 31;

/// Whether `step` makes every level 1..kTileLevels a positive, normal, finite float: a
/// denormal or zero step would read the levels as 0 (a blank tile), a huge one as infinity.
bool UsableStep(float step) {
  return std::isnormal(step) && step > 0.0f &&
         static_cast<double>(step) * kTileLevels <= std::numeric_limits<float>::max();
}

std::vector<unsigned char> Compress(const unsigned char* data, std::size_t n, int level) {
  std::vector<unsigned char> out(ZSTD_compressBound(n));
  const std::size_t size = ZSTD_compress(out.data(), out.size(), data, n, level);
  if (ZSTD_isError(size)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(size));
  out.resize(size);
  return out;
}

std::vector<unsigned char> Decompress(const unsigned char* data, std::size_t n,
                                      std::size_t expected, const std::string& what) {
  const unsigned long long declared = ZSTD_getFrameContentSize(data, n);
  if (declared == ZSTD_CONTENTSIZE_ERROR || declared == ZSTD_CONTENTSIZE_UNKNOWN ||
      declared != expected || expected > kMaxBlobBytes) {
    throw InputError(what + ": damaged blob (size " + std::to_string(declared) + ", expected " +
                     std::to_string(expected) + ")");
  }
  std::vector<unsigned char> out(expected);
  const std::size_t size = ZSTD_decompress(out.data(), out.size(), data, n);
  if (ZSTD_isError(size) || size != expected) {
    throw InputError(what + ": damaged blob (zstd: " +
                     (ZSTD_isError(size) ? ZSTD_getErrorName(size) : "short") + ")");
  }
  return out;
}

}  // namespace

std::vector<unsigned char> EncodeMat(const cv::Mat& mat, int zstd_level) {
  const cv::Mat m = mat.isContinuous() ? mat : mat.clone();
  const std::int32_t header[3] = {m.rows, m.cols, m.type()};
  const std::size_t elem = m.empty() ? 1 : m.elemSize1();
  const std::size_t n = m.empty() ? 0 : m.total() * m.elemSize();
  std::vector<unsigned char> shuffled(n);
  const std::size_t count = n / elem;
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t b = 0; b < elem; ++b) shuffled[b * count + i] = m.data[i * elem + b];
  }
  std::vector<unsigned char> out(sizeof(header));
  std::memcpy(out.data(), header, sizeof(header));
  const std::vector<unsigned char> packed = Compress(shuffled.data(), n, zstd_level);
  out.insert(out.end(), packed.begin(), packed.end());
  return out;
}

cv::Mat DecodeMat(const std::vector<unsigned char>& blob, const std::string& what,
                  const MatBudget& budget) {
  std::int32_t header[3];
  if (blob.size() < sizeof(header)) throw InputError(what + ": damaged blob (no header)");
  std::memcpy(header, blob.data(), sizeof(header));
  const int rows = header[0], cols = header[1], type = header[2];
  if (rows < 0 || cols < 0 || rows > 1 << 20 || cols > 1 << 20 || CV_MAT_DEPTH(type) > CV_16F ||
      (type & ~CV_MAT_TYPE_MASK) != 0) {
    throw InputError(what + ": damaged blob (header " + std::to_string(rows) + " x " +
                     std::to_string(cols) + ", type " + std::to_string(type) + ")");
  }
  if (!budget.types.empty() &&
      std::find(budget.types.begin(), budget.types.end(), type) == budget.types.end()) {
    throw InputError(what + ": OpenCV type " + std::to_string(type) + " is not one of this blob's");
  }
  const double pixels = static_cast<double>(rows) * static_cast<double>(cols);
  if (pixels > budget.max_pixels) {
    char budget_text[32];
    std::snprintf(budget_text, sizeof(budget_text), "%.3g", budget.max_pixels);
    throw InputError(what + ": declares " + std::to_string(rows) + " x " + std::to_string(cols) +
                     " pixels, more than " + budget.limit + " (" + budget_text +
                     "); refused before decoding");
  }
  if (rows == 0 || cols == 0) return cv::Mat();
  const std::size_t elem = CV_ELEM_SIZE1(type);
  const std::size_t n = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols) *
                        static_cast<std::size_t>(CV_ELEM_SIZE(type));
  // The frame's declared content size is checked against n before anything is allocated.
  const std::vector<unsigned char> shuffled =
      Decompress(blob.data() + sizeof(header), blob.size() - sizeof(header), n, what);
  cv::Mat m(rows, cols, type);
  const std::size_t count = n / elem;
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t b = 0; b < elem; ++b) m.data[i * elem + b] = shuffled[b * count + i];
  }
  return m;
}

std::vector<unsigned char> EncodeTile(const cv::Mat& tile, bool lossless, int zstd_level) {
  if (lossless || tile.empty()) return EncodeMat(tile, zstd_level);
  if (tile.type() != CV_32FC1) throw std::logic_error("EncodeTile: a tile is CV_32FC1");
  double max_value = 0.0;
  cv::minMaxLoc(tile, nullptr, &max_value);
  const float step = max_value > 0.0 ? static_cast<float>(max_value / kTileLevels) : 1.0f;
  // A tile too faint (or too bright) for float levels of its maximum keeps its bytes.
  if (!UsableStep(step)) return EncodeMat(tile, zstd_level);
  cv::Mat levels(tile.rows, tile.cols, CV_16UC1);
  for (int r = 0; r < tile.rows; ++r) {
    const float* x = tile.ptr<float>(r);
    std::uint16_t* q = levels.ptr<std::uint16_t>(r);
    for (int c = 0; c < tile.cols; ++c) {
      const long level = x[c] > 0.0f ? std::lround(x[c] / step) : 0;
      q[c] = static_cast<std::uint16_t>(x[c] > 0.0f ? std::clamp(level, 1L, long{kTileLevels}) : 0);
    }
  }
  std::vector<unsigned char> inner = EncodeMat(levels, zstd_level);
  std::vector<unsigned char> out(inner.begin(), inner.begin() + 12);  // the header
  const unsigned char* step_bytes = reinterpret_cast<const unsigned char*>(&step);
  out.insert(out.end(), step_bytes, step_bytes + sizeof(step));
  out.insert(out.end(), inner.begin() + 12, inner.end());
  return out;
}

cv::Mat DecodeTile(const std::vector<unsigned char>& blob, const std::string& what,
                   const MatBudget& budget) {
  std::int32_t header[3] = {0, 0, 0};
  if (blob.size() >= sizeof(header)) std::memcpy(header, blob.data(), sizeof(header));
  MatBudget tile_budget = budget;
  if (header[2] != CV_16UC1) {
    tile_budget.types = {CV_32FC1};
    return DecodeMat(blob, what, tile_budget);
  }
  float step = 0.0f;
  if (blob.size() < sizeof(header) + sizeof(step)) {
    throw InputError(what + ": damaged blob (no step)");
  }
  std::memcpy(&step, blob.data() + sizeof(header), sizeof(step));
  if (!UsableStep(step)) {
    char text[96];
    std::snprintf(text, sizeof(text), "step %.6g is not a normal float in [%.6g, %.6g]",
                  static_cast<double>(step), static_cast<double>(std::numeric_limits<float>::min()),
                  static_cast<double>(std::numeric_limits<float>::max()) / kTileLevels);
    throw InputError(what + ": damaged blob (" + text + ")");
  }
  std::vector<unsigned char> inner(blob.begin(), blob.begin() + sizeof(header));
  inner.insert(inner.end(), blob.begin() + sizeof(header) + sizeof(step), blob.end());
  tile_budget.types = {CV_16UC1};
  const cv::Mat levels = DecodeMat(inner, what, tile_budget);
  double max_level = 0.0;
  if (!levels.empty()) cv::minMaxLoc(levels, nullptr, &max_level);
  if (max_level > kTileLevels) {
    throw InputError(what + ": damaged blob (level " + std::to_string(static_cast<int>(max_level)) +
                     ", more than " + std::to_string(kTileLevels) + ")");
  }
  cv::Mat tile;
  levels.convertTo(tile, CV_32F, step);
  return tile;
}

std::vector<unsigned char> EncodeKeypoints(const std::vector<cv::KeyPoint>& keypoints,
                                           int zstd_level) {
  std::vector<unsigned char> raw(keypoints.size() * kKeypointBytes);
  unsigned char* p = raw.data();
  for (const cv::KeyPoint& k : keypoints) {
    const float f[5] = {k.pt.x, k.pt.y, k.size, k.angle, k.response};
    const std::int32_t i[2] = {k.octave, k.class_id};
    std::memcpy(p, f, sizeof(f));
    std::memcpy(p + sizeof(f), i, sizeof(i));
    p += kKeypointBytes;
  }
  const std::uint32_t count = static_cast<std::uint32_t>(keypoints.size());
  std::vector<unsigned char> out(sizeof(count));
  std::memcpy(out.data(), &count, sizeof(count));
  const std::vector<unsigned char> packed = Compress(raw.data(), raw.size(), zstd_level);
  out.insert(out.end(), packed.begin(), packed.end());
  return out;
}

std::vector<cv::KeyPoint> DecodeKeypoints(const std::vector<unsigned char>& blob,
                                          const std::string& what, std::uint32_t max_keypoints) {
  std::uint32_t count = 0;
  if (blob.size() < sizeof(count)) throw InputError(what + ": damaged blob (no count)");
  std::memcpy(&count, blob.data(), sizeof(count));
  if (count > max_keypoints) {
    throw InputError(what + ": declares " + std::to_string(count) + " keypoints, more than " +
                     std::to_string(max_keypoints) + "; refused before decoding");
  }
  const std::vector<unsigned char> raw =
      Decompress(blob.data() + sizeof(count), blob.size() - sizeof(count),
                 static_cast<std::size_t>(count) * kKeypointBytes, what);
  std::vector<cv::KeyPoint> out(count);
  const unsigned char* p = raw.data();
  for (cv::KeyPoint& k : out) {
    float f[5];
    std::int32_t i[2];
    std::memcpy(f, p, sizeof(f));
    std::memcpy(i, p + sizeof(f), sizeof(i));
    k = cv::KeyPoint(cv::Point2f(f[0], f[1]), f[2], f[3], f[4], i[0], i[1]);
    p += kKeypointBytes;
  }
  return out;
}

}  // namespace uwbsar::session
