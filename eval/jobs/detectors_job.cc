#include "eval/jobs/detectors_job.h"

#include <cstdio>
#include <map>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "core/errors.h"
#include "core/message.h"
#include "drivers/logs/log_source.h"
#include "drivers/rosbag/robot_bag.h"
#include "eval/image_match_report.h"
#include "eval/region_study.h"
#include "frontend/imaging_frontend.h"
#include "imaging/image_io.h"
#include "slam/outputs/output_folder.h"
#include "slam/progress.h"

namespace uwbsar::eval {
namespace {

std::string Fmt(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), fmt, v);
  return buf;
}

/// Good matches (green) over ratio-test matches (red), D on the left like the paper.
cv::Mat DrawMatches(const StudyRegion& d, const StudyRegion& r, DetectorKind kind,
                    const MatchResult& m) {
  std::vector<cv::DMatch> all, good;
  for (std::size_t k = 0; k < m.matches.size(); ++k) {
    const cv::DMatch dm(m.matches[k].trainIdx, m.matches[k].queryIdx, m.matches[k].distance);
    all.push_back(dm);
    if (m.inlier[k]) good.push_back(dm);
  }
  cv::Mat out;
  const auto& kd = d.features.at(kind).keypoints;
  const auto& kr = r.features.at(kind).keypoints;
  cv::drawMatches(d.image.gray, kd, r.image.gray, kr, all, out, cv::Scalar(0, 0, 255),
                  cv::Scalar(255, 200, 0));
  cv::drawMatches(d.image.gray, kd, r.image.gray, kr, good, out, cv::Scalar(0, 255, 0),
                  cv::Scalar::all(-1), std::vector<char>(), cv::DrawMatchesFlags::DRAW_OVER_OUTIMG);
  return out;
}

struct Outputs {
  std::ostringstream t3_csv, t3_md, t4_csv, t4_md, stats, loops_csv, loops_md;
};

/// Table III: every detector on the loop events D_i -> R_i.
void WriteTable3(const RegionStudy& s, const RegionStudyOptions& options, double px_m, Outputs* o) {
  o->t3_csv << "detector,loop,keypoints_d,keypoints_r,ratio_matches,good_matches,good_pct,"
               "detect_ms,match_ms,scale,tx_mm,ty_mm,rot_deg\n";
  o->t3_md << "| Desc. | Loop | #Keypts D, R | %Good matches | Matching time (ms) | "
              "scale, tx (mm), "
              "ty (mm), rot (deg) |\n|---|---|---|---|---|---|\n";
  for (DetectorKind kind : options.detectors) {
    double time_sum = 0.0;
    int n = 0;
    for (const StudyRegion& d : s.d_regions) {
      const RegionPair* p = s.Find(d.index, d.index);
      if (!p) continue;
      const MatchResult& m = p->matches.at(kind);
      const double detect = 0.5 * (d.features.at(kind).detect_ms +
                                   s.r_regions.at(static_cast<std::size_t>(&d - &s.d_regions[0]))
                                       .features.at(kind)
                                       .detect_ms);
      time_sum += 2 * detect + m.match_ms;
      ++n;
      const std::string loop = "D" + std::to_string(d.index) + "->R" + std::to_string(d.index);
      const std::string tf = m.has_transform
                                 ? Fmt("%.2f", m.scale) + "," + Fmt("%.1f", m.tx_px * px_m * 1e3) +
                                       "," + Fmt("%.1f", m.ty_px * px_m * 1e3) + "," +
                                       Fmt("%.2f", m.rotation_deg)
                                 : "-,-,-,-";
      o->t3_csv << DetectorName(kind) << "," << loop << "," << m.keypoints_a << "," << m.keypoints_b
                << "," << m.ratio_matches << "," << m.good_matches << ","
                << Fmt("%.1f", m.good_match_percent()) << "," << Fmt("%.2f", detect) << ","
                << Fmt("%.3f", m.match_ms) << "," << tf << "\n";
      std::string tf_md = tf;
      for (char& c : tf_md) c = c == ',' ? ' ' : c;
      o->t3_md << "| " << DetectorName(kind) << " | " << loop << " | " << m.keypoints_a << ", "
               << m.keypoints_b << " | " << Fmt("%.1f", m.good_match_percent()) << " | "
               << Fmt("%.2f", 2 * detect + m.match_ms) << " | " << tf_md << " |\n";
    }
    if (n > 0) {
      o->t3_md << "| " << DetectorName(kind) << " | average | | | " << Fmt("%.2f", time_sum / n)
               << " (2 detections + matching) | |\n";
    }
  }
}

