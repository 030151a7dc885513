#include "slam/jobs/simulate_job.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "core/errors.h"
#include "core/interrupt_cleanup.h"
#include "drivers/logs/text_log.h"
#include "drivers/sim/sim_recorder.h"
#include "drivers/sim/sim_stream.h"
#include "slam/app_config_io.h"
#include "slam/outputs/output_folder.h"
#include "slam/progress.h"

namespace uwbsar::slam {

SimulateJobResult RunSimulateJob(const Config& config, const SimulateJobOptions& o) {
  const std::vector<PointTargetConfig> targets =
      o.targets_path.empty() ? std::vector<PointTargetConfig>{} : LoadPointTargets(o.targets_path);
  // Every output is checked before the work: the bag folder's parent is writable and
  // neither the bag nor an interrupted attempt (BAG.partial) is in the way.
  namespace fs = std::filesystem;
  const std::string bag_dir = fs::path(o.bag_dir).lexically_normal().string();
  const std::string partial =
      (bag_dir.back() == '/' ? bag_dir.substr(0, bag_dir.size() - 1) : bag_dir) + ".partial";
  std::error_code ec;
  if (fs::exists(bag_dir, ec)) throw InputError(bag_dir + ": exists already, not overwriting");
  if (fs::exists(partial, ec)) {
    throw InputError(partial + ": exists (an interrupted recording?); remove it first");
  }
  const std::string parent = fs::path(partial).parent_path().string();
  CheckOutputFolder(parent.empty() ? "." : parent);
  if (!o.text_log.empty()) CheckOutputFile(o.text_log);
  const auto start = std::chrono::steady_clock::now();
  const sim::SimScenario scenario =
      sim::MakeScenario(config, o.map_yaml, o.route, o.scene_seed, targets);
  sim::SimStream stream(config, scenario, o.seed);
  SimulateJobResult result;
  {
    const RemoveOnInterrupt guard(partial);  // Ctrl-C leaves no BAG.partial behind
    try {
      char what[64];
      std::snprintf(what, sizeof(what), "of %.0f s of route", stream.duration_s());
      ProgressBar bar(o.progress, what);
      const TimestampNs start_ns = stream.start_ns();
      const TimestampNs end_ns = start_ns + SecondsToNs(stream.duration_s());
      result.summary =
          sim::WriteSimBag(&stream, config, o.bag_dir, o.storage, o.bag_dir + "/ground_truth.tum",
                           [&](TimestampNs t) { bar.UpdateStamp(t, start_ns, end_ns); });
    } catch (...) {
      // A failed simulation (disk full) leaves nothing that blocks a retry (neither existed
      // before: checked above).
      fs::remove_all(partial, ec);
      fs::remove_all(bag_dir, ec);
      throw;
    }
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!o.text_log.empty()) {
    sim::SimStream again(config, scenario, o.seed);  // same seed: the same messages
    WriteTextLog(o.text_log, sim::ToTextLog(sim::RecordStream(&again)));
  }
  result.scene_change.edits = scenario.scene_edits;
  result.people = static_cast<int>(stream.people().size());
  result.route_name = scenario.route.name;
  result.route_length_m = scenario.trajectory.length_m();
  result.route_duration_s = scenario.trajectory.duration_s();
  return result;
}

}  // namespace uwbsar::slam
