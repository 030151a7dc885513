#include "frontend/segment_canvas.h"

#include <cmath>

namespace uwbsar {

long long SegmentCanvas::HalfPixels(double pixel_m) const {
  return static_cast<long long>(std::ceil(half_m() / pixel_m));
}

double SegmentCanvas::Pixels(double pixel_m) const {
  const double side = 2.0 * std::ceil(half_m() / pixel_m) + 1.0;
  return side * side;
}

SegmentCanvas SegmentCanvasFor(const KeyframeConfig& keyframe,
                               const std::vector<SensorGeometry>& sensors) {
  // A segment's robot stays within tile_spacing_m (plus one scan step) of where the
  // segment started, in any direction: its canvas covers that disk plus the
  // farthest corner of any sensor's sector.
  SegmentCanvas canvas;
  canvas.spacing_term_m = 1.05 * keyframe.tile_spacing_m;
  canvas.margin_m = keyframe.margin_m;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    double b[4];
    sensors[i].SectorBoundsInRobot(b);
    for (double x : {b[0], b[1]}) {
      for (double y : {b[2], b[3]}) {
        const double reach = std::hypot(x, y);
        if (reach > canvas.reach_m) canvas.reach_m = reach, canvas.reach_sensor = int(i);
      }
    }
  }
  return canvas;
}

}  // namespace uwbsar
