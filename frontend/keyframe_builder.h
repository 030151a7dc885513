// Cuts the stream of imaged scans into overlapping keyframe tiles: a new tile
// starts every tile_spacing_m of path and takes every scan of the next
// tile_length_m, so with the defaults (2 m every 1 m) each scan lands in two
// tiles and consecutive tiles overlap by half, like the paper's regions.
#pragma once

#include <vector>

#include "frontend/back_projection.h"
#include "frontend/keyframe.h"
#include "frontend/sensor_geometry.h"
#include "slam/config.h"

namespace uwbsar {

class KeyframeBuilder {
 public:
  KeyframeBuilder(const KeyframeConfig& keyframe, const ImagingConfig& imaging,
                  std::vector<SensorGeometry> sensors);

  /// Images `scan` into every open tile; scans must come in non-decreasing path_m.
  /// Returns the pixels updated.
  long long Add(const ImagedScan& scan);
  /// End of run: closes the oldest open tile (marked incomplete if shorter than L) and
  /// drops the younger ones, whose scans it already holds.
  void Finish();
  /// Tiles closed so far, oldest first; the builder forgets them.
  std::vector<Keyframe> TakeClosed();

  /// The tile grid in the anchor frame (same for every tile).
  const ImageGrid& tile_grid() const { return tile_grid_; }

 private:
  void OpenTile(const ImagedScan& scan);

  KeyframeConfig config_;
  bool coherent_;
  std::vector<SensorGeometry> sensors_;
  ImageGrid tile_grid_;
  BackProjector projector_;
  std::vector<Keyframe> open_;
  std::vector<Keyframe> closed_;
  double next_start_m_ = 0.0;
  bool started_ = false;
  int next_id_ = 0;
};

/// Tile grid in the anchor frame covering every sensor's reach over a straight
/// path of `path_length_m` along +x, plus `margin_m`.
ImageGrid TileGridFor(const std::vector<SensorGeometry>& sensors, double path_length_m,
                      double margin_m, double resolution_m);

}  // namespace uwbsar
