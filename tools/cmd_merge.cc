// `uwbsar merge SESSION_A SESSION_B --out DIR`: two sessions of the same building joined by
// loops found between them (slam/session/session_merge.h), written as one map.
#include <chrono>
#include <cstdio>

#include "core/errors.h"
#include "slam/app_config.h"
#include "slam/jobs/saved_session.h"
#include "slam/outputs/map_report.h"
#include "slam/outputs/session_files.h"
#include "slam/outputs/session_outputs.h"
#include "slam/outputs/summary_json.h"
#include "slam/progress.h"
#include "slam/session/session_file.h"
#include "slam/session/session_merge.h"
#include "tools/commands.h"
#include "tools/map_resume.h"

namespace uwbsar::tools {

void AddMergeCommand(CLI::App& app, const GlobalOptions& globals) {
  struct Options {
    std::string a, b, out_dir;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "merge",
      "Join two saved sessions of the same building into one map (refused without a loop)");
  cmd->add_option("session_a", opts->a, "The map kept fixed (folder or session.uwbsar)")
      ->required();
  cmd->add_option("session_b", opts->b, "The session joined to it")->required();
  cmd->add_option("--out", opts->out_dir, "Output folder")->required()->check(OutputPath("--out"));
  cmd->callback([opts, &globals] {
    const Config config = LoadConfigFor(globals);
    // Either session's folder may be the output: the join replaces its outputs as one set.
    RefuseOutputsOnInputs(globals, {{"--out", opts->out_dir}}, {});
    slam::MapOutputStage stage(opts->out_dir);  // locked; the outputs committed as one set
    if (slam::SamePlace(ResolveSessionPath(opts->a), ResolveSessionPath(opts->b))) {
      throw InputError(opts->b + ": the same session as " + opts->a +
                       "; merging a session with itself would count its data twice");
    }
    slam::SavedSession saved_a = slam::OpenSavedSession(opts->a, config);
    slam::SavedSession saved_b = slam::OpenSavedSession(opts->b, config);
    saved_a.ground_truth = slam::SavedGroundTruth(saved_a.dir, saved_a.data, config);
    saved_b.ground_truth = slam::SavedGroundTruth(saved_b.dir, saved_b.data, config);
    slam::RefuseToReplaceSavedMap(opts->out_dir, {saved_a.dir, saved_b.dir}, false,
                                  "give another --out, or one of the merged sessions' folders");
    slam::RefuseRunsAlreadyJoined(saved_a.data, saved_a.path, saved_b.data.trajectories,
                                  saved_b.path);
    const SessionData& a = saved_a.data;
    const SessionData& b = saved_b.data;
    MergeReport report;
    SessionData merged;
    const auto merge_start = std::chrono::steady_clock::now();
    {
      slam::ProgressBar bar(!globals.quiet, "of the second session's keyframes matched");
      merged = MergeSessions(a, b, config, &report, [&bar](double f) { bar.Update(f); });
    }
    if (!report.connected) {
      throw InputError(opts->b + " cannot be merged into " + opts->a + ": " + report.reason);
    }
    const double merge_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - merge_start).count();
    nlohmann::json extra;
    extra["input"] = opts->a + " + " + opts->b;
    extra["inputs"] = {opts->a, opts->b};
    // What this command did: the join alone (no log read, one solve).
    slam::CommandWork work;
    work.processing_s = merge_s;
    work.times.optimization_s = report.optimization.solve_time_s;
    work.solves = 1;
    work.optimization = report.optimization;
    slam::AddCommandWork(work, &extra);
    extra["merge"] = slam::MergeReportJson(report);
    // Every run keeps its ground truth: the sessions' runs in order, A's then B's.
    std::vector<std::vector<OdometrySample>> per_run = saved_a.ground_truth;
    per_run.insert(per_run.end(), saved_b.ground_truth.begin(), saved_b.ground_truth.end());
    const std::map<int, std::vector<OdometrySample>> ground_truth =
        slam::GroundTruthByRun(merged, per_run);
    const std::vector<slam::ReportTable> timing = {
        {"Time to merge",
         {"step", "seconds"},
         {{"matching the second session to the first, placing it and optimising the joined "
           "graph",
           slam::Fixed(merge_s, 3)}},
         ""}};
    const slam::SessionOutputs outputs =
        slam::CommitSessionOutputs(&stage, merged, config, ground_truth, extra,
                                   "uwbsar merge: " + opts->a + " + " + opts->b, timing);
    if (globals.quiet) return;
    std::printf(
        "merged: %zu + %zu keyframes, %d loops between the runs found by the join (%d rejected "
        "by the backend), placed after %.2f m of the second\n",
        a.keyframes.size(), b.keyframes.size(), report.loop_edges, report.loop_edges_rejected,
        report.connect_path_m);
    PrintJoinedMap(outputs.summary, report, merged.landmarks.size());
    std::printf("report: %s/report.html\n", opts->out_dir.c_str());
    PrintWrittenFolder(opts->out_dir, outputs.files, globals);
  });
}

}  // namespace uwbsar::tools
