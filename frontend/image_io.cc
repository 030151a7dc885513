#include "frontend/image_io.h"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

namespace uwbsar {
namespace {

std::string TempNameFor(const std::string& path) {
  // Keep the extension last: OpenCV picks the encoder from it.
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  const std::string tag = ".tmp" + std::to_string(::getpid());
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return path + tag;
  return path.substr(0, dot) + tag + path.substr(dot);
}

void Commit(const std::string& tmp, const std::string& path) {
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw ImageIoError(path + ": cannot rename temporary file into place");
  }
}

}  // namespace

void WriteImageAtomic(const std::string& path, const cv::Mat& image) {
  const std::string tmp = TempNameFor(path);
  bool ok = false;
  try {
    ok = cv::imwrite(tmp, image);
  } catch (const cv::Exception& e) {
    std::remove(tmp.c_str());
    throw ImageIoError(path + ": cannot encode image: " + e.what());
  }
  if (!ok) {
    std::remove(tmp.c_str());
    throw ImageIoError(path + ": cannot write image (folder missing or unknown extension?)");
  }
  Commit(tmp, path);
}

void WriteFloatTiff(const std::string& path, const cv::Mat& sar) {
  CV_Assert(sar.depth() == CV_32F);
  if (sar.channels() == 1) return WriteImageAtomic(path, sar);
  // TIFF pages are 1, 3 or 4 channels: a complex image becomes two pages, re and im.
  std::vector<cv::Mat> pages;
  cv::split(sar, pages);
  const std::string tmp = TempNameFor(path);
  bool ok = false;
  try {
    ok = cv::imwritemulti(tmp, pages);
  } catch (const cv::Exception& e) {
    std::remove(tmp.c_str());
    throw ImageIoError(path + ": cannot encode image: " + e.what());
  }
  if (!ok) {
    std::remove(tmp.c_str());
    throw ImageIoError(path + ": cannot write image");
  }
  Commit(tmp, path);
}

void WriteTextAtomic(const std::string& path, const std::string& text) {
  const std::string tmp = TempNameFor(path);
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out.flush()) {
      std::remove(tmp.c_str());
      throw ImageIoError(path + ": cannot write file");
    }
  }
  Commit(tmp, path);
}

}  // namespace uwbsar
