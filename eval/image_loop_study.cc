#include "eval/image_loop_study.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <regex>
#include <sstream>

#include "core/errors.h"
#include "eval/image_match_report.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;

void FindRegionImages(const std::string& dir, ImageLoopStudy* study) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw InputError(dir + ": not a folder of D*/R* images" +
                     (ec ? " (" + ec.message() + ")" : ""));
  }
  const std::regex name(R"(([DR])(\d+)\.(png|pgm|tif|tiff))", std::regex::icase);
  fs::directory_iterator it(dir, ec);
  if (ec) throw InputError(dir + ": cannot list the folder: " + ec.message());
  for (const fs::directory_entry& e : it) {
    std::smatch m;
    const std::string file = e.path().filename().string();
    if (!std::regex_match(file, m, name)) continue;
    // A symlink loop or a dangling link is bad input naming the file, not an exception.
    const bool regular = e.is_regular_file(ec);
    if (ec) throw InputError(e.path().string() + ": cannot read the image: " + ec.message());
    if (!regular) continue;
    const bool d = std::toupper(static_cast<unsigned char>(m[1].str()[0])) == 'D';
    const std::string digits = m[2].str();
    const std::size_t first = std::min(digits.find_first_not_of('0'), digits.size() - 1);
    if (digits.size() - first > 9) {
      throw InputError(e.path().string() + ": region index '" + digits +
                       "' is too large (at most 999999999)");
    }
    const int index = std::stoi(digits);
    auto& files = d ? study->d_files : study->r_files;
    if (files.count(index)) {
      throw InputError(dir + ": two images for region " + std::string(d ? "D" : "R") +
                       std::to_string(index) + ": " + files[index] + " and " + e.path().string());
    }
    files[index] = e.path().string();
  }
  if (study->d_files.empty() || study->r_files.empty()) {
    throw InputError(dir + ": needs images named D<i> and R<j> (.png, .pgm, .tif), found " +
                     std::to_string(study->d_files.size()) + " D and " +
                     std::to_string(study->r_files.size()) + " R");
  }
}

std::map<int, SarImageFile> ReadAll(const std::map<int, std::string>& files, double res,
                                    double max_pixels) {
  std::map<int, SarImageFile> images;
  for (const auto& [i, path] : files) images[i] = ReadSarImageFile(path, res, max_pixels);
  return images;
}

std::map<int, ImageFeatures> Features(const std::map<int, SarImageFile>& images,
                                      const std::vector<DetectorKind>& detectors,
                                      const PlaceRecognizerConfig& config, double feature_m) {
  std::map<int, ImageFeatures> out;
  for (const auto& [i, image] : images) {
    out[i] = ExtractImageFeatures(image, detectors, config, feature_m);
  }
  return out;
}

std::string Num(const char* fmt, double v) {
  char buf[48];
  std::snprintf(buf, sizeof(buf), fmt, v);
  return buf;
}

/// Per detector: good, scale, x, y, yaw ("-" when there is no transform).
std::vector<std::string> DetectorCells(const ImageMatch& m, DetectorKind kind) {
  const auto it = m.matches.find(kind);
  if (it == m.matches.end()) return {"-", "-", "-", "-", "-"};
  const auto t = m.detector_transforms.find(kind);
  if (t == m.detector_transforms.end()) {
    return {std::to_string(it->second.good_matches), "-", "-", "-", "-"};
  }
  return {std::to_string(it->second.good_matches), Num("%.3f", it->second.scale),
          Num("%.3f", t->second.x_m), Num("%.3f", t->second.y_m), Num("%.2f", t->second.yaw_deg)};
}

