// Lossless blobs of the session file: images and descriptor matrices as
// [int32 rows, cols, type] + zstd of the pixel bytes, byte-shuffled by element (the
// exponent bytes of float tiles then compress well), and keypoint lists as zstd of
// fixed 28-byte records. Decoding checks every size against the header: a damaged blob
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

std::vector<unsigned char> EncodeKeypoints(const std::vector<cv::KeyPoint>& keypoints,
                                           int zstd_level);
/// At most `max_keypoints` (checked from the count before allocation).
std::vector<cv::KeyPoint> DecodeKeypoints(const std::vector<unsigned char>& blob,
                                          const std::string& what,
                                          std::uint32_t max_keypoints = 1u << 20);

}  // namespace uwbsar::session
