// Blobs of the session file: images and descriptor matrices as [int32 rows, cols, type] +
// zstd of the pixel bytes, byte-shuffled by element (the exponent bytes of float tiles then
// compress well), lossless; keyframe tiles either so (CV_32FC1) or compact (EncodeTile:
// 10-bit linear levels of the tile's maximum, a fifth of the size); and keypoint lists as
// zstd of fixed 28-byte records. Decoding checks every size against the header: a damaged blob
// is an InputError naming `what`, never an out-of-bounds read; the sizes a header declares
// are checked against a budget (and the zstd frame's declared content size against the
// header) before anything is allocated.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace uwbsar::session {

/// What a decoded matrix may be, checked from its header before allocation.
struct MatBudget {
  std::vector<int> types;     ///< the OpenCV types allowed; empty: any
  double max_pixels = 3.2e7;  ///< rows x cols at most (LimitsConfig::max_tile_pixels)
  std::string limit = "limits.max_tile_pixels";  ///< the budget's name in errors
};

std::vector<unsigned char> EncodeMat(const cv::Mat& mat, int zstd_level);
/// Throws InputError "<what>: ..." for a damaged blob, a type not in `budget.types`, or
/// more pixels than `budget.max_pixels` (naming the declared size and the budget).
cv::Mat DecodeMat(const std::vector<unsigned char>& blob, const std::string& what,
                  const MatBudget& budget = MatBudget());

/// Levels of a compact tile: a tile pixel x > 0 is stored as max(1, round(x / step)) with
/// step = max / kTileLevels, 0 as 0. The error is at most half a step (max / 2046: 0.26 % of
/// the demo's reference level) above half a step, and below it at most one step: the pixels
/// a tile observed (x > 0) stay exactly those, which the mosaic's mean counts.
inline constexpr int kTileLevels = 1023;

/// A detected keyframe tile (CV_32FC1, >= 0): `lossless` as EncodeMat, else compact:
/// [int32 rows, cols, CV_16UC1][float32 step] + zstd of the byte-shuffled levels (lossless
/// too when the step would not be a normal float: a tile fainter than ~1e-35).
std::vector<unsigned char> EncodeTile(const cv::Mat& tile, bool lossless, int zstd_level);
/// Either form back as CV_32FC1; the same errors as DecodeMat (`budget.types` is ignored),
/// and a compact tile's step must be a normal positive float32 whose kTileLevels steps are
/// finite (a denormal step would read as a blank tile), its levels at most kTileLevels.
cv::Mat DecodeTile(const std::vector<unsigned char>& blob, const std::string& what,
                   const MatBudget& budget = MatBudget());

std::vector<unsigned char> EncodeKeypoints(const std::vector<cv::KeyPoint>& keypoints,
                                           int zstd_level);
/// At most `max_keypoints` (checked from the count before allocation).
std::vector<cv::KeyPoint> DecodeKeypoints(const std::vector<unsigned char>& blob,
                                          const std::string& what,
                                          std::uint32_t max_keypoints = 1u << 20);

}  // namespace uwbsar::session