std::vector<std::vector<std::string>> Rows(const ImageLoopStudy& study) {
  std::vector<std::vector<std::string>> rows;
  for (const ImagePairResult& p : study.pairs) {
    std::vector<std::string> row = {std::to_string(p.d), std::to_string(p.r)};
    for (DetectorKind kind : study.rule_detectors) {
      for (std::string& c : DetectorCells(p.match, kind)) row.push_back(std::move(c));
    }
    const bool ok = p.match.accepted();
    row.push_back(ok ? Num("%.3f", p.match.transform.x_m) : "-");
    row.push_back(ok ? Num("%.3f", p.match.transform.y_m) : "-");
    row.push_back(ok ? Num("%.2f", p.match.transform.yaw_deg) : "-");
    row.push_back(ok ? "accepted" : "rejected");
    row.push_back(p.match.validation.reason);
    rows.push_back(std::move(row));
  }
  return rows;
}

/// d, r, five columns per detector of the pair (good_akaze, scale_akaze, x_akaze_m, ...), then
/// the fused transform and the decision.
std::vector<std::string> Header(const ImageLoopStudy& study) {
  std::vector<std::string> h = {"d", "r"};
  for (DetectorKind kind : study.rule_detectors) {
    const std::string n = DetectorColumnName(kind);
    for (const std::string& c :
         {"good_" + n, "scale_" + n, "x_" + n + "_m", "y_" + n + "_m", "yaw_" + n + "_deg"}) {
      h.push_back(c);
    }
  }
  for (const char* c : {"x_m", "y_m", "yaw_deg", "decision", "reason"}) h.push_back(c);
  return h;
}

}  // namespace

ImageLoopStudy RunImageLoopStudy(const std::string& dir, double resolution_m,
                                 const std::vector<DetectorKind>& detectors,
                                 const PlaceRecognizerConfig& config, double max_image_pixels) {
  ImageLoopStudy study;
  study.rule_detectors = config.place_recognition.validation.detectors;
  FindRegionImages(dir, &study);
  const double max_pixels = max_image_pixels;
  const auto d_images = ReadAll(study.d_files, resolution_m, max_pixels);
  const auto r_images = ReadAll(study.r_files, resolution_m, max_pixels);
  // One feature resolution for every image: the configured one, or the coarsest image's.
  double feature_m = config.place_recognition.detectors.feature_resolution_m;
  for (const auto* images : {&d_images, &r_images}) {
    for (const auto& [i, image] : *images) {
      feature_m = ImageFeatureResolution(feature_m, image.grid.resolution_m, config);
    }
  }
  const auto d = Features(d_images, detectors, config, feature_m);
  const auto r = Features(r_images, detectors, config, feature_m);
  for (const auto& [di, fd] : d) {
    for (const auto& [ri, fr] : r) {
      study.pairs.push_back({di, ri, MatchImages(fd, fr, config)});
    }
  }
  LoopMatrix& m = study.matrix;
  for (const auto& [i, path] : study.d_files) m.d_ids.push_back(i);
  for (const auto& [i, path] : study.r_files) m.r_ids.push_back(i);
  m.loops.assign(m.d_ids.size(), std::vector<int>(m.r_ids.size(), 0));
  m.reasons.assign(m.d_ids.size(), std::vector<std::string>(m.r_ids.size()));
  std::size_t k = 0;
  for (std::size_t i = 0; i < m.d_ids.size(); ++i) {
    for (std::size_t j = 0; j < m.r_ids.size(); ++j, ++k) {
      const ImageMatch& match = study.pairs[k].match;
      m.loops[i][j] = match.accepted() ? 1 : 0;
      if (!match.accepted()) m.reasons[i][j] = match.validation.reason;
    }
  }
  return study;
}

nlohmann::json ImageLoopStudyJson(const ImageLoopStudy& study) {
  nlohmann::json out;
  out["loops"] = study.matrix.loops;
  out["d"] = study.matrix.d_ids;
  out["r"] = study.matrix.r_ids;
  nlohmann::json pairs = nlohmann::json::array();
  for (const ImagePairResult& p : study.pairs) {
    nlohmann::json j = ImageMatchJson(p.match);
    j["d"] = p.d;
    j["r"] = p.r;
    pairs.push_back(j);
  }
  out["pairs"] = pairs;
  return out;
}

