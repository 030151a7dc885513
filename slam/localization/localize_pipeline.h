// Localisation in a saved map as a stream (`uwbsar localize`, `uwbsar run --localize-in`):
// scans and odometry go in on the feeding thread, which runs the imaging frontend; each
// closed keyframe is handed in order through a bounded FIFO to a worker thread that
// extracts its AKAZE/ORB features and localises it (slam/localization/localizer.h), as SlamSystem's
// keyframe thread does for mapping (slam.keyframe_thread, slam.keyframe_queue_size; without
// the thread the feeding thread does it). The worker takes keyframes in order and the
// frontend never reads the localiser, so the result does not depend on the threading.
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "frontend/imaging_frontend.h"
#include "frontend/keyframe_products.h"
#include "slam/localization/localize_job.h"
#include "slam/ordered_worker.h"

namespace uwbsar::slam {

class LocalizePipeline {
 public:
  /// `map` must outlive the pipeline.
  LocalizePipeline(const SessionData& map, const Config& config, std::string input);
  LocalizePipeline(const LocalizePipeline&) = delete;
  LocalizePipeline& operator=(const LocalizePipeline&) = delete;

  /// Feeding thread. Rethrow an error the worker met.
  void AddOdometry(const OdometrySample& sample);
  void AddScan(const RadarScan& scan);
  /// Feeding thread: flushes the frontend and waits until every keyframe is localised.
  void Finish();

  /// Any thread: the frontend's counters as of the last Add* call returned.
  FrontendStats frontend_stats() const;
  /// Any thread: a copy of the run so far (keyframes decided, odometry, first fix);
  /// processing_s and log_duration_s are left for the caller.
  LocalizeRun Result() const;
  /// Any thread: the latest map <- odometry correction, none before the first fix.
  std::optional<Pose2> T_map_odom() const;
  /// The products of `keyframe` (frontend/keyframe_products.h) as localisation makes them: the
  /// detected tile, and its wall profile and lines when the map has walls to observe (the same
  /// products as mapping's, slam/slam_system.h). Any thread.
  KeyframeProducts Products(const Keyframe& keyframe) const {
    return MakeKeyframeProducts(keyframe, products_);
  }

 private:
  void HandOver();
  void Localize(const Keyframe& keyframe);

  Config config_;
  // Feeding thread only.
  ImagingFrontend frontend_;
  // Worker (or feeding thread without one) only.
  Localizer localizer_;
  const KeyframeProductsConfig products_;  // after localizer_: whether the map's walls are read
  // Guarded by result_mutex_: the run so far and the frontend's counters.
  mutable std::mutex result_mutex_;
  LocalizeRun run_;
  FrontendStats frontend_stats_;
  std::optional<Pose2> T_map_odom_;
  // The keyframe thread (or inline without one), last: joined before the members above.
  OrderedWorker<Keyframe> worker_;
};

}  // namespace uwbsar::slam
