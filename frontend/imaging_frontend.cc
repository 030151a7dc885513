#include "frontend/imaging_frontend.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace uwbsar {

ImagingFrontend::ImagingFrontend(const ImagingFrontendConfig& config)
    : config_(config), odometry_(config.gating) {
  const bool coherent = config.imaging.coherent();
  for (const RadarConfig& radar : config.radars) {
    sensors_.push_back(SensorGeometry::FromConfig(radar, config.pulse));
    // imaging.method ffbp forms paper-mode images from the analytic signal at baseband.
    compressors_.push_back(std::make_unique<RangeCompressor>(
        config.pulse, sensors_.back(), coherent, config.imaging.coherent_oversampling,
        config.imaging.method == ImagingMethod::kFfbp));
  }
  have_last_.assign(sensors_.size(), false);
  last_imaged_pose_.resize(sensors_.size());
  // Per-radar tiles only where there are radars to tell apart (place_recognition.per_radar).
  const bool per_radar = config.per_radar_tiles && sensors_.size() >= 2;
  builder_ = std::make_unique<KeyframeBuilder>(config.keyframe, config.imaging, config.pulse,
                                               sensors_, per_radar);
}

ImagingFrontend::~ImagingFrontend() = default;

void ImagingFrontend::AddOdometry(const OdometrySample& sample) {
  ++stats_.odometry_received;
  const OdometryBuffer::AddReport report = odometry_.Add(sample);
  if (report.outlier_dropped) CountImplausible();
  switch (report.result) {
    case OdometryBuffer::AddResult::kAccepted:
    case OdometryBuffer::AddResult::kHeld:
      break;
    case OdometryBuffer::AddResult::kOutOfOrder:
      ++stats_.odometry_rejected_out_of_order;
      log_once_.Warn("odom_order", "odometry sample out of time order dropped");
      return;
    case OdometryBuffer::AddResult::kNonFinite:
      ++stats_.odometry_rejected_nonfinite;
      log_once_.Warn("odom_nan",
                     "odometry sample with a NaN/Inf pose or a coordinate beyond 1e9 m dropped");
      return;
  }
  if (report.jumps > 0) {
    stats_.odometry_jumps_corrected += report.jumps;
    log_once_.Warn("odom_jump",
                   "odometry jumped (a step longer than gating.max_odom_jump_m, or "
                   "faster than gating.max_odom_speed_mps / max_odom_turn_rate_radps "
                   "and confirmed by the next sample) at t=" +
                       std::to_string(NsToSeconds(sample.stamp_ns)) + " s; treated as no motion");
  }
  if (report.appended == 0) return;
  const auto& entries = odometry_.entries();
  if (odometry_observer_) {
    for (std::size_t i = entries.size() - static_cast<std::size_t>(report.appended);
         i < entries.size(); ++i) {
      odometry_observer_(entries[i]);
    }
  }
  ProcessPending(false);
}

void ImagingFrontend::CountImplausible() {
  ++stats_.odometry_rejected_implausible;
  log_once_.Warn("odom_implausible",
                 "odometry sample implying a speed above gating.max_odom_speed_mps or a turn "
                 "rate above gating.max_odom_turn_rate_radps, not confirmed by the next "
                 "sample, dropped as an outlier");
}