std::string PairsCsv(const ImageLoopStudy& study) {
  std::ostringstream out;
  const std::vector<std::string> h = Header(study);
  for (std::size_t i = 0; i < h.size(); ++i) out << (i ? "," : "") << h[i];
  out << "\n";
  for (std::vector<std::string> row : Rows(study)) {
    std::string& reason = row.back();
    std::replace(reason.begin(), reason.end(), ',', ';');  // one CSV field
    for (std::size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << row[i];
    out << "\n";
  }
  return out.str();
}

std::string PairsMarkdown(const ImageLoopStudy& study) {
  std::ostringstream out;
  out << "| D | R |";
  for (DetectorKind kind : study.rule_detectors) {
    out << " " << DetectorName(kind) << " good | scale | x (m) | y (m) | yaw (deg) |";
  }
  out << " fused x (m) | y (m) | yaw (deg) | decision | reason |\n|";
  for (std::size_t i = 0; i < Header(study).size(); ++i) out << "---|";
  out << "\n";
  for (std::vector<std::string> row : Rows(study)) {
    std::string& reason = row.back();
    std::replace(reason.begin(), reason.end(), '|', '/');
    out << "|";
    for (const std::string& c : row) out << " " << c << " |";
    out << "\n";
  }
  return out.str();
}

cv::Mat DrawLoopMatrix(const ImageLoopStudy& study) {
  const LoopMatrix& m = study.matrix;
  const int cell = 56, margin = 40;
  const int rows = static_cast<int>(m.d_ids.size()), cols = static_cast<int>(m.r_ids.size());
  cv::Mat img(margin + rows * cell + 4, margin + cols * cell + 4, CV_8UC3, cv::Scalar::all(255));
  const auto font = cv::FONT_HERSHEY_SIMPLEX;
  std::size_t k = 0;
  for (int i = 0; i < rows; ++i) {
    cv::putText(img, "D" + std::to_string(m.d_ids[i]), {4, margin + i * cell + cell / 2 + 6}, font,
                0.5, cv::Scalar::all(0), 1, cv::LINE_AA);
    for (int j = 0; j < cols; ++j, ++k) {
      const ImageMatch& match = study.pairs[k].match;
      int weaker = 0;
      const auto a = match.matches.find(DetectorKind::kAkaze);
      const auto o = match.matches.find(DetectorKind::kOrb);
      if (a != match.matches.end() && o != match.matches.end()) {
        weaker = std::min(a->second.good_matches, o->second.good_matches);
      }
      const cv::Rect r(margin + j * cell, margin + i * cell, cell - 2, cell - 2);
      const double shade = std::min(1.0, weaker / 60.0);
      const cv::Scalar fill = match.accepted() ? cv::Scalar(60, 200 - 80 * shade, 60)
                                               : cv::Scalar::all(235 - 120 * shade);
      cv::rectangle(img, r, fill, cv::FILLED);
      cv::putText(img, std::to_string(weaker), {r.x + 6, r.y + r.height - 8}, font, 0.45,
                  cv::Scalar::all(0), 1, cv::LINE_AA);
      if (match.accepted()) {
        cv::line(img, {r.x + 30, r.y + 22}, {r.x + 37, r.y + 30}, cv::Scalar::all(255), 2);
        cv::line(img, {r.x + 37, r.y + 30}, {r.x + 50, r.y + 10}, cv::Scalar::all(255), 2);
      }
    }
  }
  for (int j = 0; j < cols; ++j) {
    cv::putText(img, "R" + std::to_string(m.r_ids[j]), {margin + j * cell + 14, 26}, font, 0.5,
                cv::Scalar::all(0), 1, cv::LINE_AA);
  }
  return img;
}

}  // namespace uwbsar
