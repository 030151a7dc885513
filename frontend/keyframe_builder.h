// Cuts the stream of imaged scans into overlapping keyframe tiles, imaging each
// scan only once. The path is split into segments of tile_spacing_m; each
// segment's scans are back-projected into a dense canvas on a world-aligned
// pixel lattice (pixel centres at integer multiples of the resolution, world
// axes). A tile is the exact sum of tile_length_m / tile_spacing_m consecutive
// segments, cropped to the pixels they observed: with the defaults (2 m every
// 1 m) consecutive tiles overlap by half, like the paper's regions, at half the
// back-projection cost of imaging every scan into two tiles. With keep_sensor_images,
// each radar's scans go into a canvas of their own (per-radar matching); the tile is then
// the sum of those canvases and also carries them, cropped, as Keyframe::sensor_tiles.
#pragma once

#include <deque>
#include <vector>

#include "frontend/keyframe.h"
#include "frontend/keyframe_config.h"
#include "frontend/segment_canvas.h"
#include "imaging/back_projection.h"
#include "imaging/factorized_back_projection.h"
#include "imaging/imaging_config.h"
#include "imaging/sensor_geometry.h"

namespace uwbsar {

class KeyframeBuilder {
 public:
  /// tile_length_m must be a whole multiple of tile_spacing_m (ValidateConfig checks).
  /// `pulse` sets the polar sampling of imaging.method ffbp.
  KeyframeBuilder(const KeyframeConfig& keyframe, const ImagingConfig& imaging,
                  const PulseConfig& pulse, std::vector<SensorGeometry> sensors,
                  bool keep_sensor_images = false);

  /// Images `scan` into the current segment; scans must come in non-decreasing path_m.
  /// Returns the pixels updated (imaging.method ffbp: those written by this call, as
  /// sub-apertures complete).
  long long Add(const ImagedScan& scan);
  /// End of run: emits the last tile (marked incomplete if shorter than L) when it
  /// holds at least half a tile spacing of path.
  void Finish();
  /// Tiles closed so far, oldest first; the builder forgets them.
  std::vector<Keyframe> TakeClosed();

  int segments_per_tile() const { return segments_per_tile_; }

 private:
  /// A canvas: all sensors, or one sensor with keep_sensor_images.
  struct Layer {
    cv::Mat image;     ///< allocated on the first scan imaged into it
    cv::Rect touched;  ///< canvas pixels that received any scan
  };
  struct Segment {
    long long lattice_col0 = 0;  ///< global lattice column of the canvas's column 0
    long long lattice_row0 = 0;  ///< global lattice row of the canvas's row 0 (row = -y)
    ImageGrid grid;              ///< canvas geometry in the world frame
    std::vector<Layer> layers;   ///< index: sensor id with keep_sensor_images, else 0
    cv::Rect touched;            ///< canvas pixels that received any scan (all layers)
    std::vector<ImagedScan> scans;
    double path_begin_m = 0.0;
    double path_end_m = 0.0;
  };

  void OpenSegment(const ImagedScan& scan);
  /// Drops the oldest segment, keeping its canvases, zeroed, for the next segments.
  void DropOldestSegment();
  /// A canvas of zeros for `grid`: a kept one when one fits, else a new one.
  cv::Mat TakeCanvas(const ImageGrid& grid);
  /// imaging.method ffbp: writes every radar's pending sub-apertures into the newest segment;
  /// returns the pixels written.
  long long FlushSubapertures();
  Layer& LayerOf(Segment& segment, int sensor_id);
  /// Tile of the segments [first, first + count) of segments_.
  Keyframe MakeTile(std::size_t first, std::size_t count, bool complete);
  /// Where a layer's touched pixels land in a tile whose top-left lattice pixel is (c_lo, r_lo).
  static cv::Rect LayerRectInTile(const Segment& s, const Layer& layer, long long c_lo,
                                  long long r_lo);
  /// Keyframe::sensor_tiles of the tile of segments [first, first + count).
  void AddSensorTiles(std::size_t first, std::size_t count, long long c_lo, long long r_lo,
                      Keyframe* tile) const;

  KeyframeConfig config_;
  double resolution_m_;
  bool coherent_;
  bool keep_sensor_images_;
  int segments_per_tile_;
  std::vector<SensorGeometry> sensors_;
  SegmentCanvas canvas_;  ///< one segment's canvas (SegmentCanvasFor)
  BackProjector projector_;
  /// imaging.method ffbp: one per radar (sub-apertures never mix radars); empty for direct.
  std::vector<FactorizedBackProjector> subapertures_;
  std::deque<Segment> segments_;  ///< the last segments_per_tile_ segments, newest last
  /// Canvases of dropped segments, all zeros again: only their touched pixels were written, and
  /// those are zeroed on the way here, which is much cheaper than a new canvas (the page faults
  /// and zeroing of megabytes per segment; measured in BM_ImageTile).
  std::vector<cv::Mat> spare_canvases_;
  std::vector<Keyframe> closed_;
  int segments_opened_ = 0;
  int next_id_ = 0;
};

}  // namespace uwbsar
