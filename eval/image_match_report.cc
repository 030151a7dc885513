#include "eval/image_match_report.h"

#include <algorithm>
#include <cctype>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "core/errors.h"

namespace uwbsar {
namespace {

std::string LowerName(DetectorKind kind) {
  std::string name = DetectorName(kind);
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
}

nlohmann::json TransformJson(const CentredTransform& t) {
  return {{"x_m", t.x_m}, {"y_m", t.y_m}, {"yaw_deg", t.yaw_deg}};
}

cv::Scalar ColourOf(DetectorKind kind) {
  if (kind == DetectorKind::kAkaze) return {0, 255, 0};
  if (kind == DetectorKind::kOrb) return {0, 255, 255};
  return {255, 255, 0};
}

}  // namespace

nlohmann::json ImageMatchJson(const ImageMatch& match) {
  nlohmann::json out;
  out["accepted"] = match.accepted();
  out["reason"] = match.accepted() ? "" : match.validation.reason;
  out["transform"] = match.accepted() ? TransformJson(match.transform) : nlohmann::json();
  nlohmann::json detectors = nlohmann::json::object();
  for (const auto& [kind, m] : match.matches) {
    nlohmann::json d;
    d["keypoints"] = {m.keypoints_b, m.keypoints_a};  // A is the query (b), B the train (a)
    d["ratio_matches"] = m.ratio_matches;
    d["good"] = m.good_matches;
    const auto t = match.detector_transforms.find(kind);
    d["scale"] = m.has_transform ? nlohmann::json(m.scale) : nlohmann::json();
    if (t != match.detector_transforms.end()) {
      d.update(TransformJson(t->second));
    } else {
      d["x_m"] = d["y_m"] = d["yaw_deg"] = nullptr;
    }
    detectors[LowerName(kind)] = d;
  }
  out["detectors"] = detectors;
  // The dense refinement of a near agreement (dense_refinement.h); null when not tried.
  const LoopValidation& v = match.validation;
  out["refinement"] = nlohmann::json();
  if (v.refinement_tried) {
    const DenseRefinement& r = v.refinement;
    out["refinement"] = {
        {"accepted", v.refined},
        {"peak_ncc", r.peak_ncc},
        {"second_ncc", r.second_ncc},
        {"peak_ratio", r.peak_ratio},
        {"overlap_fraction", r.overlap_fraction},
        {"transform", r.found ? TransformJson(match.refinement_transform) : nlohmann::json()}};
  }
  return out;
}

cv::Mat DrawImageMatch(const ImageFeatures& a, const ImageFeatures& b, const ImageMatch& match) {
  cv::Mat canvas;
  bool first = true;
  for (const auto& [kind, m] : match.matches) {
    std::vector<cv::DMatch> all, good;
    for (std::size_t k = 0; k < m.matches.size(); ++k) {
      // The matcher's query is A (queryIdx) and its train B (trainIdx): A is drawn left.
      const cv::DMatch dm(m.matches[k].queryIdx, m.matches[k].trainIdx, m.matches[k].distance);
      all.push_back(dm);
      if (m.inlier[k]) good.push_back(dm);
    }
    const auto& ka = a.features.at(kind).keypoints;
    const auto& kb = b.features.at(kind).keypoints;
    const int flags = first ? static_cast<int>(cv::DrawMatchesFlags::DEFAULT)
                            : static_cast<int>(cv::DrawMatchesFlags::DRAW_OVER_OUTIMG);
    cv::drawMatches(a.image.gray, ka, b.image.gray, kb, all, canvas, cv::Scalar(0, 0, 140),
                    cv::Scalar(90, 90, 90), std::vector<char>(),
                    static_cast<cv::DrawMatchesFlags>(flags));
    cv::drawMatches(a.image.gray, ka, b.image.gray, kb, good, canvas, ColourOf(kind),
                    cv::Scalar::all(-1), std::vector<char>(),
                    cv::DrawMatchesFlags::DRAW_OVER_OUTIMG);
    first = false;
  }
  if (canvas.empty()) cv::hconcat(a.image.gray, b.image.gray, canvas);
  return canvas;
}

std::vector<DetectorKind> ParseDetectorList(const std::string& list) {
  std::vector<DetectorKind> out;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    DetectorKind kind;
    if (!ParseDetector(name, &kind))
      throw InputError("--detectors: unknown detector '" + name + "'");
    if (!DetectorAvailable(kind)) throw InputError("--detectors: " + name + " was not built");
    if (std::find(out.begin(), out.end(), kind) == out.end()) out.push_back(kind);
  }
  if (out.empty()) throw InputError("--detectors: no detector given");
  return out;
}

}  // namespace uwbsar
