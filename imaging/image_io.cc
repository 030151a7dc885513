#include "imaging/image_io.h"

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.h"

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

/// " (no space left on device)" when the file system of `path` is full, else "".
std::string SpaceHint(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash + 1);
  struct statvfs fs {};
  if (::statvfs(dir.c_str(), &fs) == 0 && fs.f_bavail == 0) return " (no space left on device)";
  return {};
}

}  // namespace

void WriteImageAtomic(const std::string& path, const cv::Mat& image) {
  // Encoded in memory and written here, so a failed write names its cause (disk full).
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  const std::string ext = dot == std::string::npos || (slash != std::string::npos && dot < slash)
                              ? std::string()
                              : path.substr(dot);
  std::vector<unsigned char> bytes;
  bool ok = false;
  try {
    ok = !ext.empty() && cv::imencode(ext, image, bytes);
  } catch (const cv::Exception& e) {
    throw ImageIoError(path + ": cannot encode image: " + e.what());
  }
  if (!ok) throw ImageIoError(path + ": cannot encode image (unknown extension?)");
  WriteTextAtomic(path, std::string(bytes.begin(), bytes.end()));
}

void WriteFloatTiff(const std::string& path, const cv::Mat& sar) {
  if (sar.empty()) throw InputError(path + ": nothing imaged: the image to write is empty");
  if (sar.depth() != CV_32F) {
    throw std::logic_error(path + ": WriteFloatTiff needs a 32-bit float image, got depth " +
                           std::to_string(sar.depth()));
  }
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
    throw ImageIoError(path + ": cannot write image" + SpaceHint(path));
  }
  Commit(tmp, path);
}

void WriteTextAtomic(const std::string& path, const std::string& text) {
  const std::string tmp = TempNameFor(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw ImageIoError(path + ": cannot write file: " + std::strerror(errno));
  int error = 0;
  for (std::size_t done = 0; done < text.size() && error == 0;) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) error = n < 0 ? errno : ENOSPC;
    if (n > 0) done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) {
    std::remove(tmp.c_str());
    throw ImageIoError(path + ": cannot write file: " + std::strerror(error));
  }
  Commit(tmp, path);
}

}  // namespace uwbsar
