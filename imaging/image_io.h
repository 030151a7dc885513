// Writing images atomically: every file is written under a temporary name in the
// same folder and renamed, so a crash never leaves a half-written output.
#pragma once

#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

namespace uwbsar {

class ImageIoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Writes any image OpenCV can encode for the extension (.png, .tif, .pgm, ...).
void WriteImageAtomic(const std::string& path, const cv::Mat& image);
/// Raw float values: 32-bit float TIFF (1 page, or 2 pages re and im for coherent images).
/// An empty image (nothing was imaged) throws InputError naming the path; an image that is
/// not float is a programmer error (std::logic_error), never an OpenCV assertion.
void WriteFloatTiff(const std::string& path, const cv::Mat& sar);
/// Writes `text` to `path` atomically.
void WriteTextAtomic(const std::string& path, const std::string& text);

}  // namespace uwbsar
