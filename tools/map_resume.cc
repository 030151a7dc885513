#include "tools/map_resume.h"

#include <cstdio>

#include "pipeline/app_config.h"
#include "pipeline/map_outputs.h"
#include "pipeline/session_capture.h"
#include "pipeline/session_outputs.h"
#include "session/session_file.h"
#include "session/session_merge.h"
#include "tools/commands.h"

namespace uwbsar::tools {

SessionData LoadSessionToResume(const std::string& dir_or_file, const Config& config) {
  return ReadSession(ResolveSessionPath(dir_or_file), &config);
}

void WriteResumedMap(const SessionData& saved, const pipeline::MapRun& run,
                     pipeline::MapOutputStage* stage, const std::string& out_dir, bool quiet) {
  const Config& config = run.slam->config();
  MergeReport report;
  const SessionData merged = MergeSessions(saved, pipeline::CaptureSession(run), config, &report);
  if (!report.connected) {
    std::fprintf(stderr,
                 "warning: the run is not connected to the saved map (%s): wrote it alone\n",
                 report.reason.c_str());
    stage->SetExtraOutputs([&run](const std::string& dir) {
      WriteSession(dir + "/" + kSessionFileName, pipeline::CaptureSession(run));
      return std::vector<std::string>{kSessionFileName};
    });
    const pipeline::MapOutputs outputs = stage->Commit(run);
    if (!quiet) PrintMapSummary(run, outputs, out_dir);
    return;
  }
  std::map<int, std::vector<OdometrySample>> ground_truth;
  if (!run.ground_truth.empty()) ground_truth[report.trajectory_offset] = run.ground_truth;
  nlohmann::json extra;
  extra["input"] = run.input;
  extra["processing_s"] = run.processing_s;
  extra["merge"] = pipeline::MergeReportJson(report);
  // Staged and committed as one set, like the plain map's outputs.
  pipeline::CommitSessionOutputs(stage, merged, config, ground_truth, extra,
                                 "uwbsar map --resume: " + run.input);
  if (quiet) return;
  std::printf("mapped %.1f s of log in %.2f s: %zu keyframes\n", run.log_duration_s(),
              run.processing_s, run.slam->keyframes().size());
  std::printf(
      "joined the saved map as run %d after %.2f m (keyframe %d): %d loops between the runs "
      "(%d rejected by the backend), %d dropped before placement\n",
      report.trajectory_offset, report.connect_path_m, report.connect_keyframe_id,
      report.loop_edges, report.loop_edges_rejected, report.dropped);
  std::printf("%zu keyframes in the map; report: %s/report.html\n", merged.keyframes.size(),
              out_dir.c_str());
}

}  // namespace uwbsar::tools
