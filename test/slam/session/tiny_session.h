// A tiny, valid session built in memory (no simulation): three keyframes of one run with
// 8 x 8 tiles and a few fake AKAZE/ORB features, two odometry edges and a loop edge, one loop
// record and a few odometry samples. For the reader's hostile-input tests and the fuzz seed.
#pragma once

#include <opencv2/core.hpp>

#include "app/app_config_io.h"
#include "slam/app_config.h"
#include "slam/config/config_fingerprint.h"
#include "slam/session/session_data.h"

namespace uwbsar::testing {

inline FeatureSet TinyFeatures(DetectorKind kind, int descriptor_bytes, int seed) {
  FeatureSet f;
  f.detector = kind;
  f.norm_type = cv::NORM_HAMMING;
  for (int i = 0; i < 3; ++i) {
    f.keypoints.emplace_back(1.0f + static_cast<float>(i + seed), 2.0f + static_cast<float>(i),
                             4.0f, 10.0f * static_cast<float>(i), 0.5f, 0, -1);
  }
  f.descriptors = cv::Mat(3, descriptor_bytes, CV_8UC1);
  cv::randu(f.descriptors, 0, 256);
  return f;
}

/// Keyframe k at (k, 0.5 k) in the map, tiles of 8 x 8 pixels of 5 cm with positive pixels.
inline SessionData TinySession() {
  SessionData d;
  const Config config;
  d.config_yaml = ConfigToYaml(config);
  d.fingerprint = ConfigFingerprint(config);
  d.trajectories.push_back({0, "tiny.db3", "storage:tiny first:0 last:3 messages:12"});
  cv::theRNG().state = 7;
  for (int k = 0; k < 3; ++k) {
    SessionKeyframe s;
    s.id = k;
    s.trajectory = 0;
    s.stamp_ns = 1000000000LL * (k + 1);
    s.T_odom_anchor = {1.0 * k, 0.5 * k, 0.1 * k};
    s.T_odom_robot = {1.0 * k + 0.2, 0.5 * k, 0.1 * k};
    s.T_map_anchor = {1.0 * k + 0.01, 0.5 * k - 0.02, 0.1 * k + 0.003};
    s.path_begin_m = 1.0 * k;
    s.path_end_m = 1.0 * k + 1.0;
    s.fixed = k == 0;
    cv::Mat tile(8, 8, CV_32FC1);
    cv::randu(tile, 0.1, 1.0);
    s.detected = TileRef(tile);
    s.detected_grid.x0_m = -0.2;
    s.detected_grid.y0_m = 0.2;
    s.detected_grid.resolution_m = 0.05;
    s.detected_grid.rows = s.detected_grid.cols = 8;
    s.features.id = k;
    s.features.grid = s.detected_grid;
    s.features.grid.resolution_m = 0.1;
    s.features.grid.rows = s.features.grid.cols = 4;
    s.features.by_detector[DetectorKind::kAkaze] = TinyFeatures(DetectorKind::kAkaze, 61, k);
    s.features.by_detector[DetectorKind::kOrb] = TinyFeatures(DetectorKind::kOrb, 32, k);
    s.features.centre_anchor = {0.1, -0.1};
    s.features.path_begin_m = s.path_begin_m;
    s.features.T_world_anchor = s.T_map_anchor;
    d.keyframes.push_back(s);
  }
  for (int k = 0; k < 2; ++k) {
    SessionEdge e;
    e.edge.from_id = k;
    e.edge.to_id = k + 1;
    e.edge.kind = EdgeKind::kOdometry;
    e.edge.T_from_to = Between(d.keyframes[k].T_map_anchor, d.keyframes[k + 1].T_map_anchor);
    e.edge.trajectory = 0;
    e.edge.path_m = 1.0;
    d.edges.push_back(e);
  }
  SessionEdge loop;
  loop.edge.from_id = 0;
  loop.edge.to_id = 2;
  loop.edge.kind = EdgeKind::kLoop;
  loop.edge.T_from_to = Between(d.keyframes[0].T_map_anchor, d.keyframes[2].T_map_anchor);
  loop.edge.information = Eigen::Vector3d(100.0, 100.0, 400.0).asDiagonal();
  d.edges.push_back(loop);
  SessionLoop l;
  l.query_id = 2;
  l.match_id = 0;
  l.validated = l.accepted = true;
  l.T_ij = loop.edge.T_from_to;
  l.chi2 = 0.25;
  l.good_matches = {{DetectorKind::kAkaze, 12}, {DetectorKind::kOrb, 9}};
  l.reason = "accepted";
  d.loops.push_back(l);
  for (int i = 0; i < 5; ++i) {
    d.odometry.push_back({0, 500000000LL * (i + 1), Pose2{0.5 * i, 0.25 * i, 0.05 * i}, 0.56 * i});
  }
  return d;
}

}  // namespace uwbsar::testing
