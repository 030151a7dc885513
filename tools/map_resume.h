// `uwbsar map BAG --resume SESSION`: the new run mapped as usual, then joined to the saved
// session as a new trajectory (session/session_merge.h) and the joined map written
// (tools/session_outputs.h). A run that never connects is written alone, with a warning.
#pragma once

#include <string>
#include <vector>

#include "drivers/rosbag/bag_storage.h"
#include "pipeline/app_config.h"
#include "pipeline/map_job.h"
#include "pipeline/map_outputs.h"
#include "session/session_data.h"

namespace uwbsar::tools {

/// Reads the saved session for `config` (InputError, exit 3, when it cannot be resumed).
SessionData LoadSessionToResume(const std::string& dir_or_file, const Config& config);

/// Joins `run` to `saved` and writes the outputs into out_dir; prints a summary unless quiet.
void WriteResumedMap(const SessionData& saved, const pipeline::MapRun& run,
                     pipeline::MapOutputStage* stage, const std::string& out_dir, bool quiet);

}  // namespace uwbsar::tools
