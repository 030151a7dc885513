#include "slam/outputs/localize_outputs.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "backend/g2o_io.h"
#include "imaging/image_io.h"
#include "slam/map_job.h"
#include "slam/outputs/map_outputs.h"
#include "slam/outputs/results_timeline.h"
#include "slam/outputs/summary_json.h"

namespace uwbsar::slam {
namespace {

/// trajectory.tum, localize.csv and summary.json of `run` in `dir`; returns the summary.
nlohmann::json WriteLocalizeFiles(const LocalizeRun& run, const std::string& out_dir) {
  const auto trajectory = run.Trajectory(false);
  std::vector<std::pair<double, Pose2>> tum;
  // From the first fix on (docs/cli.md): before it the robot was not placed in the map, and a
  // pose back-corrected from a later fix is not one a live robot would have had.
  for (const auto& [t, p] : trajectory) {
    if (t >= run.first_fix_stamp_ns) tum.push_back({NsToSeconds(t), p});
  }
  WriteTum(out_dir + "/trajectory.tum", tum);
  std::ostringstream csv;
  csv << "keyframe_id,stamp_s,path_m,status,x_m,y_m,yaw_deg,candidates,loops,registrations,walls\n";
  csv << std::fixed;
  int tracking = 0, lost = 0, relocalised = 0, with_walls = 0, registered = 0;
  for (const LocalizedKeyframe& k : run.keyframes) {
    tracking += k.status == LocalizeStatus::kTracking;
    lost += k.status == LocalizeStatus::kLost;
    relocalised += k.status == LocalizeStatus::kRelocalised;
    with_walls += k.walls > 0;
    registered += k.registrations > 0;
    csv << k.id << "," << std::setprecision(6) << NsToSeconds(k.stamp_ns) << ","
        << std::setprecision(3) << k.path_end_m << "," << LocalizeStatusName(k.status) << ",";
    if (k.placed) {
      csv << std::setprecision(4) << k.T_map_anchor.x_m << "," << k.T_map_anchor.y_m << ","
          << std::setprecision(3) << k.T_map_anchor.yaw_rad * 180 / M_PI;
    } else {
      csv << ",,";
    }
    csv << "," << k.candidates << "," << k.loops << "," << k.registrations << "," << k.walls
        << "\n";
  }
  WriteTextAtomic(out_dir + "/localize.csv", csv.str());
  // A single map run's keys (docs/formats.md), then localisation's own.
  nlohmann::json s;
  s["input"] = run.input;
  CommandWork work;
  work.log_duration_s = run.log_duration_s;
  work.processing_s = run.processing_s;
  work.frontend = run.frontend_stats;
  work.stages_timed = false;  // imaging, features and localisation overlap, timed together
  AddCommandWork(work, &s);
  int candidates = 0, loops = 0;
  for (const LocalizedKeyframe& k : run.keyframes) candidates += k.candidates, loops += k.loops;
  s["keyframes"] = run.keyframes.size();
  s["path_length_m"] = run.odometry.empty() ? 0.0 : run.odometry.back().path_m;
  s["loops"] = {{"candidates", candidates},
                {"validated", loops},
                {"accepted", loops},
                {"rejected_by_backend", 0}};
  s["odometry_calibration"] = OdometryCalibrationJson(run.backend);
  s["map"] = nullptr;  // it localises in a map and makes none
  nlohmann::json only_run = {{"id", 0},
                             {"input", run.input},
                             {"keyframes", run.keyframes.size()},
                             {"keyframes_kept", run.keyframes.size()},
                             {"tum", "trajectory.tum"}};
  if (!run.ground_truth.empty() && run.first_fix >= 0) {
    std::vector<std::pair<TimestampNs, Pose2>> from_fix, odometry;
    for (const auto& [t, p] : trajectory)
      if (t >= run.first_fix_stamp_ns) from_fix.push_back({t, p});
    for (const OdometryEntry& e : run.odometry) odometry.push_back({e.stamp_ns, e.T_world_robot});
    s["ate"] = AteJson(TrajectoryError(from_fix, run.ground_truth));
    s["odometry_ate"] = AteJson(TrajectoryError(odometry, run.ground_truth));
    only_run["ate"] = s["ate"];
  }
  s["runs"] = nlohmann::json::array({only_run});
  s["localization"] = {{"tracking", tracking},
                       {"lost", lost},
                       {"relocalised", relocalised},
                       {"observing_walls", with_walls},
                       {"registered", registered}};
  if (run.first_fix >= 0) {
    s["first_fix"] = {{"keyframe_id", run.keyframes[run.first_fix].id},
                      {"path_m", run.first_fix_path_m},
                      {"time_s", run.first_fix_time_s}};
  } else {
    s["first_fix"] = nullptr;
  }
  // The map -> odom correction of the latest placed keyframe (what run publishes on /tf).
  s["T_map_odom"] = nullptr;
  for (auto k = run.keyframes.rbegin(); k != run.keyframes.rend(); ++k) {
    if (!k->placed) continue;
    const Pose2 T = k->T_map_anchor * k->T_odom_anchor.Inverse();
    s["T_map_odom"] = {{"keyframe_id", k->id},
                       {"x_m", T.x_m},
                       {"y_m", T.y_m},
                       {"yaw_deg", T.yaw_rad * 180 / M_PI}};
    break;
  }
  if (!run.ground_truth.empty() && run.first_fix >= 0) {
    const AteResult ate = TrajectoryError(run.Trajectory(true), run.ground_truth);
    s["ate_tracking"] = {{"poses", ate.num_poses}, {"rmse_m", ate.rmse_m}, {"max_m", ate.max_m}};
  }
  WriteTextAtomic(out_dir + "/summary.json", s.dump(2) + "\n");
  return s;
}

}  // namespace

nlohmann::json WriteLocalizeOutputs(const LocalizeRun& run, const std::string& out_dir,
                                    const SessionData* map, const Config* config,
                                    const OccupancyGrid* map_grid) {
  MapOutputStage stage(out_dir);
  nlohmann::json summary;
  stage.CommitWritten([&](const std::string& dir) {
    summary = WriteLocalizeFiles(run, dir);
    std::vector<std::string> names = {"trajectory.tum", "localize.csv"};
    if (map != nullptr && config != nullptr && map_grid != nullptr && config->slam.results_mcap) {
      WriteLocalizeResultsMcap(dir + "/" + kResultsMcapName, run, *map, *config, *map_grid);
      names.push_back(kResultsMcapName);
    }
    return names;
  });
  return summary;
}

}  // namespace uwbsar::slam
