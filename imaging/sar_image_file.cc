#include "imaging/sar_image_file.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <vector>

#include "core/bounded_file.h"
#include "core/errors.h"
#include "core/log.h"
#include "imaging/image_header.h"
#include "imaging/sar_grid_metadata.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// All pages of the file, decoded as stored.
std::vector<cv::Mat> DecodePages(const std::string& path, double max_pixels) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec && ec != std::errc::no_such_file_or_directory) {
    throw InputError(path + ": cannot read SAR image: " + ec.message());  // e.g. a symlink loop
  }
  if (!fs::exists(status)) throw InputError(path + ": SAR image does not exist");
  CheckInputFile(path, "SAR image");  // a folder, FIFO or device, named
  CheckImageSize(path, max_pixels, "SAR image");
  std::vector<cv::Mat> pages;
  try {
    const std::string ext = Lower(fs::path(path).extension().string());
    if (ext == ".tif" || ext == ".tiff") {
      cv::imreadmulti(path, pages, cv::IMREAD_UNCHANGED);
    } else {
      cv::Mat one = cv::imread(path, cv::IMREAD_UNCHANGED);
      if (!one.empty()) pages.push_back(one);
    }
  } catch (const cv::Exception& e) {
    throw InputError(path + ": cannot decode SAR image: " + e.err);
  }
  if (pages.empty()) throw InputError(path + ": cannot decode SAR image (not an image file)");
  return pages;
}

/// The largest value a 16-bit image's pixels may take: a PGM's declared maxval (a 10-bit
/// sensor writes 1023), else the image's own maximum (at least 1). Its range becomes 0..255.
double SixteenBitFullScale(const std::string& path, const cv::Mat& image) {
  const ImageHeader header = ReadImageHeader(path);
  if (header.format == "PNM" && header.maxval > 0) return static_cast<double>(header.maxval);
  double lo = 0.0, hi = 0.0;
  cv::minMaxLoc(image, &lo, &hi);
  return std::max(1.0, hi);
}

/// One CV_8UC1 (enhanced) or CV_32FC1/2 (as imaged) image from the decoded pages.
cv::Mat ToSarImage(const std::string& path, std::vector<cv::Mat> pages, bool* enhanced) {
  const cv::Mat& first = pages.front();
  if (pages.size() == 1 && first.channels() == 1 &&
      (first.depth() == CV_8U || first.depth() == CV_16U)) {
    *enhanced = true;
    if (first.depth() == CV_8U) return first;
    cv::Mat out;
    first.convertTo(out, CV_8U, 255.0 / SixteenBitFullScale(path, first));
    return out;
  }
  if (pages.size() <= 2) {
    bool all_float = true;
    for (const cv::Mat& p : pages) {
      all_float = all_float && p.type() == CV_32FC1 && p.size() == first.size();
    }
    if (all_float) {
      *enhanced = false;
      if (pages.size() == 1) return first;
      cv::Mat merged;
      cv::merge(pages, merged);
      return merged;
    }
  }
  throw InputError(path + ": unsupported SAR image: expected 8- or 16-bit gray (PNG/PGM) or a " +
                   "32-bit float TIFF with 1 (real) or 2 (re, im) pages");
}

/// NaN or infinite pixels of a float image are "not measured": set to 0 (what every imager
/// leaves unobserved), with one warning giving the count, which is returned. An image with no
/// finite pixel is refused.
long long ZeroNonFinite(const std::string& path, cv::Mat* image) {
  cv::Mat flat = image->reshape(1);
  cv::Mat finite = (flat == flat) & (flat < std::numeric_limits<float>::infinity()) &
                   (flat > -std::numeric_limits<float>::infinity());
  const double total = static_cast<double>(flat.total());
  const double bad = total - cv::countNonZero(finite);
  if (bad == 0) return 0;
  if (bad == total) {
    throw InputError(path + ": SAR image holds no finite pixel (every value is NaN or infinite)");
  }
  flat.setTo(0.0f, ~finite);
  std::ostringstream msg;
  msg << path << ": " << static_cast<long long>(bad) << " of " << static_cast<long long>(total)
      << " values are NaN or infinite; read as not measured (0)";
  Log(LogLevel::kWarning, msg.str());
  return static_cast<long long>(bad);
}

}  // namespace

