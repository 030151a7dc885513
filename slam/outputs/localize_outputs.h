// The outputs of `uwbsar localize` and `run --localize-in` (slam/localization/localize_job.h):
// trajectory.tum in the map frame (from the first fix on), localize.csv (status per keyframe),
// summary.json (with the latest map -> odom correction) and, when asked, results.mcap.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "imaging/occupancy_grid.h"
#include "slam/app_config.h"
#include "slam/localization/localize_job.h"
#include "slam/session/session_data.h"

namespace uwbsar::slam {

/// trajectory.tum, localize.csv and summary.json (last) into out_dir, staged and committed as
/// one set under out_dir's lock (slam/outputs/map_outputs.h MapOutputStage), replacing an earlier
/// run's outputs; returns the summary. With the saved `map`, its navigation grid `map_grid`
/// (slam/outputs/navigation_map.h SavedNavigationGrid) and a `config` asking for it
/// (slam.results_mcap), also results.mcap (slam/outputs/results_timeline.h). The commands refuse a
/// map's folder first (slam/jobs/saved_session.h RefuseMapFolderForLocalize).
nlohmann::json WriteLocalizeOutputs(const LocalizeRun& run, const std::string& out_dir,
                                    const SessionData* map = nullptr,
                                    const Config* config = nullptr,
                                    const OccupancyGrid* map_grid = nullptr);

}  // namespace uwbsar::slam