/// Table IV: AKAZE and ORB on the non-loop events |i - j| >= 2.
void WriteTable4(const RegionStudy& s, double px_m, Outputs* o) {
  o->t4_csv << "detector,event,total_matches,good_matches,scale,tx_m,ty_m,rot_deg\n";
  o->t4_md << "| Desc. | non-loop event | Total matches | Good matches | scale, tx (m), ty (m), "
              "rot (deg) |\n|---|---|---|---|---|\n";
  for (DetectorKind kind : {DetectorKind::kAkaze, DetectorKind::kOrb}) {
    for (const RegionPair& p : s.pairs) {
      if (std::abs(p.d - p.r) < 2 || !p.matches.count(kind)) continue;
      const MatchResult& m = p.matches.at(kind);
      const std::string ev = "D" + std::to_string(p.d) + "->R" + std::to_string(p.r);
      const std::string tf =
          m.has_transform ? Fmt("%.2f", m.scale) + "," + Fmt("%.2f", m.tx_px * px_m) + "," +
                                Fmt("%.2f", m.ty_px * px_m) + "," + Fmt("%.2f", m.rotation_deg)
                          : "-,-,-,-";
      o->t4_csv << DetectorName(kind) << "," << ev << "," << m.ratio_matches << ","
                << m.good_matches << "," << tf << "\n";
      std::string tf_md = tf;
      for (char& c : tf_md) c = c == ',' ? ' ' : c;
      o->t4_md << "| " << DetectorName(kind) << " | " << ev << " | " << m.ratio_matches << " | "
               << m.good_matches << " | " << tf_md << " |\n";
    }
  }
}

/// The per-pair statistics, and the loop matrix and list of the AKAZE+ORB rule.
void WriteStatsAndLoops(const RegionStudy& s, Outputs* o) {
  o->stats << [&s] {
    std::string h;
    for (const std::string& c : PairStatsColumns(s.stats_detectors))
      h += (h.empty() ? "" : ",") + c;
    return h;
  }() << "\n";
  for (const PairStats& p : s.stats) o->stats << PairStatsRow(p, s.stats_detectors) << "\n";
  o->loops_csv << "d,r,accepted,x_m,y_m,yaw_deg,reason\n";
  o->loops_md << "| D \\ R |";
  for (const StudyRegion& r : s.r_regions) o->loops_md << " R" << r.index << " |";
  o->loops_md << "\n|---|";
  for (std::size_t k = 0; k < s.r_regions.size(); ++k) o->loops_md << "---|";
  o->loops_md << "\n";
  for (const StudyRegion& d : s.d_regions) {
    o->loops_md << "| D" << d.index << " |";
    for (const StudyRegion& r : s.r_regions) {
      const RegionPair* p = s.Find(d.index, r.index);
      const bool ok = p && p->validation.accepted;
      o->loops_md << (ok ? " 1 |" : " 0 |");
      if (!p) continue;
      const Pose2& t = p->validation.constraint.T_ij;
      o->loops_csv << p->d << "," << p->r << "," << (ok ? 1 : 0) << ","
                   << (ok ? Fmt("%.4f", t.x_m) + "," + Fmt("%.4f", t.y_m) + "," +
                                Fmt("%.3f", t.yaw_rad * 180.0 / M_PI)
                          : ",,")
                   << ",\"" << p->validation.reason << "\"\n";
    }
    o->loops_md << "\n";
  }
}

void WriteTables(const RegionStudy& s, const RegionStudyOptions& options, double px_m, Outputs* o) {
  WriteTable3(s, options, px_m, o);
  WriteTable4(s, px_m, o);
  WriteStatsAndLoops(s, o);
}

RegionStudyOptions StudyOptions(const DetectorsJobOptions& opts) {
  RegionStudyOptions options;
  if (!opts.regions.empty()) {
    options.region_length_m = opts.regions[0];
    options.region_step_m = opts.regions[1];
    if (!(options.region_length_m > 0) || !(options.region_step_m > 0)) {
      throw InputError("--regions: length and step must be > 0");
    }
  }
  if (!opts.detectors.empty()) options.detectors = ParseDetectorList(opts.detectors);
  return options;
}

/// The share of the progress bar that imaging the bag fills; matching the regions fills most
/// of the rest.
constexpr double kImagingShare = 0.4;