std::string FindGridYaml(const std::string& image_path) {
  const fs::path p(image_path);
  std::string stem = p.stem().string();
  std::vector<std::string> names = {stem + "_grid.yaml"};
  if (EndsWith(stem, "_float")) names.push_back(stem.substr(0, stem.size() - 6) + "_grid.yaml");
  for (const std::string& name : names) {
    const fs::path candidate = p.parent_path() / name;
    std::error_code ec;  // an unreadable candidate (a symlink loop) is no grid YAML
    if (fs::is_regular_file(candidate, ec)) return candidate.string();
  }
  return {};
}

SarImageFile ReadSarImageFile(const std::string& path, double default_resolution_m,
                              double max_pixels) {
  SarImageFile out;
  SarGridMetadata meta;
  const std::string ext = Lower(fs::path(path).extension().string());
  if (ext == ".yaml" || ext == ".yml") {
    meta = LoadSarGridMetadata(path);
    if (meta.image.empty()) throw InputError(path + ": grid YAML has no 'image' key");
    out.grid_yaml = path;
    out.path = meta.image;
  } else {
    out.path = path;
    out.grid_yaml = FindGridYaml(path);
    if (!out.grid_yaml.empty()) meta = LoadSarGridMetadata(out.grid_yaml);
  }
  out.image = ToSarImage(out.path, DecodePages(out.path, max_pixels), &out.enhanced);
  if (out.grid_yaml.empty()) {
    if (!(default_resolution_m > 0.0) || !std::isfinite(default_resolution_m)) {
      throw InputError(path + ": resolution must be > 0 metres per pixel");
    }
    out.grid.resolution_m = default_resolution_m;
  } else {
    if (meta.rows > 0 && (meta.rows != out.image.rows || meta.cols != out.image.cols)) {
      throw InputError(out.path + ": image is " + std::to_string(out.image.cols) + " x " +
                       std::to_string(out.image.rows) + " pixels but " + out.grid_yaml + " says " +
                       std::to_string(meta.cols) + " x " + std::to_string(meta.rows));
    }
    out.grid.x0_m = meta.x0_m;
    out.grid.y0_m = meta.y0_m;
    out.grid.resolution_m = meta.resolution_m;
  }
  out.grid.rows = out.image.rows;
  out.grid.cols = out.image.cols;
  if (!out.enhanced) out.nonfinite_values = ZeroNonFinite(out.path, &out.image);
  // A measurement is a non-zero, finite pixel (0 is what every imager leaves unobserved).
  cv::Mat magnitude;
  if (out.image.channels() == 2) {
    std::vector<cv::Mat> parts;
    cv::split(out.image, parts);
    cv::magnitude(parts[0], parts[1], magnitude);
  } else {
    out.image.convertTo(magnitude, CV_32F);
  }
  cv::patchNaNs(magnitude, 0.0);
  out.observed = (magnitude != 0.0) & (magnitude < 1e30f) & (magnitude > -1e30f);
  if (cv::countNonZero(out.observed) == 0) {
    throw InputError(out.path + ": SAR image holds no measurement (every pixel is 0)");
  }
  double lo = 0.0, hi = 0.0;
  cv::minMaxLoc(magnitude, &lo, &hi, nullptr, nullptr, out.observed);
  if (lo == hi) {
    throw InputError(out.path + ": SAR image is uniform (every measured pixel is " +
                     std::to_string(hi) + "): nothing to match or map");
  }
  return out;
}

}  // namespace uwbsar
