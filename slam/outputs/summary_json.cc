#include "slam/outputs/summary_json.h"

#include "slam/map_job.h"

namespace uwbsar::slam {

void AddCommandWork(const CommandWork& work, nlohmann::json* summary) {
  nlohmann::json& s = *summary;
  const FrontendStats& f = work.frontend;
  s["log_duration_s"] = work.log_duration_s;
  s["processing_s"] = work.processing_s;
  s["real_time_factor"] = work.processing_s > 0 ? work.log_duration_s / work.processing_s : 0.0;
  s["peak_memory_mib"] = PeakMemoryMiB();
  s["scans"] = {{"received", f.scans_received},
                {"imaged", f.scans_imaged},
                {"gated", f.scans_gated},
                {"rejected", f.scans_rejected()},
                {"rejected_wrong_length", f.scans_rejected_length},
                {"rejected_non_finite", f.scans_rejected_nonfinite},
                {"rejected_no_odometry", f.scans_rejected_no_odometry + f.scans_rejected_stale}};
  s["odometry"] = {{"received", f.odometry_received},
                   {"jumps_corrected", f.odometry_jumps_corrected},
                   {"rejected", f.odometry_rejected_out_of_order + f.odometry_rejected_nonfinite +
                                    f.odometry_rejected_implausible},
                   {"rejected_implausible", f.odometry_rejected_implausible}};
  const StageTimes& t = work.times;
  const auto stage = [&](double seconds) {
    return work.stages_timed ? nlohmann::json(seconds) : nlohmann::json();
  };
  s["time_s"] = {{"imaging", stage(t.imaging_s)},
                 {"features", stage(t.features_s)},
                 {"matching", stage(t.matching_s)},
                 {"optimization", stage(t.optimization_s)},
                 {"total", work.processing_s}};
  const OptimizeResult& opt = work.optimization;
  s["optimization"] = {{"solves", work.solves},
                       {"converged", opt.converged},
                       {"termination", opt.termination},
                       {"iterations", opt.iterations},
                       {"final_cost", opt.final_cost}};
}

nlohmann::json OdometryCalibrationJson(const BackendConfig& backend) {
  return {{"scale", backend.calibration_scale_mean},
          {"heading_drift_rad_per_m", backend.calibration_heading_drift_mean_rad_per_m},
          {"rotation", backend.calibration_rotation_mean}};
}

nlohmann::json MapExtentJson(const ImageGrid& grid, std::size_t blocks, std::size_t memory_bytes) {
  return {{"resolution_m", grid.resolution_m},
          {"rows", grid.rows},
          {"cols", grid.cols},
          {"blocks", blocks},
          {"memory_mib", static_cast<double>(memory_bytes) / 1048576.0}};
}

}  // namespace uwbsar::slam