/// The bag's scans that `frontend` imaged, in time order.
std::vector<ImagedScan> ImageBag(const std::string& bag, const Config& config,
                                 ImagingFrontend* frontend, slam::ProgressBar* bar) {
  bar->Update(0.0, "reading the bag");
  const rosbag::RobotLog log = rosbag::LoadRobotBag(bag, rosbag::RobotBagOptionsFromConfig(config));
  std::vector<ImagedScan> scans;
  frontend->SetScanObserver([&](const ImagedScan& s) { scans.push_back(s); });
  const TimestampNs start = log.odometry.empty() ? 0 : log.odometry.front().stamp_ns;
  const TimestampNs end = log.odometry.empty() ? 0 : log.odometry.back().stamp_ns;
  const double span = static_cast<double>(end) - static_cast<double>(start);
  // The one merge of a log's streams (odometry first on equal stamps); imaging only, so the
  // messages go to the frontend (FeedScanOrOdometry) rather than into a SlamSystem.
  LogSource(log.odometry, log.scans).Run([&](const Message& m) {
    if (span > 0) {
      bar->Update(
          kImagingShare * (static_cast<double>(m.stamp_ns) - static_cast<double>(start)) / span,
          "imaging");
    }
    FeedScanOrOdometry(*frontend, m);
  });
  frontend->Finish();
  if (scans.size() < 10) throw InputError(bag + ": fewer than 10 radar scans could be imaged");
  return scans;
}

/// Index of the first scan of the returning pass: at --split-path-m, else where the run
/// turns back.
std::size_t SplitIndex(const std::vector<ImagedScan>& scans, const DetectorsJobOptions& opts) {
  std::size_t turn = TurnaroundIndex(scans);
  if (opts.split_path_m > 0) {
    turn = 0;
    while (turn < scans.size() && scans[turn].path_m < opts.split_path_m) ++turn;
  }
  if (turn < 1 || turn + 1 >= scans.size()) {
    throw InputError(opts.bag + ": cannot split the run into a departing and a returning pass");
  }
  return turn;
}

void WriteDetectorOutputs(const std::string& dir, const Outputs& out, const RegionStudy& study,
                          const RegionStudyOptions& options, bool images) {
  WriteTextAtomic(dir + "table3.csv", out.t3_csv.str());
  WriteTextAtomic(dir + "table3.md", out.t3_md.str());
  WriteTextAtomic(dir + "table4.csv", out.t4_csv.str());
  WriteTextAtomic(dir + "table4.md", out.t4_md.str());
  WriteTextAtomic(dir + "stats.csv", out.stats.str());
  WriteTextAtomic(dir + "loops.csv", out.loops_csv.str());
  WriteTextAtomic(dir + "loops.md", out.loops_md.str());
  if (!images) return;
  for (std::size_t k = 0; k < study.d_regions.size(); ++k) {
    const StudyRegion& d = study.d_regions[k];
    const RegionPair* p = study.Find(d.index, d.index);
    for (DetectorKind kind : options.detectors) {
      WriteImageAtomic(dir + "matches/" + DetectorName(kind) + "_D" + std::to_string(d.index) +
                           "_R" + std::to_string(d.index) + ".png",
                       DrawMatches(d, study.r_regions[k], kind, p->matches.at(kind)));
    }
  }
}

}  // namespace

DetectorsJobResult RunDetectorsJob(const Config& config, const DetectorsJobOptions& opts) {
  slam::EnsureDirectory(opts.out_dir);  // every output is checked before the work
  if (!opts.no_images) slam::EnsureDirectory(opts.out_dir + "/matches");
  const RegionStudyOptions options = StudyOptions(opts);
  ImagingFrontend frontend(config);
  slam::ProgressBar bar(opts.progress, "of the detector comparison");
  const std::vector<ImagedScan> scans = ImageBag(opts.bag, config, &frontend, &bar);
  const std::size_t turn = SplitIndex(scans, opts);
  const std::vector<ImagedScan> depart(scans.begin(), scans.begin() + static_cast<long>(turn));
  const std::vector<ImagedScan> back(scans.begin() + static_cast<long>(turn), scans.end());
  bar.Update(kImagingShare, "matching the regions");
  const RegionStudy study = RunRegionStudy(depart, back, frontend.sensors(), config, options);
  bar.Update(0.9, "writing");
  if (study.d_regions.empty()) throw InputError(opts.bag + ": the passes share no region");
  Outputs out;
  WriteTables(study, options, config.imaging.pixel_size_m, &out);
  const std::string dir = opts.out_dir + "/";
  WriteDetectorOutputs(dir, out, study, options, !opts.no_images);
  bar.Update(1.0, "done");
  DetectorsJobResult result;
  result.scans = scans.size();
  result.departing = depart.size();
  result.returning = back.size();
  result.regions = study.d_regions.size();
  result.region_length_m = options.region_length_m;
  result.region_step_m = options.region_step_m;
  result.table3_md = out.t3_md.str();
  result.table4_md = out.t4_md.str();
  result.loops_md = out.loops_md.str();
  result.dir = dir;
  return result;
}

}  // namespace uwbsar::eval
