// `uwbsar merge SESSION_A SESSION_B --out DIR`: two sessions of the same building joined by
// loops found between them (slam/session/session_merge.h), written as one map.
#include <chrono>
#include <cstdio>

#include "core/errors.h"
#include "slam/app_config.h"
#include "slam/map_report.h"
#include "slam/progress.h"
#include "slam/saved_session.h"
#include "slam/session/session_file.h"
#include "slam/session/session_merge.h"
#include "slam/session_outputs.h"
#include "tools/commands.h"

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
    const slam::SavedSession saved_a = slam::OpenSavedSession(opts->a, config);
    const slam::SavedSession saved_b = slam::OpenSavedSession(opts->b, config);
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
    extra["merge"] = slam::MergeReportJson(report);
    const std::vector<slam::ReportTable> timing = {
        {"Time to merge",
         {"step", "seconds"},
         {{"matching the second session to the first, placing it and optimising the joined "
           "graph",
           slam::Fixed(merge_s, 3)}},
         ""}};
    const slam::SessionOutputs outputs = slam::CommitSessionOutputs(
        &stage, merged, config, {}, extra, "uwbsar merge: " + opts->a + " + " + opts->b, timing);
    if (globals.quiet) return;
    std::printf(
        "merged: %zu + %zu keyframes, %d loops between the sessions (%d rejected by the "
        "backend), placed after %.2f m of the second; %zu keyframes in the map (%d older views "
        "retired), %zu wall landmarks (%d seen again)\n",
        a.keyframes.size(), b.keyframes.size(), report.loop_edges, report.loop_edges_rejected,
        report.connect_path_m, merged.keyframes.size(), report.retired, merged.landmarks.size(),
        report.walls_reused);
    std::printf("report: %s/report.html\n", opts->out_dir.c_str());
    PrintWrittenFolder(opts->out_dir, outputs.files, globals);
  });
}

}  // namespace uwbsar::tools
