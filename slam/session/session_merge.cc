#include "slam/session/session_merge.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>

#include "core/log.h"
#include "core/types.h"
#include "frontend/place_recognition/feature_matcher.h"
#include "frontend/place_recognition/loop_validator.h"
#include "slam/session/join_retirement.h"
#include "slam/session/landmark_join.h"

namespace uwbsar {
namespace {

struct Hypothesis {
  int a_id = 0, b_id = 0;  ///< b_id in the merged numbering
  Pose2 T_ij;
  Eigen::Matrix3d information;
  Pose2 T_mapA_mapB;  ///< where the loop puts the new session's frame
};

bool Agree(const Pose2& x, const Pose2& y, const SessionConfig& c) {
  const Pose2 d = Between(x, y);
  return std::hypot(d.x_m, d.y_m) <= c.connect_agree_m &&
         std::abs(NormalizeAngle(d.yaw_rad)) <= c.connect_agree_deg * M_PI / 180.0;
}

Point2 Centre(const SessionKeyframe& k, const Pose2& T_map_anchor) {
  return T_map_anchor * k.features.centre_anchor;
}

/// b renumbered: keyframe ids + id_offset, trajectories + trajectory_offset, landmarks +
/// landmark_offset, nothing fixed.
SessionData Renumbered(const SessionData& b, int id_offset, int trajectory_offset,
                       int landmark_offset) {
  SessionData out = b;
  for (SessionLandmark& l : out.landmarks) l.id += landmark_offset;
  for (SessionLineObservation& o : out.line_observations) {
    o.observation.node_id += id_offset;
    o.observation.landmark_id += landmark_offset;
  }
  for (SessionTrajectory& t : out.trajectories) t.id += trajectory_offset;
  for (SessionKeyframe& k : out.keyframes) {
    k.id += id_offset;
    k.features.id = k.id;
    k.trajectory += trajectory_offset;
    k.fixed = false;
  }
  for (SessionEdge& e : out.edges) {
    e.edge.from_id += id_offset;
    e.edge.to_id += id_offset;
    if (e.edge.trajectory >= 0) e.edge.trajectory += trajectory_offset;
  }
  for (SessionLoop& l : out.loops) {
    l.query_id += id_offset;
    l.match_id += id_offset;
  }
  for (SessionOdometry& o : out.odometry) o.trajectory += trajectory_offset;
  for (SessionAnchor& a : out.anchors) {
    a.id += id_offset;
    if (a.hub_id >= 0) a.hub_id += id_offset;
    a.trajectory += trajectory_offset;
  }
  return out;
}

/// The saved map's keyframes a new keyframe `kb` is matched against: all of them until
/// the new session is placed, then those within session.search_radius_m of where it lies.
std::vector<const SessionKeyframe*> MergeCandidates(const SessionData& a, const SessionKeyframe& kb,
                                                    const MergeReport& r, const SessionConfig& sc) {
  std::vector<const SessionKeyframe*> candidates;
  if (!r.connected) {
    for (const SessionKeyframe& ka : a.keyframes) candidates.push_back(&ka);
  } else {
    const Point2 p = Centre(kb, r.T_mapA_mapB * kb.T_map_anchor);
    for (const SessionKeyframe& ka : a.keyframes) {
      const Point2 q = Centre(ka, ka.T_map_anchor);
      if (std::hypot(p.x_m - q.x_m, p.y_m - q.y_m) <= sc.search_radius_m) {
        candidates.push_back(&ka);
      }
    }
  }
  return candidates;
}

/// Matches every keyframe of `b` (renumbered) against `a` in b's order. Until enough
/// validated loops agree on where b lies (session.connect_min_loops), they are kept in
/// `before`; then the agreeing ones and every later loop go into the graph (returned), and
/// `r` records the connection.
std::vector<Hypothesis> FindMergeLoops(const SessionData& a, const SessionData& b,
                                       const SessionSettings& config, MergeReport* report,
                                       std::vector<Hypothesis>* before,
                                       const std::function<void(double)>& on_progress) {
  MergeReport& r = *report;
  const SessionConfig& sc = config.session;
  const PlaceRecognitionConfig pr =
      AtFeatureResolution(config.place_recognition, FeatureDownsampling(config));
  // Path of each new trajectory at its start, so that connect_path_m counts from there.
  std::map<int, double> path_origin;
  for (const SessionOdometry& o : b.odometry) path_origin.emplace(o.trajectory, o.path_m);

  std::vector<Hypothesis> loops;  // the loops that go into the graph
  for (std::size_t n = 0; n < b.keyframes.size(); ++n) {
    const SessionKeyframe& kb = b.keyframes[n];
    if (on_progress) on_progress(static_cast<double>(n) / static_cast<double>(b.keyframes.size()));
    for (const SessionKeyframe* ka : MergeCandidates(a, kb, r, sc)) {
      ++r.candidates;
      const DetectorMap<MatchResult> matches = MatchDetectorPair(ka->features, kb.features, pr);
      const LoopValidation v =
          ValidateLoop(ka->id, ka->features.grid, kb.id, kb.features.grid, matches, pr.validation);
      if (!v.accepted) continue;
      ++r.validated;
      Hypothesis h;
      h.a_id = ka->id;
      h.b_id = kb.id;
      h.T_ij = v.constraint.T_ij;
      h.information = v.constraint.information;
      h.T_mapA_mapB = ka->T_map_anchor * h.T_ij * kb.T_map_anchor.Inverse();
      if (r.connected) {
        loops.push_back(h);
        continue;
      }
      before->push_back(h);
      std::vector<Hypothesis> agreeing;
      for (const Hypothesis& o : *before) {
        if (Agree(o.T_mapA_mapB, h.T_mapA_mapB, sc)) agreeing.push_back(o);
      }
      if (static_cast<int>(agreeing.size()) >= std::max(1, sc.connect_min_loops)) {
        r.connected = true;
        r.T_mapA_mapB = h.T_mapA_mapB;
        r.connect_keyframe_id = kb.id;
        r.connect_path_m = kb.path_end_m - path_origin[kb.trajectory];
        loops.insert(loops.end(), agreeing.begin(), agreeing.end());
        r.dropped = static_cast<int>(before->size() - agreeing.size());
      }
    }
  }
  return loops;
}

/// One graph: the saved map keeps its gauge (its fixed keyframes, else its first; every
/// keyframe with `freeze_saved_map`); the new session starts where it was placed; both
/// sessions' kept edges and the new loops (ShareLoopInformationPerKeyframe). Returns the new
/// loops' edge indices.
std::vector<int> BuildJointGraph(const SessionData& a, const SessionData& b,
                                 const Pose2& T_mapA_mapB, const std::vector<Hypothesis>& loops,
                                 bool freeze_saved_map, PoseGraph* graph) {
  bool any_fixed = false;
  for (const SessionKeyframe& k : a.keyframes) {
    graph->AddNode(k.id, k.T_map_anchor, false);
    if (k.fixed || freeze_saved_map) graph->FixNode(k.id), any_fixed = true;
  }
  if (!any_fixed && !a.keyframes.empty()) graph->FixNode(a.keyframes.front().id);
  for (const SessionKeyframe& k : b.keyframes) {
    graph->AddNode(k.id, T_mapA_mapB * k.T_map_anchor, false);
  }
  // An odometry edge's times are its keyframes' (a gyro base's bias acts over them): the file
  // keeps the stamps, not the edges' times.
  std::map<int, TimestampNs> stamp_of;
  for (const SessionData* s : {&a, &b}) {
    for (const SessionKeyframe& k : s->keyframes) stamp_of[k.id] = k.stamp_ns;
  }
  for (const SessionData* s : {&a, &b}) {
    for (const SessionEdge& e : s->edges) {
      if (e.rejected) continue;
      PoseGraphEdge edge = e.edge;
      const auto from = stamp_of.find(edge.from_id), to = stamp_of.find(edge.to_id);
      if (edge.kind == EdgeKind::kOdometry && from != stamp_of.end() && to != stamp_of.end() &&
          to->second >= from->second) {
        edge.begin_s = NsToSeconds(from->second);
        edge.end_s = NsToSeconds(to->second);
      }
      graph->AddEdge(edge);
    }
  }
  // Both sessions' walls, b's moved into a's map frame with it.
  for (const SessionData* s : {&a, &b}) {
    const Pose2 T_map_session = s == &b ? T_mapA_mapB : Pose2{};
    for (const SessionLandmark& l : s->landmarks)
      graph->AddLandmark(l.id, LineToWorld(T_map_session, l.line_map));
    for (const SessionLineObservation& o : s->line_observations) {
      if (!o.rejected) graph->AddLineObservation(o.observation);
    }
  }
  std::vector<PoseGraphEdge> between;
  for (const Hypothesis& h : loops) {
    PoseGraphEdge e;
    e.from_id = h.a_id;
    e.to_id = h.b_id;
    e.T_from_to = h.T_ij;
    e.information = h.information;
    e.kind = EdgeKind::kLoop;
    between.push_back(e);
  }
  ShareLoopInformationPerKeyframe(&between);
  std::vector<int> new_edges;
  for (const PoseGraphEdge& e : between) new_edges.push_back(graph->AddEdge(e));
  return new_edges;
}

/// `out` (a copy of the saved map) joined with `b` as `graph` solved it: every keyframe still
/// in the graph at its solved pose, the graph's edges, b's loops and the new ones (with their
/// verdicts at the solve, `solved`) between kept keyframes, and the anchors of both runs and of
/// the keyframes the join retired (`retired`).
void StoreJoined(const PoseGraph& graph, const std::vector<EdgeReport>& solved,
                 const SessionData& b, const std::vector<Hypothesis>& loops,
                 const std::vector<int>& new_edges, const std::vector<SessionAnchor>& retired,
                 MergeReport* r, SessionData* out) {
  const std::map<int, Pose2> poses = graph.GetPoses();
  const std::vector<PoseGraphEdge> edges = graph.Edges();
  const std::vector<EdgeReport> reports = graph.EdgeReports();
  out->keyframes.insert(out->keyframes.end(), b.keyframes.begin(), b.keyframes.end());
  out->keyframes.erase(std::remove_if(out->keyframes.begin(), out->keyframes.end(),
                                      [&](const SessionKeyframe& k) { return !poses.count(k.id); }),
                       out->keyframes.end());
  for (SessionKeyframe& k : out->keyframes) {
    k.T_map_anchor = poses.at(k.id);
    k.features.T_world_anchor = k.T_map_anchor;
  }
  out->edges.clear();
  for (std::size_t i = 0; i < edges.size(); ++i)
    out->edges.push_back({edges[i], reports[i].rejected});
  CaptureLandmarks(graph, out);
  out->loops.insert(out->loops.end(), b.loops.begin(), b.loops.end());
  std::map<int, const EdgeReport*> verdict;  // by AddEdge index
  for (const EdgeReport& e : solved) verdict[e.index] = &e;
  for (std::size_t i = 0; i < loops.size(); ++i) {
    SessionLoop l;
    l.query_id = loops[i].b_id;
    l.match_id = loops[i].a_id;
    l.validated = true;
    l.accepted = !verdict.at(new_edges[i])->rejected;
    l.T_ij = loops[i].T_ij;
    l.chi2 = verdict.at(new_edges[i])->chi2;
    l.reason = "between sessions";
    r->loop_edges_rejected += !l.accepted;
    out->loops.push_back(l);
  }
  // Loops to a retired keyframe go with it, as in a run's own session (CaptureSession).
  out->loops.erase(std::remove_if(out->loops.begin(), out->loops.end(),
                                  [&](const SessionLoop& l) {
                                    return !poses.count(l.query_id) || !poses.count(l.match_id);
                                  }),
                   out->loops.end());
  out->odometry.insert(out->odometry.end(), b.odometry.begin(), b.odometry.end());
  for (SessionAnchor a : b.anchors) {  // b's, placed in a's frame
    if (a.hub_id < 0) a.T_hub_anchor = r->T_mapA_mapB * a.T_hub_anchor;
    out->anchors.push_back(a);
  }
  out->anchors.insert(out->anchors.end(), retired.begin(), retired.end());
  FollowRetiredHubs(&out->anchors);
  // By run, in the order the runs joined, then in time (session_data.h).
  std::map<int, std::size_t> order;
  for (std::size_t i = 0; i < out->trajectories.size(); ++i) order[out->trajectories[i].id] = i;
  std::stable_sort(out->anchors.begin(), out->anchors.end(),
                   [&](const SessionAnchor& x, const SessionAnchor& y) {
                     const std::size_t ox = order[x.trajectory], oy = order[y.trajectory];
                     return ox != oy ? ox < oy : x.stamp_ns < y.stamp_ns;
                   });
}

}  // namespace

void ShareLoopInformationPerKeyframe(std::vector<PoseGraphEdge>* loops) {
  std::map<int, int> loops_of_keyframe;
  for (const PoseGraphEdge& e : *loops) ++loops_of_keyframe[e.to_id];
  for (PoseGraphEdge& e : *loops) e.information /= loops_of_keyframe.at(e.to_id);
}

SessionData MergeSessions(const SessionData& a_in, const SessionData& b_in,
                          const SessionSettings& config, MergeReport* report,
                          const std::function<void(double)>& on_progress) {
  MergeReport& r = *report;
  r = MergeReport{};
  // Ids offset past the saved map's never wrap: when the joined ids would pass kMaxJoinedId
  // (ids read from a file may be anything up to INT_MAX), both sessions are renumbered densely
  // first.
  const auto joined_max = [](const SessionData& x, const SessionData& y, bool keyframes) {
    const auto max_id = [keyframes](const SessionData& s) {
      return static_cast<std::int64_t>(keyframes ? s.MaxKeyframeId() : s.MaxTrajectoryId());
    };
    return max_id(x) + 1 + std::max<std::int64_t>(max_id(y), 0);
  };
  const bool dense =
      joined_max(a_in, b_in, true) > kMaxJoinedId || joined_max(a_in, b_in, false) > kMaxJoinedId;
  const SessionData a_dense = dense ? WithDenseIds(a_in) : SessionData();
  const SessionData& a = dense ? a_dense : a_in;
  r.renumbered = dense;
  r.id_offset = a.MaxKeyframeId() + 1;
  r.trajectory_offset = a.MaxTrajectoryId() + 1;
  SessionData b = Renumbered(dense ? WithDenseIds(b_in) : b_in, r.id_offset, r.trajectory_offset,
                             a.MaxLandmarkId() + 1);
  std::vector<Hypothesis> before;  // validated loops before placement
  const std::vector<Hypothesis> loops = FindMergeLoops(a, b, config, &r, &before, on_progress);
  Log(LogLevel::kDebug,
      "stage merge matching: " + std::to_string(b.keyframes.size()) + " keyframes against " +
          std::to_string(a.keyframes.size()) + ", " + std::to_string(r.candidates) +
          " pairs matched, " + std::to_string(r.validated) + " validated" +
          (r.connected ? ", placed after " + std::to_string(r.connect_path_m) + " m"
                       : ", not placed"));

  SessionData out = a;
  out.trajectories.insert(out.trajectories.end(), b.trajectories.begin(), b.trajectories.end());
  if (!r.connected) {
    r.reason = before.empty() ? "no loop connects the sessions (" + std::to_string(r.candidates) +
                                    " keyframe pairs matched)"
                              : std::to_string(before.size()) +
                                    " loops between the sessions, fewer than "
                                    "session.connect_min_loops agree on where the run lies";
    return out;
  }
  // The saved map's walls seen again are the same landmarks (within a tile of them).
  r.walls_reused =
      ReuseSavedWalls(a, r.T_mapA_mapB, config.place_recognition.wall_profiles.landmarks,
                      2.0 * config.keyframe.tile_length_m, &b);
  PoseGraph graph(config.backend);
  const std::vector<int> new_edges =
      BuildJointGraph(a, b, r.T_mapA_mapB, loops, config.session.freeze_saved_map, &graph);
  r.optimization = graph.Optimize();
  Log(LogLevel::kDebug, "stage merge optimisation: " + std::to_string(r.optimization.solve_time_s) +
                            " s, " + r.optimization.termination);
  r.loop_edges = static_cast<int>(loops.size());
  const std::vector<EdgeReport> solved = graph.EdgeReports();
  std::vector<const SessionKeyframe*> oldest_first;
  std::vector<int> new_ids;
  for (const SessionKeyframe& k : a.keyframes) oldest_first.push_back(&k);
  for (const SessionKeyframe& k : b.keyframes) oldest_first.push_back(&k), new_ids.push_back(k.id);
  const std::vector<SessionAnchor> retired =
      RetireRevisitedViews(oldest_first, new_ids, config.slam.place_views, &graph);
  r.retired = static_cast<int>(retired.size());
  StoreJoined(graph, solved, b, loops, new_edges, retired, &r, &out);
  return out;
}

}  // namespace uwbsar
