// The imaging frontend: validates raw scans, interpolates the odometry pose at
// each scan's timestamp, gates scans by travel (paper: >= 3 mm), range-compresses
// them and back-projects them into overlapping keyframe tiles.
// Bad input never crashes it and never reaches a tile: each rejection is
// counted in FrontendStats and logged once per kind.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/log.h"
#include "core/radar_config.h"
#include "frontend/gating_config.h"
#include "frontend/keyframe.h"
#include "frontend/keyframe_builder.h"
#include "frontend/keyframe_config.h"
#include "frontend/odometry_buffer.h"
#include "imaging/imaging_config.h"
#include "imaging/pulse_config.h"

namespace uwbsar {

/// The largest sample magnitude a scan may hold: beyond any digitiser's range (the LT102's
/// int32 counts reach 2.1e9), and small enough that range compression and back-projection in
/// float cannot overflow to inf (3e38 samples did, and ended in an assertion).
constexpr float kMaxScanSample = 1e12f;

struct FrontendStats {
  long long scans_received = 0;
  long long scans_imaged = 0;
  long long scans_gated = 0;  ///< dropped because the robot had not moved min_travel_m
  long long scans_rejected_unknown_sensor = 0;
  long long scans_rejected_empty = 0;
  long long scans_rejected_length = 0;     ///< length differs from radars[i].num_samples
  long long scans_rejected_nonfinite = 0;  ///< NaN/Inf samples, or beyond kMaxScanSample
  long long scans_zero = 0;  ///< accepted scans whose samples are all 0 (a silent radar)
  long long scans_rejected_no_odometry = 0;  ///< before the first odometry or in a gap
  long long scans_rejected_stale = 0;        ///< waited longer than max_scan_latency_s for odometry
  long long odometry_received = 0;
  long long odometry_jumps_corrected = 0;
  long long odometry_rejected_out_of_order = 0;
  long long odometry_rejected_nonfinite = 0;    ///< NaN/Inf, or beyond kMaxOdomCoordinateM
  long long odometry_rejected_implausible = 0;  ///< impossible speed/turn rate, not confirmed
  long long pixel_updates = 0;
  long long keyframes = 0;
  /// The first scan rejected for its samples (non-finite or beyond kMaxScanSample): radar,
  /// topic, stamp and the sample, for the message that refuses a run with nothing imaged.
  std::string first_bad_samples;

  long long scans_rejected() const {
    return scans_rejected_unknown_sensor + scans_rejected_empty + scans_rejected_length +
           scans_rejected_nonfinite + scans_rejected_no_odometry + scans_rejected_stale;
  }
  /// Scans whose samples passed validation (a known radar, the right length, finite).
  long long scans_valid() const {
    return scans_received - scans_rejected_unknown_sensor - scans_rejected_empty -
           scans_rejected_length - scans_rejected_nonfinite;
  }
  /// Every valid scan was all zero: radars powered but silent (nothing to image).
  bool all_valid_scans_zero() const { return scans_valid() > 0 && scans_zero == scans_valid(); }
  /// "; non-finite or overflowing samples, first: <first_bad_samples>", or "" without one: the
  /// end of a message refusing a run with nothing imaged.
  std::string BadSamplesNote() const {
    return first_bad_samples.empty()
               ? std::string()
               : "; non-finite or overflowing samples, first: " + first_bad_samples;
  }
};

/// The sections the imaging frontend reads: the pulse and radars (range compression, sensor
/// geometry), imaging (pixel size, mode), gating and keyframe tiling. Nothing else of the
/// configuration reaches it.
struct ImagingFrontendConfig {
  PulseConfig pulse;
  std::vector<RadarConfig> radars = DefaultRadars();
  ImagingConfig imaging;
  GatingConfig gating;
  KeyframeConfig keyframe;
  /// Keep each radar's part of the tile (place_recognition.per_radar.enabled).
  bool per_radar_tiles = false;

  ImagingFrontendConfig() = default;
  /// Its sections of any configuration holding them (implicit: callers hand the configuration
  /// they hold, the frontend keeps its part).
  template <class Config>
  ImagingFrontendConfig(const Config& config)  // NOLINT(google-explicit-constructor)
      : pulse(config.pulse),
        radars(config.radars),
        imaging(config.imaging),
        gating(config.gating),
        keyframe(config.keyframe),
        per_radar_tiles(config.place_recognition.per_radar.enabled) {}
};

class ImagingFrontend {
 public:
  explicit ImagingFrontend(const ImagingFrontendConfig& config);
  ~ImagingFrontend();

  void AddOdometry(const OdometrySample& sample);
  /// Queues the scan until odometry covers its timestamp, then images it.
  void AddScan(const RadarScan& scan);
  /// Images what can still be imaged and closes the open tiles.
  void Finish();

  /// Keyframes closed since the last call, oldest first.
  std::vector<Keyframe> TakeKeyframes();
  /// Called for every scan that passed gating (e.g. to render a whole-run strip).
  void SetScanObserver(std::function<void(const ImagedScan&)> observer) {
    observer_ = std::move(observer);
  }
  /// Called for every odometry sample accepted, as the frontend uses it (jumps corrected).
  void SetOdometryObserver(std::function<void(const OdometryEntry&)> observer) {
    odometry_observer_ = std::move(observer);
  }

  const FrontendStats& stats() const { return stats_; }
  const std::vector<SensorGeometry>& sensors() const { return sensors_; }
  const KeyframeBuilder& builder() const { return *builder_; }

 private:
  void ProcessPending(bool final);
  void ImageScan(RadarScan&& scan, const OdometryEntry& odom);
  void CountImplausible();

  ImagingFrontendConfig config_;
  std::vector<SensorGeometry> sensors_;
  std::vector<std::unique_ptr<RangeCompressor>> compressors_;
  std::vector<bool> have_last_;
  std::vector<Pose2> last_imaged_pose_;
  OdometryBuffer odometry_;
  std::unique_ptr<KeyframeBuilder> builder_;
  std::vector<RadarScan> pending_;  ///< sorted by stamp
  std::function<void(const ImagedScan&)> observer_;
  std::function<void(const OdometryEntry&)> odometry_observer_;
  FrontendStats stats_;
  LogOnce log_once_;
};

}  // namespace uwbsar
