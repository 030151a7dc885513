#include "slam/outputs/session_capture.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "slam/app_config_io.h"
#include "slam/config/config_fingerprint.h"
#include "slam/session/landmark_join.h"
#include "slam/session/session_file.h"

namespace uwbsar::slam {
namespace {

// With session.odometry_spacing_m: a sample is kept after this turn or this time as well.
constexpr double kOdometryKeepTurnRad = M_PI / 180.0;
constexpr TimestampNs kOdometryKeepIntervalNs = 1'000'000'000;

}  // namespace

SessionData CaptureSession(const MapRun& run) {
  const SlamSystem& slam = *run.slam;
  SessionData d;
  d.config_yaml = ConfigToYaml(slam.config());
  d.fingerprint = ConfigFingerprint(slam.config());
  // A run without a recording's identity (a simulation, a live run) is identified by what it
  // is and when it began.
  d.trajectories.push_back({0, run.input,
                            !run.fingerprint.empty()
                                ? run.fingerprint
                                : "run " + run.input + " " + std::to_string(run.first_stamp_ns)});
  const std::map<int, Pose2> poses = slam.KeyframePoses();
  const std::vector<int> fixed = slam.graph().FixedNodes();
  for (const KeyframeRecord& r : slam.keyframes()) {
    const Keyframe& k = r.keyframe;
    const KeyframeFeatures* f = slam.recognizer().Find(k.id);
    if (f == nullptr) throw std::logic_error("keyframe without features: " + std::to_string(k.id));
    SessionKeyframe s;
    s.id = k.id;
    s.trajectory = 0;
    s.stamp_ns = k.stamp_ns;
    s.T_odom_anchor = k.T_world_anchor;
    s.T_odom_robot = k.T_world_robot;
    s.T_map_anchor = poses.at(k.id);
    s.path_begin_m = k.path_begin_m;
    s.path_end_m = k.path_end_m;
    s.fixed = std::find(fixed.begin(), fixed.end(), k.id) != fixed.end();
    s.detected = r.detected;  // shared, not read back: the session file is written tile by tile
    s.detected_grid = r.detected_grid;
    s.features = *f;
    s.features.T_world_anchor = s.T_map_anchor;
    d.keyframes.push_back(std::move(s));
  }
  // Retired keyframes follow a kept one: a hub retired later is followed to the one it follows.
  std::map<int, const RetiredKeyframe*> retired;
  for (const RetiredKeyframe& r : slam.retired()) retired[r.id] = &r;
  for (const RetiredKeyframe& r : slam.retired()) {
    SessionAnchor a;
    a.id = r.id;
    a.trajectory = 0;
    a.stamp_ns = r.stamp_ns;
    a.T_odom_anchor = r.T_odom_anchor;
    a.hub_id = r.hub_id;
    a.T_hub_anchor = r.T_hub_anchor;
    for (auto hub = retired.find(a.hub_id); hub != retired.end(); hub = retired.find(a.hub_id)) {
      a.T_hub_anchor = hub->second->T_hub_anchor * a.T_hub_anchor;
      a.hub_id = hub->second->hub_id;
    }
    if (a.hub_id >= 0 && !poses.count(a.hub_id)) continue;  // never: hubs are kept or retired
    d.anchors.push_back(a);
  }
  std::stable_sort(
      d.anchors.begin(), d.anchors.end(),
      [](const SessionAnchor& x, const SessionAnchor& y) { return x.stamp_ns < y.stamp_ns; });
  const std::vector<PoseGraphEdge> edges = slam.graph().Edges();
  const std::vector<EdgeReport> reports = slam.graph().EdgeReports();
  for (std::size_t i = 0; i < edges.size(); ++i) {
    d.edges.push_back({edges[i], i < reports.size() && reports[i].rejected});
  }
  CaptureLandmarks(slam.graph(), &d);
  for (const LoopRecord& l : slam.loops()) {
    // A retired keyframe's loops went into the marginal edges with it: the session keeps the
    // loops between the keyframes it holds.
    if (!poses.count(l.query_id) || !poses.count(l.match_id)) continue;
    SessionLoop s;
    s.query_id = l.query_id;
    s.match_id = l.match_id;
    s.validated = l.validation.accepted;
    s.accepted = l.accepted();
    s.T_ij = l.validation.constraint.T_ij;
    s.chi2 = l.chi2;
    for (const auto& [kind, m] : l.matches) s.good_matches[kind] = m.good_matches;
    s.reason = l.validation.reason;
    d.loops.push_back(std::move(s));
  }
  // Thinned (session.odometry_spacing_m): a stop or a turn on the spot still leaves samples.
  const double spacing_m = slam.config().session.odometry_spacing_m;
  const std::vector<OdometryEntry>& odometry = slam.odometry();
  for (std::size_t i = 0; i < odometry.size(); ++i) {
    const OdometryEntry& e = odometry[i];
    if (spacing_m > 0 && !d.odometry.empty() && i + 1 < odometry.size()) {
      const SessionOdometry& last = d.odometry.back();
      const bool moved = e.path_m - last.path_m >= spacing_m;
      const bool turned =
          std::abs(NormalizeAngle(e.T_world_robot.yaw_rad - last.T_odom_robot.yaw_rad)) >=
          kOdometryKeepTurnRad;
      const bool waited = e.stamp_ns - last.stamp_ns >= kOdometryKeepIntervalNs;
      if (!moved && !turned && !waited) continue;
    }
    d.odometry.push_back({0, e.stamp_ns, e.T_world_robot, e.path_m});
  }
  return d;
}

void SaveSessionWithOutputs(MapOutputStage* stage, const MapRun& run) {
  stage->SetExtraOutputs([&run](const std::string& dir) {
    WriteSession(dir + "/" + kSessionFileName, CaptureSession(run),
                 run.slam->config().session.lossless_tiles);
    return std::vector<std::string>{kSessionFileName};
  });
}

}  // namespace uwbsar::slam
