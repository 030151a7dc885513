#include "tools/map_resume.h"

#include <chrono>
#include <cstdio>

#include "core/errors.h"
#include "slam/app_config.h"
#include "slam/outputs/map_outputs.h"
#include "slam/outputs/map_report.h"
#include "slam/outputs/session_capture.h"
#include "slam/outputs/session_files.h"
#include "slam/outputs/session_outputs.h"
#include "slam/outputs/summary_json.h"
#include "slam/session/session_file.h"
#include "slam/session/session_merge.h"
#include "tools/commands.h"

namespace uwbsar::tools {

slam::SavedSession OpenSessionToResume(const std::string& dir_or_file, const std::string& bag,
                                       const std::string& fingerprint, const Config& config) {
  slam::SavedSession saved = slam::OpenSavedSession(dir_or_file, config);
  SessionTrajectory run;
  run.input = bag;
  run.fingerprint = fingerprint;
  slam::RefuseRunsAlreadyJoined(saved.data, saved.path, {run}, bag);
  saved.ground_truth = slam::SavedGroundTruth(saved.dir, saved.data, config);
  return saved;
}

void PrintJoinedMap(const nlohmann::json& summary, const MergeReport& report,
                    std::size_t landmarks) {
  std::printf(
      "%d keyframes in the map (%d older views retired, with their loops), %d loops accepted in "
      "the map (%d between runs), %zu wall landmarks (%d seen again)\n",
      summary["keyframes"].get<int>(), report.retired, summary["loops"]["accepted"].get<int>(),
      summary["loops"]["between_runs"].get<int>(), landmarks, report.walls_reused);
}

void WriteResumedMap(const slam::SavedSession& saved, const slam::MapRun& run,
                     slam::MapOutputStage* stage, const std::string& out_dir,
                     const GlobalOptions& globals) {
  const Config& config = run.slam->config();
  MergeReport report;
  const auto join_start = std::chrono::steady_clock::now();
  const SessionData merged = MergeSessions(saved.data, slam::CaptureSession(run), config, &report);
  const double join_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - join_start).count();
  if (!report.connected) {
    throw InputError(run.input + ": does not connect to the saved map " + saved.path + " (" +
                     report.reason + "); nothing written. Map it on its own: uwbsar map " +
                     run.input + " --out ANOTHER_DIR");
  }
  // Every run's ground truth: the saved map's runs' from its folder, the new run's from its bag.
  std::vector<std::vector<OdometrySample>> per_run = saved.ground_truth;
  per_run.push_back(run.ground_truth);
  const std::map<int, std::vector<OdometrySample>> ground_truth =
      slam::GroundTruthByRun(merged, per_run);
  nlohmann::json extra;
  extra["input"] = run.input;
  // What this command did: the new run (its log, scans, stage times and solves), then the join.
  slam::CommandWork work{run.log_duration_s(),
                         run.processing_s + join_s,
                         run.slam->frontend_stats(),
                         run.slam->times(),
                         true,
                         run.slam->num_solves() + 1,
                         report.optimization};
  work.times.optimization_s += report.optimization.solve_time_s;
  slam::AddCommandWork(work, &extra);
  extra["merge"] = slam::MergeReportJson(report);
  // The report times what this command did: the new run's stages, then the join.
  const std::vector<slam::ReportTable> timing = {
      slam::StageTimingTable(run.slam->times(), run.processing_s, config.slam.keyframe_thread,
                             "Time per stage of run " + std::to_string(report.trajectory_offset) +
                                 " (mapped by this command)"),
      {"Time to join the saved map",
       {"step", "seconds"},
       {{"matching the run to the saved map, placing it and optimising the joined graph",
         slam::Fixed(join_s, 3)}},
       ""}};
  // Staged and committed as one set, like the plain map's outputs.
  const slam::SessionOutputs outputs = slam::CommitSessionOutputs(
      stage, merged, config, ground_truth, extra, "uwbsar map --resume: " + run.input, timing);
  if (globals.quiet) return;
  std::printf("mapped %.1f s of log in %.2f s: %zu keyframes\n", run.log_duration_s(),
              run.processing_s, run.slam->keyframes().size());
  std::printf(
      "joined the saved map as run %d after %.2f m (keyframe %d): %d loops between the runs "
      "found by the join (%d rejected by the backend), %d dropped before placement\n",
      report.trajectory_offset, report.connect_path_m, report.connect_keyframe_id,
      report.loop_edges, report.loop_edges_rejected, report.dropped);
  PrintJoinedMap(outputs.summary, report, merged.landmarks.size());
  std::printf("report: %s/report.html\n", out_dir.c_str());
  PrintOdometryCalibration(config, globals);
  PrintWrittenFolder(out_dir, outputs.files, globals);
}

}  // namespace uwbsar::tools