void ImagingFrontend::AddScan(const RadarScan& scan) {
  ++stats_.scans_received;
  if (scan.sensor_id < 0 || scan.sensor_id >= static_cast<int>(sensors_.size())) {
    ++stats_.scans_rejected_unknown_sensor;
    log_once_.Warn("scan_sensor", "scan from unknown sensor id " + std::to_string(scan.sensor_id));
    return;
  }
  const std::string& name = config_.radars[scan.sensor_id].name;
  if (scan.samples.empty()) {
    ++stats_.scans_rejected_empty;
    log_once_.Warn("scan_empty/" + name, "empty scan from radar '" + name + "' rejected");
    return;
  }
  const int expected = config_.radars[scan.sensor_id].num_samples;
  if (static_cast<int>(scan.samples.size()) != expected) {
    ++stats_.scans_rejected_length;
    log_once_.Warn("scan_length/" + name, "scan from radar '" + name + "' has " +
                                              std::to_string(scan.samples.size()) +
                                              " samples, radars[].num_samples says " +
                                              std::to_string(expected) + "; rejected");
    return;
  }
  const auto bad = std::find_if(scan.samples.begin(), scan.samples.end(),
                                [](float v) { return !(std::abs(v) <= kMaxScanSample); });
  if (bad != scan.samples.end()) {
    ++stats_.scans_rejected_nonfinite;
    std::ostringstream what;
    what << "radar '" << name << "' (topic " << config_.radars[scan.sensor_id].topic
         << ") at t=" << std::fixed << std::setprecision(6) << NsToSeconds(scan.stamp_ns)
         << " s: sample " << (bad - scan.samples.begin()) << " is " << std::defaultfloat << *bad;
    if (stats_.first_bad_samples.empty()) stats_.first_bad_samples = what.str();
    log_once_.Warn("scan_nan/" + name,
                   "scan with a NaN/Inf sample or one beyond 1e12 rejected: " + what.str());
    return;
  }
  if (std::all_of(scan.samples.begin(), scan.samples.end(), [](float v) { return v == 0.0f; })) {
    ++stats_.scans_zero;
  }
  auto pos = std::upper_bound(pending_.begin(), pending_.end(), scan.stamp_ns,
                              [](TimestampNs t, const RadarScan& s) { return t < s.stamp_ns; });
  pending_.insert(pos, scan);
  ProcessPending(false);
}

void ImagingFrontend::ProcessPending(bool final) {
  std::size_t done = 0;
  const TimestampNs newest_scan = pending_.empty() ? 0 : pending_.back().stamp_ns;
  for (; done < pending_.size(); ++done) {
    RadarScan& scan = pending_[done];
    OdometryEntry odom;
    const auto result = odometry_.Lookup(scan.stamp_ns, &odom);
    // No odometry yet counts as "after the last": in a live run the first odometry sample
    // may arrive after scans stamped later than it (another topic, discovered later).
    const bool no_odometry_yet =
        result == OdometryBuffer::LookupResult::kBeforeFirst && odometry_.empty();
    if (result == OdometryBuffer::LookupResult::kAfterLast || no_odometry_yet) {
      // Wait for odometry, unless it has stalled for too long.
      const bool stale =
          NsToSeconds(newest_scan - scan.stamp_ns) > config_.gating.max_scan_latency_s;
      if (!final && !stale) break;
      ++stats_.scans_rejected_stale;
      log_once_.Warn("scan_stale", "scans arrived with no odometry to cover them; dropped");
      continue;
    }
    if (result != OdometryBuffer::LookupResult::kOk) {
      ++stats_.scans_rejected_no_odometry;
      log_once_.Warn("scan_no_odom",
                     "scans before the first odometry sample or in an odometry "
                     "gap longer than gating.max_odom_gap_s; dropped");
      continue;
    }
    ImageScan(std::move(scan), odom);
  }
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(done));
  if (!pending_.empty())
    odometry_.TrimBefore(pending_.front().stamp_ns);
  else
    odometry_.TrimBefore(odometry_.latest_stamp_ns());
}

void ImagingFrontend::ImageScan(RadarScan&& scan, const OdometryEntry& odom) {
  const int id = scan.sensor_id;
  // Gating (paper: a scan is used once the robot moved >= 3 mm since the last one used).
  if (have_last_[id] &&
      Distance(last_imaged_pose_[id], odom.T_world_robot) < config_.gating.min_travel_m) {
    ++stats_.scans_gated;
    return;
  }
  have_last_[id] = true;
  last_imaged_pose_[id] = odom.T_world_robot;
  ImagedScan imaged;
  imaged.stamp_ns = scan.stamp_ns;
  imaged.sensor_id = id;
  imaged.T_world_robot = odom.T_world_robot;
  imaged.path_m = odom.path_m;
  imaged.profile = compressors_[id]->Compress(scan.samples);
  stats_.pixel_updates += builder_->Add(imaged);
  ++stats_.scans_imaged;
  if (observer_) observer_(imaged);
}

void ImagingFrontend::Finish() {
  if (odometry_.DropHeld()) CountImplausible();
  ProcessPending(true);
  builder_->Finish();
}

std::vector<Keyframe> ImagingFrontend::TakeKeyframes() {
  std::vector<Keyframe> out = builder_->TakeClosed();
  stats_.keyframes += static_cast<long long>(out.size());
  return out;
}

}  // namespace uwbsar
