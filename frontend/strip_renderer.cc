#include "frontend/strip_renderer.h"

#include <algorithm>

#include "imaging/back_projection.h"
#include "imaging/factorized_back_projection.h"

namespace uwbsar {

ImageGrid WorldGridCovering(const std::vector<Pose2>& T_world_robot,
                            const std::vector<SensorGeometry>& sensors, double margin_m,
                            double resolution_m) {
  double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
  for (const SensorGeometry& s : sensors) {
    double b[4];
    s.SectorBoundsInRobot(b);
    const Point2 corners[4] = {{b[0], b[2]}, {b[0], b[3]}, {b[1], b[2]}, {b[1], b[3]}};
    for (const Pose2& T : T_world_robot) {
      for (const Point2& c : corners) {
        const Point2 p = T * c;
        lo_x = std::min(lo_x, p.x_m);
        hi_x = std::max(hi_x, p.x_m);
        lo_y = std::min(lo_y, p.y_m);
        hi_y = std::max(hi_y, p.y_m);
      }
    }
  }
  if (lo_x > hi_x) return ImageGrid::Covering(0, resolution_m, 0, resolution_m, resolution_m);
  return ImageGrid::Covering(lo_x - margin_m, hi_x + margin_m, lo_y - margin_m, hi_y + margin_m,
                             resolution_m);
}

StripImage RenderScans(const std::vector<ImagedScan>& scans,
                       const std::vector<SensorGeometry>& sensors, const ImageGrid& grid,
                       bool coherent, int threads,
                       const std::function<Pose2(const ImagedScan&)>& pose_of) {
  StripImage out;
  out.grid = grid;
  out.image = MakeSarImage(grid, coherent);
  BackProjector projector(std::max(1, threads));
  for (const ImagedScan& scan : scans) {
    const SensorGeometry& sensor = sensors.at(scan.sensor_id);
    const Pose2 T_world_robot = pose_of ? pose_of(scan) : scan.T_world_robot;
    out.pixel_updates += projector.Accumulate(*scan.profile, T_world_robot * sensor.T_robot_sensor,
                                              sensor, grid, &out.image);
  }
  return out;
}

StripImage RenderScans(const std::vector<ImagedScan>& scans,
                       const std::vector<SensorGeometry>& sensors, const ImageGrid& grid,
                       const ImagingConfig& imaging, const PulseConfig& pulse,
                       const std::function<Pose2(const ImagedScan&)>& pose_of) {
  if (imaging.method == ImagingMethod::kDirect) {
    return RenderScans(scans, sensors, grid, imaging.coherent(), imaging.num_threads, pose_of);
  }
  StripImage out;
  out.grid = grid;
  out.image = MakeSarImage(grid, imaging.coherent());
  const PolarSampling sampling = PolarSamplingFor(imaging.ffbp, pulse, imaging.coherent());
  std::vector<FactorizedBackProjector> streams(
      sensors.size(),
      FactorizedBackProjector(imaging.ffbp, sampling, std::max(1, imaging.num_threads)));
  for (const ImagedScan& scan : scans) {
    const SensorGeometry& sensor = sensors.at(scan.sensor_id);
    const Pose2 T_world_robot = pose_of ? pose_of(scan) : scan.T_world_robot;
    out.pixel_updates +=
        streams.at(scan.sensor_id)
            .Add(scan.profile, T_world_robot * sensor.T_robot_sensor, sensor, grid, &out.image);
  }
  for (FactorizedBackProjector& stream : streams)
    out.pixel_updates += stream.Flush(grid, &out.image);
  return out;
}

}  // namespace uwbsar
