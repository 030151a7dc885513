// `uwbsar map BAG --resume SESSION`: the new run mapped as usual, then joined to the saved
// session as a new trajectory (slam/session/session_merge.h) and the joined map written
// (slam/outputs/session_outputs.h). A run that never connects is refused and nothing is written:
// the saved map is never replaced by a run that is not part of it.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "slam/app_config.h"
#include "slam/jobs/saved_session.h"
#include "slam/map_job.h"
#include "slam/outputs/map_outputs.h"
#include "slam/session/session_data.h"
#include "slam/session/session_merge.h"
#include "tools/commands.h"

namespace uwbsar::tools {

/// Reads the saved session for `config` under a shared lock on its folder, held while the
/// result lives (InputError, exit 3, when it cannot be resumed: incompatible, or it already
/// holds the recording `bag` of identity `fingerprint`).
slam::SavedSession OpenSessionToResume(const std::string& dir_or_file, const std::string& bag,
                                       const std::string& fingerprint, const Config& config);

/// The joined map's keyframes and loops as its summary.json counts them (and report.html shows
/// them), after a join that found report.loop_edges loops between the runs.
void PrintJoinedMap(const nlohmann::json& summary, const MergeReport& report,
                    std::size_t landmarks);

/// Joins `run` to `saved` and writes the outputs into out_dir; prints a summary unless quiet.
/// Throws InputError naming the bag and the session, writing nothing, when the run does not
/// connect to the saved map.
void WriteResumedMap(const slam::SavedSession& saved, const slam::MapRun& run,
                     slam::MapOutputStage* stage, const std::string& out_dir,
                     const GlobalOptions& globals);

}  // namespace uwbsar::tools
