// Lossless blobs of the session file: images and descriptor matrices as
// [int32 rows, cols, type] + zstd of the pixel bytes, byte-shuffled by element (the
// exponent bytes of float tiles then compress well), and keypoint lists as zstd of
// fixed 28-byte records. Decoding checks every size against the header: a damaged blob
// is an InputError naming `what`, never an out-of-bounds read.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace uwbsar::session {

std::vector<unsigned char> EncodeMat(const cv::Mat& mat, int zstd_level);
cv::Mat DecodeMat(const std::vector<unsigned char>& blob, const std::string& what);

std::vector<unsigned char> EncodeKeypoints(const std::vector<cv::KeyPoint>& keypoints,
                                           int zstd_level);
std::vector<cv::KeyPoint> DecodeKeypoints(const std::vector<unsigned char>& blob,
                                          const std::string& what);

}  // namespace uwbsar::session
