// Shared by `uwbsar image` and the imaging demo: read a text log or simulate a built-in
// scene, run the frontend over it, render the whole-run strip in the world frame and write
// it in every form.
#pragma once

#include <string>
#include <vector>

#include "drivers/sim/synthetic_run.h"
#include "frontend/imaging_frontend.h"
#include "frontend/strip_renderer.h"
#include "slam/app_config.h"

namespace uwbsar::slam {

struct StripResult {
  StripImage strip;
  FrontendStats stats;
  std::vector<ImagedScan> scans;
  double seconds = 0.0;
};

/// The odometry and radar scans of a whole run to image.
struct ImagingInput {
  std::vector<OdometrySample> odometry;
  std::vector<RadarScan> scans;
};

/// A text log's records (drivers/logs/text_log.h). Throws InputError naming the log on a
/// malformed record, and when it holds no scans (nothing to image) or no odometry (the
/// scans cannot be placed), or when it is not a regular file of at most `max_mb` MiB
/// (limits.max_input_file_mb).
ImagingInput ReadImagingLog(const std::string& path, double max_mb);

/// A built-in synthetic run past DemoScatterers (seed 1, EchoModel defaults): `scene`
/// "straight" (SyntheticPath's defaults) or "arc" (the same path on a 4 m turn radius).
ImagingInput SyntheticImagingRun(const Config& config, const std::string& scene);

/// Feeds scans and odometry in time order through an ImagingFrontend and renders the strip.
/// Throws InputError ("nothing imaged: ...", naming no file: the caller prefixes its input)
/// when there are no scans, every valid scan is all zero, or no scan could be imaged.
StripResult ImageRun(const Config& config, const std::vector<OdometrySample>& odometry,
                     const std::vector<RadarScan>& scans);

/// Writes <prefix>_raw.png, _positive.png, _enhanced.png, (_logmag.png), _float.tif, _grid.yaml.
std::vector<std::string> WriteStripOutputs(const std::string& dir, const std::string& prefix,
                                           const StripImage& strip, const EnhanceConfig& enhance);

/// The built-in imaging scene: a wall 1.5 m to the left along the path and point
/// targets on both sides (metal poles).
std::vector<Scatterer> DemoScatterers();
std::vector<Point2> DemoPointTargets();

}  // namespace uwbsar::slam
