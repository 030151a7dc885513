#include "slam/jobs/calibrate_job.h"

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <vector>

#include "core/config_io.h"
#include "core/errors.h"
#include "drivers/rosbag/robot_bag.h"
#include "imaging/image_io.h"
#include "slam/map_job.h"
#include "slam/outputs/output_folder.h"

namespace uwbsar::slam {
namespace {

/// Keeps the odometry and the ground truth of a bag.
class OdometryAndTruth : public rosbag::RobotBagVisitor {
 public:
  void OnOdometry(const OdometrySample& o) override { odometry.push_back(o); }
  void OnGroundTruth(const OdometrySample& p) override { ground_truth.push_back(p); }
  std::vector<OdometrySample> odometry, ground_truth;
};

/// A Visit() visitor that writes through config_yaml::Writer only the fields at the addresses
/// `fields` and the sections (structs with a Visit) that hold one, under the keys the Visit()
/// functions give them; everything else is skipped.
class SelectedFieldsWriter {
 public:
  SelectedFieldsWriter(YAML::Emitter& out, std::vector<const void*> fields)
      : out_(out), writer_(out), fields_(std::move(fields)) {}

  template <class T>
  void operator()(const char* key, T& value) {
    if constexpr (config_yaml::HasVisit<T>::value) {
      if (!Holds(value)) return;
      out_ << YAML::Key << key << YAML::Value << YAML::BeginMap;
      value.Visit(*this);
      out_ << YAML::EndMap;
    } else if (std::find(fields_.begin(), fields_.end(), static_cast<const void*>(&value)) !=
               fields_.end()) {
      writer_(key, value);
    }
  }

 private:
  /// A selected field lies inside `value`.
  template <class T>
  bool Holds(const T& value) const {
    const auto begin = reinterpret_cast<std::uintptr_t>(&value);
    return std::any_of(fields_.begin(), fields_.end(), [begin](const void* field) {
      const auto at = reinterpret_cast<std::uintptr_t>(field);
      return at >= begin && at < begin + sizeof(T);
    });
  }

  YAML::Emitter& out_;
  config_yaml::Writer writer_;
  std::vector<const void*> fields_;
};

}  // namespace

std::string CalibrationYaml(const CalibrationFit& fit) {
  Config config;
  BackendConfig& b = config.backend;
  constexpr int kDigits = 6;  // a measured figure: more digits would be noise
  b.odometry_model = fit.model;
  b.calibration_scale_mean = RoundToDigits(fit.calibration[kCalibScale], kDigits);
  b.calibration_rotation_mean = RoundToDigits(fit.calibration[kCalibRotation], kDigits);
  std::vector<const void*> fields = {&b.odometry_model, &b.calibration_scale_mean,
                                     &b.calibration_rotation_mean};
  // A gyro's heading error is the run's bias: nothing per metre belongs to the robot.
  if (fit.model == OdometryModel::kWheel) {
    b.calibration_heading_drift_mean_rad_per_m =
        RoundToDigits(fit.calibration[kCalibHeadingDrift], kDigits);
    fields.push_back(&b.calibration_heading_drift_mean_rad_per_m);
  }
  if (fit.observed[kCalibScale]) {
    b.calibration_scale_sigma =
        RoundToDigits(std::max(0.001, 3.0 * fit.sigma[kCalibScale]), kDigits);
    fields.push_back(&b.calibration_scale_sigma);
  }
  YAML::Emitter out;
  SelectedFieldsWriter writer(out, std::move(fields));
  out << YAML::BeginMap;
  config.Visit(writer);
  out << YAML::EndMap;
  std::ostringstream y;
  y.precision(kDigits);
  y << "# uwbsar calibrate: " << fit.segments << " segments, " << fit.path_m << " m, "
    << EnumName(fit.model) << " base\n"
    << out.c_str() << "\n";
  return y.str();
}

CalibrateJobResult RunCalibrateJob(const Config& config, const CalibrateJobOptions& options) {
  if (!options.out_yaml.empty()) CheckOutputFile(options.out_yaml);  // before the work
  OdometryAndTruth streams;
  rosbag::ReadRobotBag(options.bag, rosbag::RobotBagOptionsFromConfig(config), streams);
  CalibrationFitOptions fit_options;
  if (!options.ground_truth_tum.empty()) {
    streams.ground_truth = ReadGroundTruthFile(
        options.ground_truth_tum, config.limits.max_input_file_mb, &fit_options.truth_lines);
  }
  if (streams.ground_truth.empty()) {
    throw InputError(options.bag + ": no ground truth (topic " + config.slam.ground_truth_topic +
                     "); give one with --ground-truth");
  }
  fit_options.segment_m = options.segment_m;
  fit_options.model = options.base;
  fit_options.max_step_m = config.gating.max_odom_jump_m;
  fit_options.max_speed_mps = config.gating.max_odom_speed_mps;
  fit_options.max_turn_rate_radps = config.gating.max_odom_turn_rate_radps;
  fit_options.odometry_source = options.bag;
  fit_options.truth_source = options.ground_truth_tum.empty()
                                 ? options.bag + " (" + config.slam.ground_truth_topic + ")"
                                 : options.ground_truth_tum;
  CalibrateJobResult result;
  result.fit =
      FitOdometryCalibration(streams.odometry, streams.ground_truth, config.backend, fit_options);
  result.yaml = CalibrationYaml(result.fit);
  if (!options.out_yaml.empty()) WriteTextAtomic(options.out_yaml, result.yaml);
  return result;
}

}  // namespace uwbsar::slam
