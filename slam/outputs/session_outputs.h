// The outputs of a session with several runs in one map frame (`uwbsar map --resume`,
// `uwbsar merge`): map.png (the mosaic with each run's trajectory in its own colour and the
// accepted loops), map_float.tif + map_grid.yaml, map.pgm + map.yaml, trajectory_<run>.tum
// per run (in the map frame), a single run's trajectory.tum, odometry.tum, ground_truth.tum
// and loops.csv over every run (slam/outputs/session_files.h), graph.g2o, session.uwbsar,
// report.html (as full as a plain map's: the annotated figures, the timings, the loop table and one
// section per run with its own figure; slam/outputs/session_report.h) and summary.json (last), with
// every key a single run's has (slam/outputs/summary_json.h). Every file is written to a temporary
// name and renamed.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "backend/trajectory_metrics.h"
#include "core/types.h"
#include "slam/app_config.h"
#include "slam/outputs/map_outputs.h"
#include "slam/outputs/report_html.h"
#include "slam/session/session_data.h"
#include "slam/session/session_merge.h"

namespace uwbsar::slam {

struct SessionOutputs {
  std::vector<std::string> files;
  nlohmann::json summary;
};

/// Writes the outputs of `session` into `out_dir` (created when missing). `ground_truth`
/// (optional) by trajectory id: that run's ATE goes into the summary, and the ATE of all
/// runs together after one common alignment ("ate_common"). `extra` is merged into
/// summary.json: the merge report and what the command did (AddCommandWork). `title` heads
/// report.html; `timing`: the tables of what this command timed (StageTimingTable of a resumed run,
/// the merge), shown before the loop table.
SessionOutputs WriteSessionOutputs(const SessionData& session, const Config& config,
                                   const std::string& out_dir,
                                   const std::map<int, std::vector<OdometrySample>>& ground_truth,
                                   const nlohmann::json& extra, const std::string& title,
                                   const std::vector<ReportTable>& timing = {});

/// WriteSessionOutputs into `stage`'s staging folder, committed into its DIR as one set
/// (slam/outputs/map_outputs.h MapOutputStage::CommitWritten): a failure leaves DIR as it was.
/// The returned files are the committed paths.
SessionOutputs CommitSessionOutputs(MapOutputStage* stage, const SessionData& session,
                                    const Config& config,
                                    const std::map<int, std::vector<OdometrySample>>& ground_truth,
                                    const nlohmann::json& extra, const std::string& title,
                                    const std::vector<ReportTable>& timing = {});

/// The ATE of several runs after one SE(2) alignment of all of them together (the common
/// frame), pairing poses by nearest stamp per run as TrajectoryError does.
AteResult CommonFrameError(const SessionData& session,
                           const std::map<int, std::vector<OdometrySample>>& ground_truth);

/// One run's odometry corrected by its optimised keyframes (as
/// SlamSystem::CorrectedTrajectory), in the session's map frame.
std::vector<std::pair<TimestampNs, Pose2>> CorrectedTrajectory(const SessionData& session,
                                                               int trajectory);

/// The merge report as JSON (summary.json's "merge").
nlohmann::json MergeReportJson(const MergeReport& report);

}  // namespace uwbsar::slam
