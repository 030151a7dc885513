#include "eval/region_study.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "frontend/strip_renderer.h"

namespace uwbsar {
namespace {

DetectorStats StatsFor(const RegionPair& p, DetectorKind kind) {
  auto it = p.matches.find(kind);
  return it == p.matches.end() ? DetectorStats{} : StatsOf(it->second);
}

StudyRegion MakeRegion(int index, const cv::Rect& rect, const ImageGrid& strip_grid,
                       const cv::Mat& strip, const RegionStudyConfig& config,
                       const std::vector<DetectorKind>& detectors) {
  StudyRegion r;
  r.index = index;
  r.rect = rect;
  r.grid = strip_grid;
  r.grid.x0_m = strip_grid.ColToX(rect.x);
  r.grid.y0_m = strip_grid.RowToY(rect.y);
  r.grid.cols = rect.width;
  r.grid.rows = rect.height;
  const DetectorConfig& d = config.place_recognition.detectors;
  r.image = MakeFeatureImage(strip(rect), config.enhance, d.mask_erode_px);
  for (DetectorKind kind : detectors) r.features[kind] = ComputeFeatures(r.image, kind, d);
  return r;
}

double ObservedFraction(const cv::Mat& strip, const cv::Rect& rect) {
  const cv::Mat crop = strip(rect);
  cv::Mat nonzero;
  if (crop.channels() == 2) {
    std::vector<cv::Mat> parts;
    cv::split(crop, parts);
    nonzero = (parts[0] != 0) | (parts[1] != 0);
  } else {
    nonzero = crop != 0;
  }
  return static_cast<double>(cv::countNonZero(nonzero)) / static_cast<double>(crop.total());
}

/// Regions along the departing path's main world axis, from its start, kept where both
/// passes observed at least a quarter of the region; features computed for each.
void CutRegions(const std::vector<ImagedScan>& depart, const RegionStudyConfig& config,
                const RegionStudyOptions& options, RegionStudy* study_ptr) {
  RegionStudy& study = *study_ptr;
  const Pose2& a = depart.front().T_world_robot;
  const Pose2& b = depart.back().T_world_robot;
  const bool along_x = std::abs(b.x_m - a.x_m) >= std::abs(b.y_m - a.y_m);
  const double start = along_x ? a.x_m : a.y_m;
  const double end = along_x ? b.x_m : b.y_m;
  const double dir = end >= start ? 1.0 : -1.0;
  const double extent = std::abs(end - start);
  const ImageGrid& g = study.strip_grid;
  int index = 0;
  for (double s = 0.0; s + options.region_length_m <= extent + 1e-6; s += options.region_step_m) {
    const double lo = start + dir * s, hi = start + dir * (s + options.region_length_m);
    const double v0 = std::min(lo, hi), v1 = std::max(lo, hi);
    cv::Rect rect;
    if (along_x) {
      const int c0 = static_cast<int>(std::lround(g.XToCol(v0)));
      const int c1 = static_cast<int>(std::lround(g.XToCol(v1)));
      rect = cv::Rect(c0, 0, c1 - c0, g.rows);
    } else {
      const int r0 = static_cast<int>(std::lround(g.YToRow(v1)));  // rows grow towards -y
      const int r1 = static_cast<int>(std::lround(g.YToRow(v0)));
      rect = cv::Rect(0, r0, g.cols, r1 - r0);
    }
    rect &= cv::Rect(0, 0, g.cols, g.rows);
    ++index;
    if (rect.area() == 0 || ObservedFraction(study.d_strip, rect) < 0.25 ||
        ObservedFraction(study.r_strip, rect) < 0.25) {
      continue;
    }
    study.d_regions.push_back(MakeRegion(index, rect, g, study.d_strip, config, options.detectors));
    study.r_regions.push_back(MakeRegion(index, rect, g, study.r_strip, config, options.detectors));
  }
}

}  // namespace

const RegionPair* RegionStudy::Find(int d, int r) const {
  for (const RegionPair& p : pairs) {
    if (p.d == d && p.r == r) return &p;
  }
  return nullptr;
}

std::size_t TurnaroundIndex(const std::vector<ImagedScan>& scans) {
  std::size_t best = 0;
  double best_d = -1.0;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    const double d = Distance(scans.front().T_world_robot, scans[k].T_world_robot);
    if (d > best_d) {
      best_d = d;
      best = k;
    }
  }
  return best;
}

RegionStudy RunRegionStudy(const std::vector<ImagedScan>& depart,
                           const std::vector<ImagedScan>& ret,
                           const std::vector<SensorGeometry>& sensors,
                           const RegionStudyConfig& config, const RegionStudyOptions& options) {
  if (depart.empty() || ret.empty()) {
    throw std::invalid_argument("region study: a pass has no scans");
  }
  RegionStudy study;
  std::vector<Pose2> poses;
  for (const auto* pass : {&depart, &ret}) {
    for (const ImagedScan& s : *pass) poses.push_back(s.T_world_robot);
  }
  study.strip_grid =
      WorldGridCovering(poses, sensors, config.keyframe.margin_m, config.imaging.pixel_size_m);
  const bool coherent = config.imaging.coherent();
  const int threads = std::max(1, config.imaging.num_threads);
  study.d_strip = RenderScans(depart, sensors, study.strip_grid, coherent, threads).image;
  study.r_strip = RenderScans(ret, sensors, study.strip_grid, coherent, threads).image;

  CutRegions(depart, config, options, &study);
  const PlaceRecognitionConfig& pr = config.place_recognition;
  study.stats_detectors = pr.validation.detectors;
  for (const StudyRegion& d : study.d_regions) {
    for (const StudyRegion& r : study.r_regions) {
      RegionPair pair;
      pair.d = d.index;
      pair.r = r.index;
      for (DetectorKind kind : options.detectors) {
        pair.matches[kind] = MatchFeatures(d.features.at(kind), r.features.at(kind), pr.matching);
      }
      const std::vector<DetectorKind>& rule = pr.validation.detectors;
      if (pair.matches.count(rule[0]) && pair.matches.count(rule[1])) {
        pair.validation =
            ValidateLoop(d.index, d.grid, r.index, r.grid, pair.matches, pr.validation);
      } else {
        pair.validation.reason = std::string(DetectorName(rule[0])) + " and " +
                                 DetectorName(rule[1]) + " were not both run";
      }
      PairStats stats;
      stats.d = d.index;
      stats.r = r.index;
      for (DetectorKind kind : rule) stats.detectors[kind] = StatsFor(pair, kind);
      study.stats.push_back(stats);
      study.pairs.push_back(std::move(pair));
    }
  }
  return study;
}

}  // namespace uwbsar
