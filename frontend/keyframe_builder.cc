#include "frontend/keyframe_builder.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include "imaging/sector_spans.h"

namespace uwbsar {

KeyframeBuilder::KeyframeBuilder(const KeyframeConfig& keyframe, const ImagingConfig& imaging,
                                 const PulseConfig& pulse, std::vector<SensorGeometry> sensors,
                                 bool keep_sensor_images)
    : config_(keyframe),
      resolution_m_(imaging.pixel_size_m),
      coherent_(imaging.coherent()),
      keep_sensor_images_(keep_sensor_images),
      segments_per_tile_(std::max(
          1, static_cast<int>(std::lround(keyframe.tile_length_m / keyframe.tile_spacing_m)))),
      sensors_(std::move(sensors)),
      canvas_(SegmentCanvasFor(keyframe, sensors_)),
      projector_(std::max(1, imaging.num_threads)) {
  if (imaging.method == ImagingMethod::kFfbp) {
    const PolarSampling sampling = PolarSamplingFor(imaging.ffbp, pulse, coherent_);
    for (std::size_t i = 0; i < sensors_.size(); ++i) {
      subapertures_.emplace_back(imaging.ffbp, sampling, std::max(1, imaging.num_threads));
    }
  }
}

void KeyframeBuilder::DropOldestSegment() {
  for (Layer& layer : segments_.front().layers) {
    if (layer.image.empty()) continue;
    if (!layer.touched.empty()) layer.image(layer.touched).setTo(0);
    spare_canvases_.push_back(layer.image);
  }
  segments_.pop_front();
}

cv::Mat KeyframeBuilder::TakeCanvas(const ImageGrid& grid) {
  while (!spare_canvases_.empty()) {
    cv::Mat canvas = spare_canvases_.back();
    spare_canvases_.pop_back();
    if (canvas.rows == grid.rows && canvas.cols == grid.cols) return canvas;
  }
  return MakeSarImage(grid, coherent_);
}

KeyframeBuilder::Layer& KeyframeBuilder::LayerOf(Segment& segment, int sensor_id) {
  return segment.layers.at(keep_sensor_images_ ? static_cast<std::size_t>(sensor_id) : 0);
}

long long KeyframeBuilder::FlushSubapertures() {
  long long pixels = 0;
  if (segments_.empty()) return pixels;
  Segment& seg = segments_.back();
  for (std::size_t sensor = 0; sensor < subapertures_.size(); ++sensor) {
    // Even with no scans pending: a top sub-aperture written by the last Add is reported here.
    Layer& layer = LayerOf(seg, static_cast<int>(sensor));
    cv::Rect touched;
    pixels += subapertures_[sensor].Flush(seg.grid, &layer.image, &touched);
    UniteBounds(&layer.touched, touched);
    UniteBounds(&seg.touched, touched);
  }
  return pixels;
}

void KeyframeBuilder::OpenSegment(const ImagedScan& scan) {
  Segment seg;
  const long long half = canvas_.HalfPixels(resolution_m_);
  const long long cx = std::llround(scan.T_world_robot.x_m / resolution_m_);
  const long long cy = std::llround(scan.T_world_robot.y_m / resolution_m_);
  seg.lattice_col0 = cx - half;
  seg.lattice_row0 = -(cy + half);  // lattice row r has y = -r * resolution
  seg.grid.resolution_m = resolution_m_;
  seg.grid.cols = static_cast<int>(2 * half + 1);
  seg.grid.rows = static_cast<int>(2 * half + 1);
  seg.grid.x0_m = static_cast<double>(seg.lattice_col0) * resolution_m_;
  seg.grid.y0_m = -static_cast<double>(seg.lattice_row0) * resolution_m_;
  seg.layers.resize(keep_sensor_images_ ? sensors_.size() : 1);
  seg.path_begin_m = seg.path_end_m = scan.path_m;
  segments_.push_back(std::move(seg));
  ++segments_opened_;
}

Keyframe KeyframeBuilder::MakeTile(std::size_t first, std::size_t count, bool complete) {
  // Union of the observed pixels, in global lattice indices.
  long long c_lo = LLONG_MAX, c_hi = LLONG_MIN, r_lo = LLONG_MAX, r_hi = LLONG_MIN;
  for (std::size_t i = first; i < first + count; ++i) {
    const Segment& s = segments_[i];
    if (s.touched.empty()) continue;
    c_lo = std::min(c_lo, s.lattice_col0 + s.touched.x);
    c_hi = std::max(c_hi, s.lattice_col0 + s.touched.x + s.touched.width);
    r_lo = std::min(r_lo, s.lattice_row0 + s.touched.y);
    r_hi = std::max(r_hi, s.lattice_row0 + s.touched.y + s.touched.height);
  }
  const Segment& head = segments_[first];
  // The anchor: the lattice point nearest the robot at the middle of the tile's path,
  // with world orientation. At the middle of the aperture, an odometry scale error
  // stretches the tile symmetrically about the anchor, so tile-to-tile transforms
  // (loops) are not biased by it.
  const double mid_path_m = 0.5 * (head.path_begin_m + segments_[first + count - 1].path_end_m);
  const ImagedScan* mid = &head.scans.front();
  for (std::size_t i = first; i < first + count; ++i) {
    for (const ImagedScan& s : segments_[i].scans) {
      if (std::abs(s.path_m - mid_path_m) < std::abs(mid->path_m - mid_path_m)) mid = &s;
    }
  }
  Keyframe tile;
  tile.id = next_id_++;
  tile.stamp_ns = mid->stamp_ns;
  tile.T_world_robot = mid->T_world_robot;
  const long long ax = std::llround(mid->T_world_robot.x_m / resolution_m_);
  const long long ay = std::llround(mid->T_world_robot.y_m / resolution_m_);
  tile.T_world_anchor = {static_cast<double>(ax) * resolution_m_,
                         static_cast<double>(ay) * resolution_m_, 0.0};
  tile.complete = complete;
  tile.path_begin_m = head.path_begin_m;
  tile.path_end_m = segments_[first + count - 1].path_end_m;
  if (c_lo > c_hi) {  // nothing observed
    c_lo = c_hi = ax;
    r_lo = r_hi = -ay;
  }
  tile.grid.resolution_m = resolution_m_;
  tile.grid.cols = static_cast<int>(std::max(1LL, c_hi - c_lo));
  tile.grid.rows = static_cast<int>(std::max(1LL, r_hi - r_lo));
  tile.grid.x0_m = static_cast<double>(c_lo - ax) * resolution_m_;
  tile.grid.y0_m = static_cast<double>(-r_lo - ay) * resolution_m_;
  tile.image = MakeSarImage(tile.grid, coherent_);
  for (std::size_t i = first; i < first + count; ++i) {
    const Segment& s = segments_[i];
    tile.scans.insert(tile.scans.end(), s.scans.begin(), s.scans.end());
    for (const Layer& layer : s.layers) {
      if (layer.touched.empty()) continue;
      cv::Mat roi = tile.image(LayerRectInTile(s, layer, c_lo, r_lo));
      roi += layer.image(layer.touched);
    }
  }
  if (keep_sensor_images_) AddSensorTiles(first, count, c_lo, r_lo, &tile);
  return tile;
}

cv::Rect KeyframeBuilder::LayerRectInTile(const Segment& s, const Layer& layer, long long c_lo,
                                          long long r_lo) {
  return cv::Rect(static_cast<int>(s.lattice_col0 + layer.touched.x - c_lo),
                  static_cast<int>(s.lattice_row0 + layer.touched.y - r_lo), layer.touched.width,
                  layer.touched.height);
}

void KeyframeBuilder::AddSensorTiles(std::size_t first, std::size_t count, long long c_lo,
                                     long long r_lo, Keyframe* tile) const {
  const cv::Rect whole(0, 0, tile->grid.cols, tile->grid.rows);
  for (std::size_t sensor = 0; sensor < sensors_.size(); ++sensor) {
    cv::Rect box;  // the sensor's pixels, in tile pixels
    for (std::size_t i = first; i < first + count; ++i) {
      const Segment& s = segments_[i];
      if (sensor >= s.layers.size() || s.layers[sensor].touched.empty()) continue;
      const cv::Rect r = LayerRectInTile(s, s.layers[sensor], c_lo, r_lo) & whole;
      box = box.empty() ? r : (r.empty() ? box : box | r);
    }
    if (box.empty()) continue;
    SensorTile st;
    st.sensor_id = static_cast<int>(sensor);
    st.grid = tile->grid;
    st.grid.cols = box.width;
    st.grid.rows = box.height;
    st.grid.x0_m = tile->grid.ColToX(box.x);
    st.grid.y0_m = tile->grid.RowToY(box.y);
    st.image = MakeSarImage(st.grid, coherent_);
    for (std::size_t i = first; i < first + count; ++i) {
      const Segment& s = segments_[i];
      if (sensor >= s.layers.size() || s.layers[sensor].touched.empty()) continue;
      const cv::Rect r = LayerRectInTile(s, s.layers[sensor], c_lo, r_lo);
      cv::Mat roi = st.image(r - box.tl());
      roi += s.layers[sensor].image(s.layers[sensor].touched);
    }
    tile->sensor_tiles.push_back(std::move(st));
  }
}

long long KeyframeBuilder::Add(const ImagedScan& scan) {
  long long flushed = 0;
  if (segments_.empty() || scan.path_m >= segments_.back().path_begin_m + config_.tile_spacing_m) {
    // The newest segment is full. When the window holds a whole tile's worth, that
    // tile is complete; then the oldest segment is no longer needed.
    flushed = FlushSubapertures();
    if (static_cast<int>(segments_.size()) == segments_per_tile_) {
      closed_.push_back(MakeTile(0, segments_.size(), /*complete=*/true));
      DropOldestSegment();
    }
    OpenSegment(scan);
  }
  Segment& seg = segments_.back();
  const SensorGeometry& sensor = sensors_.at(scan.sensor_id);
  Layer& layer = LayerOf(seg, scan.sensor_id);
  if (layer.image.empty()) layer.image = TakeCanvas(seg.grid);
  cv::Rect touched;
  const Pose2 T_grid_sensor = scan.T_world_robot * sensor.T_robot_sensor;
  const long long pixels =
      subapertures_.empty() ? projector_.Accumulate(*scan.profile, T_grid_sensor, sensor, seg.grid,
                                                    &layer.image, &touched)
                            : subapertures_.at(static_cast<std::size_t>(scan.sensor_id))
                                  .Add(scan.profile, T_grid_sensor, sensor, seg.grid, &layer.image);
  UniteBounds(&layer.touched, touched);  // ffbp: at FlushSubapertures
  UniteBounds(&seg.touched, touched);
  seg.scans.push_back(scan);
  seg.path_end_m = scan.path_m;
  return pixels + flushed;
}

void KeyframeBuilder::Finish() {
  // The last tile holds what the window has, if that is at least half a tile
  // spacing of path (less is too little aperture to be worth a keyframe); so a run
  // shorter than a whole tile still gives one tile.
  if (!segments_.empty()) {
    FlushSubapertures();
    const double path = segments_.back().path_end_m - segments_.front().path_begin_m;
    const bool complete = static_cast<int>(segments_.size()) == segments_per_tile_ &&
                          path >= config_.tile_length_m * 0.999;
    if (path >= 0.5 * config_.tile_spacing_m) {
      closed_.push_back(MakeTile(0, segments_.size(), complete));
    }
  }
  segments_.clear();
}

std::vector<Keyframe> KeyframeBuilder::TakeClosed() {
  std::vector<Keyframe> out;
  out.swap(closed_);
  return out;
}

}  // namespace uwbsar
