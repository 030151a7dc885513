// Joining a run to a saved map (points 2 and 4): `uwbsar map --resume` and
// `uwbsar merge`. The new session's keyframes are matched, in their order, against the
// saved map: until the new run is placed, every saved keyframe is a candidate (its start
// pose is unknown: global search, as drought re-localisation does); a validated loop
// implies where the whole new run lies in the map frame, and the run is placed once
// session.connect_min_loops such loops agree. From then on the candidates are the saved
// keyframes near each new keyframe's placed estimate. Loops found before placement that
// disagree with it are dropped as false. Then one pose graph holds both sessions (both
// runs' odometry and loops, the new loops between them) and is optimised: with
// session.freeze_saved_map (the default) the saved keyframes are held where they are and the
// new run is fitted to them; without it, both move (the saved map's gauge is kept). Last, the
// new run's keyframes retire the older views of the places they revisit
// (slam/session/join_retirement.h), so the joined map keeps what one run would.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "backend/pose_graph.h"
#include "slam/session/session_data.h"
#include "slam/session/session_settings.h"

namespace uwbsar {

struct MergeReport {
  bool connected = false;
  std::string reason;            ///< why not connected
  int connect_keyframe_id = -1;  ///< the new keyframe (merged id) whose loop placed the run
  double connect_path_m = 0.0;   ///< the new run's path when it was placed (end of that tile)
  Pose2 T_mapA_mapB;             ///< the placement of the new session's frame
  int candidates = 0;            ///< keyframe pairs matched
  int validated = 0;             ///< of those, passed the validator
  int dropped = 0;               ///< validated before placement but disagreeing with it
  int loop_edges = 0;            ///< new loops between the sessions put into the graph
  int loop_edges_rejected = 0;   ///< of those, rejected by the backend
  int id_offset = 0;             ///< added to the new session's keyframe ids
  bool renumbered = false;       ///< both sessions' ids were made dense first (kMaxJoinedId)
  int trajectory_offset = 0;     ///< added to its trajectory ids
  int retired = 0;  ///< keyframes (of either run) the join retired (slam/session/join_retirement.h)
  int walls_reused =
      0;  ///< the new run's wall landmarks that are the saved map's (ReuseSavedWalls)
  OptimizeResult optimization;
};

/// Loops from one new keyframe (`to_id`) into n saved ones share that keyframe's tile, and with
/// it the tile's imaging error (its odometry distortion): one measurement of where the tile
/// lies, not n independent ones. Divides each loop's information by the n of its `to_id`, so a
/// new keyframe weighs like one loop however many saved keyframes overlap it (office, seed 1,
/// both runs optimised together: the new run's part 3.21 -> 2.83 cm, the saved one's 3.35 ->
/// 2.97 cm).
void ShareLoopInformationPerKeyframe(std::vector<PoseGraphEdge>* loops);

/// Joined keyframe and trajectory ids stay at or below this: a join whose offset ids would pass
/// it renumbers both sessions densely (WithDenseIds) first, so ids never approach INT_MAX.
constexpr std::int64_t kMaxJoinedId = std::int64_t{1} << 30;

/// `b` joined to `a` (both read under `config`). The result holds a's keyframes with their
/// ids and b's with ids + report->id_offset, in a's map frame (with report->renumbered, the
/// ids of both are first made dense: 0..n-1 in their order); when b cannot be connected
/// it is `a` unchanged plus b's trajectories (report->connected false, reason set) and b's
/// keyframes are not in it.
/// `on_progress` (optional) is called with the share of b's keyframes matched so far.
SessionData MergeSessions(const SessionData& a, const SessionData& b, const SessionSettings& config,
                          MergeReport* report,
                          const std::function<void(double)>& on_progress = nullptr);

}  // namespace uwbsar
