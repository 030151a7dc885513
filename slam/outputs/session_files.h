// The files a single run's folder holds, written for a joined map too (`uwbsar map --resume`,
// `uwbsar merge`; README "Outputs"): trajectory.tum, odometry.tum, ground_truth.tum and
// loops.csv over every run, and ground_truth_<run>.tum per run with ground truth, which a
// later join of the folder reads back so that every run keeps its ATE.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/types.h"
#include "slam/app_config.h"
#include "slam/session/session_data.h"

namespace uwbsar::slam {

/// The run of keyframe `keyframe` (-1 when the session has no such keyframe).
int RunOfKeyframe(const SessionData& session, int keyframe);

/// The keyframes run `run` made: those the map keeps and those later views retired (anchors).
int KeyframesMade(const SessionData& session, int run);

/// Run `run`'s odometry in the map frame, placed where its first keyframe was optimised to:
/// how far the uncorrected odometry drifts from the corrected path.
std::vector<std::pair<TimestampNs, Pose2>> PlacedOdometry(const SessionData& session, int run);

/// Into `dir`, over the runs `runs` one after another (in that order): trajectory.tum (each
/// run's CorrectedTrajectory), odometry.tum (each run's PlacedOdometry), loops.csv (every loop
/// record, a single run's columns and query_run, match_run) and, when a run has ground truth,
/// ground_truth.tum (theirs) and ground_truth_<run>.tum for each. Returns the names written.
std::vector<std::string> WriteJoinedRunFiles(
    const SessionData& session, const Config& config, const std::vector<int>& runs,
    const std::map<int, std::vector<OdometrySample>>& ground_truth, const std::string& dir);

/// The ground truth of each run of the saved map in `dir` (`session` read from it), in the
/// order of session.trajectories (empty where it has none): ground_truth_<id>.tum, or, for a
/// folder of one run, ground_truth.tum. InputError naming the file and line when one is damaged.
std::vector<std::vector<OdometrySample>> SavedGroundTruth(const std::string& dir,
                                                          const SessionData& session,
                                                          const Config& config);

/// `per_run` (the ground truth of each of session.trajectories, in their order) by run id,
/// the runs without ground truth left out.
std::map<int, std::vector<OdometrySample>> GroundTruthByRun(
    const SessionData& session, const std::vector<std::vector<OdometrySample>>& per_run);

}  // namespace uwbsar::slam
