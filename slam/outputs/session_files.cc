#include "slam/outputs/session_files.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "backend/g2o_io.h"
#include "imaging/image_io.h"
#include "slam/map_job.h"
#include "slam/outputs/map_outputs.h"
#include "slam/outputs/map_report.h"
#include "slam/outputs/session_outputs.h"

namespace uwbsar::slam {
namespace fs = std::filesystem;
namespace {

using Stamped = std::vector<std::pair<TimestampNs, Pose2>>;

void Append(const Stamped& from, std::vector<std::pair<double, Pose2>>* to) {
  for (const auto& [t, p] : from) to->push_back({NsToSeconds(t), p});
}

/// loops.csv as a single run's (slam/outputs/map_outputs.cc), the matches' ratio and scale, which a
/// session does not keep, empty, and the runs of both ends last.
std::string JoinedLoopsCsv(const SessionData& session, const Config& config) {
  const std::vector<DetectorKind>& detectors = config.place_recognition.validation.detectors;
  std::ostringstream csv;
  csv << LoopsCsvHeader(detectors) << ",query_run,match_run\n";
  for (const SessionLoop& l : session.loops) {
    const bool v = l.validated;
    std::string reason = l.reason;
    for (char& c : reason) {
      if (c == ',' || c == '\n') c = ';';
    }
    csv << l.query_id << "," << l.match_id << ",";
    for (DetectorKind d : detectors) {
      const auto it = l.good_matches.find(d);
      csv << "," << (it == l.good_matches.end() ? "" : std::to_string(it->second)) << ",,";
    }
    csv << (v ? Fixed(l.T_ij.x_m, 4) : "") << "," << (v ? Fixed(l.T_ij.y_m, 4) : "") << ","
        << (v ? Fixed(l.T_ij.yaw_rad * 180.0 / M_PI, 3) : "") << ","
        << (v ? "accepted" : "rejected") << "," << reason << ","
        << (v ? (l.accepted ? "accepted" : "rejected") : "") << "," << (v ? Fixed(l.chi2, 3) : "")
        << "," << RunOfKeyframe(session, l.query_id) << "," << RunOfKeyframe(session, l.match_id)
        << "\n";
  }
  return csv.str();
}

}  // namespace

int RunOfKeyframe(const SessionData& s, int keyframe) {
  const SessionKeyframe* k = s.Find(keyframe);
  return k == nullptr ? -1 : k->trajectory;
}

int KeyframesMade(const SessionData& s, int run) {
  int n = 0;
  for (const SessionKeyframe& k : s.keyframes) n += k.trajectory == run;
  for (const SessionAnchor& a : s.anchors) n += a.trajectory == run;
  return n;
}

Stamped PlacedOdometry(const SessionData& s, int run) {
  const SessionKeyframe* first = nullptr;
  for (const SessionKeyframe& k : s.keyframes) {
    if (k.trajectory == run && (first == nullptr || k.stamp_ns < first->stamp_ns)) first = &k;
  }
  Stamped out;
  if (first == nullptr) return out;
  const Pose2 T_map_odom = first->T_map_anchor * first->T_odom_anchor.Inverse();
  for (const SessionOdometry& o : s.odometry) {
    if (o.trajectory == run) out.push_back({o.stamp_ns, T_map_odom * o.T_odom_robot});
  }
  return out;
}

std::vector<std::string> WriteJoinedRunFiles(
    const SessionData& session, const Config& config, const std::vector<int>& runs,
    const std::map<int, std::vector<OdometrySample>>& ground_truth, const std::string& dir) {
  std::vector<std::pair<double, Pose2>> trajectory, odometry, truth;
  std::vector<std::string> names = {"trajectory.tum", "odometry.tum", "loops.csv"};
  for (int run : runs) {
    Append(CorrectedTrajectory(session, run), &trajectory);
    Append(PlacedOdometry(session, run), &odometry);
    const auto gt = ground_truth.find(run);
    if (gt == ground_truth.end()) continue;
    std::vector<std::pair<double, Pose2>> own;
    for (const OdometrySample& g : gt->second)
      own.push_back({NsToSeconds(g.stamp_ns), g.T_world_robot});
    const std::string name = "ground_truth_" + std::to_string(run) + ".tum";
    WriteTum(dir + "/" + name, own);
    names.push_back(name);
    truth.insert(truth.end(), own.begin(), own.end());
  }
  WriteTum(dir + "/trajectory.tum", trajectory);
  WriteTum(dir + "/odometry.tum", odometry);
  WriteTextAtomic(dir + "/loops.csv", JoinedLoopsCsv(session, config));
  if (!truth.empty()) {
    WriteTum(dir + "/ground_truth.tum", truth);
    names.push_back("ground_truth.tum");
  }
  return names;
}

std::vector<std::vector<OdometrySample>> SavedGroundTruth(const std::string& dir,
                                                          const SessionData& session,
                                                          const Config& config) {
  std::vector<std::vector<OdometrySample>> out;
  std::error_code ec;
  for (const SessionTrajectory& t : session.trajectories) {
    std::string path = dir + "/ground_truth_" + std::to_string(t.id) + ".tum";
    if (!fs::exists(path, ec) && session.trajectories.size() == 1) path = dir + "/ground_truth.tum";
    out.push_back(fs::exists(path, ec) ? ReadGroundTruthFile(path, config.limits.max_input_file_mb)
                                       : std::vector<OdometrySample>{});
  }
  return out;
}

std::map<int, std::vector<OdometrySample>> GroundTruthByRun(
    const SessionData& session, const std::vector<std::vector<OdometrySample>>& per_run) {
  std::map<int, std::vector<OdometrySample>> out;
  for (std::size_t i = 0; i < session.trajectories.size() && i < per_run.size(); ++i) {
    if (!per_run[i].empty()) out[session.trajectories[i].id] = per_run[i];
  }
  return out;
}

}  // namespace uwbsar::slam
