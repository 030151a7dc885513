#include "imaging/sensor_geometry.h"

#include <algorithm>
#include <cmath>

#include "imaging/pulse.h"

namespace uwbsar {

SensorGeometry SensorGeometry::FromConfig(const RadarConfig& radar, const PulseConfig& pulse) {
  SensorGeometry g;
  g.T_robot_sensor = {radar.mount_x_m, radar.mount_y_m, radar.boresight_yaw_deg * M_PI / 180.0};
  g.fov_half_angle_rad = radar.fov_half_angle_deg * M_PI / 180.0;
  g.min_range_m = radar.min_range_m;
  g.max_range_m = radar.max_range_m;
  g.range_offset_m = radar.range_offset_m;
  g.bin_size_m = RangeBinSizeM(pulse);
  g.num_samples = radar.num_samples;
  g.zero_leading_samples = radar.zero_leading_samples;
  return g;
}

void SensorGeometry::SectorBoundsInRobot(double bounds[4]) const {
  // The sector's extreme points lie on its corners or where the outer arc
  // crosses an axis direction; sampling the arcs finely is exact enough here.
  bounds[0] = bounds[2] = 1e300;
  bounds[1] = bounds[3] = -1e300;
  constexpr int kSteps = 64;
  for (int i = 0; i <= kSteps; ++i) {
    const double angle = -fov_half_angle_rad + 2.0 * fov_half_angle_rad * i / kSteps;
    for (double range : {min_range_m, max_range_m}) {
      const Point2 p = T_robot_sensor * Point2{range * std::cos(angle), range * std::sin(angle)};
      bounds[0] = std::min(bounds[0], p.x_m);
      bounds[1] = std::max(bounds[1], p.x_m);
      bounds[2] = std::min(bounds[2], p.y_m);
      bounds[3] = std::max(bounds[3], p.y_m);
    }
  }
}

}  // namespace uwbsar
