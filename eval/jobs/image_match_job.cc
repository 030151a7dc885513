#include "eval/jobs/image_match_job.h"

#include <cstdio>
#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "core/errors.h"
#include "eval/image_loop_study.h"
#include "eval/image_match_report.h"
#include "imaging/image_io.h"
#include "slam/outputs/output_folder.h"

namespace uwbsar::eval {
namespace {

constexpr double kMaxExtentRatio = 4.0;  ///< larger differences in metric size are refused

void CheckComparable(const SarImageFile& a, const SarImageFile& b) {
  const double wa = a.grid.width_m(), wb = b.grid.width_m();
  const double ha = a.grid.height_m(), hb = b.grid.height_m();
  if (std::max(wa, wb) > kMaxExtentRatio * std::min(wa, wb) ||
      std::max(ha, hb) > kMaxExtentRatio * std::min(ha, hb)) {
    char buf[256];
    std::snprintf(buf, sizeof(buf),
                  "%s is %.2f m x %.2f m but %s is %.2f m x %.2f m: sizes differ by more than "
                  "%.0fx (check --resolution)",
                  a.path.c_str(), wa, ha, b.path.c_str(), wb, hb, kMaxExtentRatio);
    throw InputError(buf);
  }
}

/// Writes the study's files into out_dir; returns their paths.
std::vector<std::string> WriteStudy(const ImageLoopStudy& study, const std::string& out_dir) {
  slam::EnsureDirectory(out_dir);
  const std::filesystem::path dir(out_dir);
  const std::vector<std::string> files = {(dir / "pairs.csv").string(), (dir / "pairs.md").string(),
                                          (dir / "loops.json").string(),
                                          (dir / "matrix.png").string()};
  WriteTextAtomic(files[0], PairsCsv(study));
  WriteTextAtomic(files[1], PairsMarkdown(study));
  WriteTextAtomic(files[2], ImageLoopStudyJson(study).dump(2) + "\n");
  WriteImageAtomic(files[3], DrawLoopMatrix(study));
  return files;
}

}  // namespace

ImageMatchJobResult RunImageMatchJob(const Config& config, const ImageMatchJobOptions& o) {
  const std::vector<DetectorKind> detectors = o.detectors.empty()
                                                  ? config.place_recognition.validation.detectors
                                                  : ParseDetectorList(o.detectors);
  if (!o.out_dir.empty()) slam::EnsureDirectory(o.out_dir);
  const double max_pixels = config.limits.max_map_image_pixels;
  const SarImageFile a = ReadSarImageFile(o.a, o.resolution_m, max_pixels);
  const SarImageFile b = ReadSarImageFile(o.b, o.resolution_m, max_pixels);
  CheckComparable(a, b);
  const double feature_m = ImageFeatureResolution(a.grid.resolution_m, b.grid.resolution_m, config);
  const ImageFeatures fa = ExtractImageFeatures(a, detectors, config, feature_m);
  const ImageFeatures fb = ExtractImageFeatures(b, detectors, config, feature_m);
  ImageMatchJobResult result;
  result.match = MatchImages(fa, fb, config);
  result.json = ImageMatchJson(result.match);
  if (!o.out_dir.empty()) {
    const std::filesystem::path dir(o.out_dir);
    result.files = {(dir / "match.png").string(), (dir / "match.json").string()};
    WriteImageAtomic(result.files[0], DrawImageMatch(fa, fb, result.match));
    WriteTextAtomic(result.files[1], result.json.dump(2) + "\n");
  }
  return result;
}

LoopMatrixJobResult LoopMatrixFromStats(const Config& config, const std::string& stats_csv) {
  LoopMatrixJobResult result;
  result.matrix =
      EvaluateLoopMatrix(ReadPairStatsFile(stats_csv, config.place_recognition.validation.detectors,
                                           config.limits.max_input_file_mb),
                         config.place_recognition.validation);
  const LoopMatrix& m = result.matrix;
  result.json = {{"loops", m.loops}, {"d", m.d_ids}, {"r", m.r_ids}};
  return result;
}

LoopMatrixJobResult LoopMatrixFromImages(const Config& config, const std::string& images_dir,
                                         double resolution_m, const std::string& detectors,
                                         const std::string& out_dir) {
  const std::vector<DetectorKind> kinds = detectors.empty()
                                              ? config.place_recognition.validation.detectors
                                              : ParseDetectorList(detectors);
  if (!out_dir.empty()) slam::EnsureDirectory(out_dir);
  const ImageLoopStudy study = RunImageLoopStudy(images_dir, resolution_m, kinds, config,
                                                 config.limits.max_map_image_pixels);
  LoopMatrixJobResult result{study.matrix, ImageLoopStudyJson(study), {}};
  if (!out_dir.empty()) result.files = WriteStudy(study, out_dir);
  return result;
}

}  // namespace uwbsar::eval
