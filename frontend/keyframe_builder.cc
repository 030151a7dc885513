#include "frontend/keyframe_builder.h"

#include <algorithm>

namespace uwbsar {

ImageGrid TileGridFor(const std::vector<SensorGeometry>& sensors, double path_length_m,
                      double margin_m, double resolution_m) {
  double lo_x = 0.0, hi_x = 0.0, lo_y = 0.0, hi_y = 0.0;
  for (const SensorGeometry& s : sensors) {
    double b[4];
    s.SectorBoundsInRobot(b);
    lo_x = std::min(lo_x, b[0]);
    hi_x = std::max(hi_x, b[1]);
    lo_y = std::min(lo_y, b[2]);
    hi_y = std::max(hi_y, b[3]);
  }
  return ImageGrid::Covering(lo_x - margin_m, path_length_m + hi_x + margin_m, lo_y - margin_m,
                             hi_y + margin_m, resolution_m);
}

KeyframeBuilder::KeyframeBuilder(const KeyframeConfig& keyframe, const ImagingConfig& imaging,
                                 std::vector<SensorGeometry> sensors)
    : config_(keyframe),
      coherent_(imaging.mode == "coherent"),
      sensors_(std::move(sensors)),
      tile_grid_(TileGridFor(sensors_, keyframe.tile_length_m, keyframe.margin_m,
                             imaging.pixel_size_m)),
      projector_(std::max(1, imaging.num_threads)) {}

void KeyframeBuilder::OpenTile(const ImagedScan& scan) {
  Keyframe tile;
  tile.id = next_id_++;
  tile.stamp_ns = scan.stamp_ns;
  tile.T_world_anchor = scan.T_world_robot;
  tile.grid = tile_grid_;
  tile.image = MakeSarImage(tile_grid_, coherent_);
  tile.path_begin_m = scan.path_m;
  tile.path_end_m = scan.path_m;
  open_.push_back(std::move(tile));
}

long long KeyframeBuilder::Add(const ImagedScan& scan) {
  // Close the tiles this scan lies beyond.
  auto done = [&](const Keyframe& k) {
    return scan.path_m >= k.path_begin_m + config_.tile_length_m;
  };
  std::vector<Keyframe> still_open;
  for (Keyframe& k : open_) {
    if (done(k)) {
      k.complete = true;
      closed_.push_back(std::move(k));
    } else {
      still_open.push_back(std::move(k));
    }
  }
  open_.swap(still_open);
  // Open a new tile when the path reaches the next start; after a long gap the
  // missed starts are skipped rather than opened empty.
  if (!started_ || scan.path_m >= next_start_m_) {
    OpenTile(scan);
    const double base = started_ ? next_start_m_ : scan.path_m;
    started_ = true;
    next_start_m_ = base + config_.tile_spacing_m;
    while (next_start_m_ <= scan.path_m) next_start_m_ += config_.tile_spacing_m;
  }
  const SensorGeometry& sensor = sensors_.at(scan.sensor_id);
  long long pixels = 0;
  for (Keyframe& k : open_) {
    const Pose2 T_anchor_sensor =
        k.T_world_anchor.Inverse() * scan.T_world_robot * sensor.T_robot_sensor;
    pixels += projector_.Accumulate(*scan.profile, T_anchor_sensor, sensor, k.grid, &k.image);
    k.scans.push_back(scan);
    k.path_end_m = scan.path_m;
  }
  return pixels;
}

void KeyframeBuilder::Finish() {
  // Open tiles all end at the last scan, so a younger one holds a subset of the
  // oldest one's scans: only the oldest carries information; the others are dropped.
  if (!open_.empty()) {
    Keyframe& k = open_.front();
    k.complete = k.path_end_m - k.path_begin_m >= config_.tile_length_m * 0.999;
    closed_.push_back(std::move(k));
  }
  open_.clear();
}

std::vector<Keyframe> KeyframeBuilder::TakeClosed() {
  std::vector<Keyframe> out;
  out.swap(closed_);
  return out;
}

}  // namespace uwbsar
