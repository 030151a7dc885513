// Resource budgets (limits.*): the sizes the imaging and map settings imply, checked before
// any work; the last step of ValidateSystemConfig.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "core/config_require.h"
#include "core/errors.h"
#include "frontend/segment_canvas.h"
#include "imaging/sensor_geometry.h"
#include "slam/config/system_config.h"

namespace uwbsar {
namespace {

using config_validation::Require;

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3g", v);
  return buf;
}

/// A derived size against its budget: "<key> (<value>) makes <what> <size>, more than
/// limits.<limit> (<budget>)".
void RequireWithin(double size, double budget, const std::string& src, const std::string& key,
                   double value, const std::string& what, const std::string& limit) {
  if (size <= budget) return;  // NaN/Inf sizes fail too
  throw ConfigValueError(src, key,
                         "(" + Num(value) + ") makes " + what + " " + Num(size) +
                             ", more than limits." + limit + " (" + Num(budget) + ")");
}

/// Range samples per scan (oversampled in coherent mode) within limits.max_range_samples.
void ValidateRangeSamples(const SystemConfig& c, const std::string& src) {
  const LimitsConfig& l = c.limits;
  const bool coherent = c.imaging.coherent();
  for (std::size_t i = 0; i < c.radars.size(); ++i) {
    const double samples = static_cast<double>(c.radars[i].num_samples) *
                           (coherent ? c.imaging.coherent_oversampling : 1);
    const bool oversampling = coherent && c.radars[i].num_samples <= l.max_range_samples;
    RequireWithin(
        samples, l.max_range_samples, src,
        oversampling ? "imaging.coherent_oversampling" : RadarKey(c.radars, i) + ".num_samples",
        oversampling ? c.imaging.coherent_oversampling : c.radars[i].num_samples,
        "range samples per scan", "max_range_samples");
  }
}

/// "<n> <word>s" ("1 <word>"), whole numbers in full below 1e9.
std::string Count(double n, const std::string& word) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), n < 1e9 ? "%.0f" : "%.3g", n);
  return buf + (" " + word) + (n == 1 ? "" : "s");
}

/// The lines map.pgm's sensor model casts per keyframe (backend/navigation_grid.h: a fan of
/// 2 SideLines() + 1 from each antenna every ray_spacing_m of the tile's path) within
/// limits.max_navigation_rays, blaming the fan when the positions alone fit.
void ValidateNavigationRays(const SystemConfig& c, const std::string& src) {
  const NavigationGridConfig& n = c.slam.navigation;
  const double positions = std::floor(c.keyframe.tile_length_m / n.ray_spacing_m + 1e-9) + 1.0;
  const double radars = static_cast<double>(c.radars.size());
  const double lines = 2.0 * n.SideLines() + 1.0;
  const double budget = c.limits.max_navigation_rays;
  const std::string count =
      Count(positions, "position") + " x " + Count(radars, "radar") + " x " + Count(lines, "line");
  const std::string k = "slam.navigation.";
  const std::string what = "navigation rays per keyframe";
  if (lines > 1 && positions * radars <= budget) {
    RequireWithin(
        positions * radars * lines, budget, src, k + "ray_half_angle_deg", n.ray_half_angle_deg,
        what + " (at " + k + "ray_angle_step_deg " + Num(n.ray_angle_step_deg) + ": " + count + ")",
        "max_navigation_rays");
  }
  // Too many positions: a fine ray spacing, else a long tile.
  const bool fine = n.ray_spacing_m < NavigationGridConfig{}.ray_spacing_m;
  RequireWithin(positions * radars * lines, budget, src,
                fine ? k + "ray_spacing_m" : "keyframe.tile_length_m",
                fine ? n.ray_spacing_m : c.keyframe.tile_length_m, what + " (" + count + ")",
                "max_navigation_rays");
}

/// A segment's canvas (frontend/keyframe_builder.h SegmentCanvasFor, the size KeyframeBuilder
/// allocates) against limits.max_tile_pixels, blaming the setting that makes it too large.
SegmentCanvas ValidateSegmentCanvas(const SystemConfig& c, const std::string& src) {
  const LimitsConfig& l = c.limits;
  const KeyframeConfig& k = c.keyframe;
  std::vector<SensorGeometry> sensors;
  for (const RadarConfig& r : c.radars) sensors.push_back(SensorGeometry::FromConfig(r, c.pulse));
  const SegmentCanvas canvas = SegmentCanvasFor(k, sensors);
  const double pixel_m = c.imaging.pixel_size_m;
  const double pixels = canvas.Pixels(pixel_m);
  if (pixels > l.max_tile_pixels) {
    // Blame the pixel size if the geometry fits at the default one, else the longest term.
    std::string key = "imaging.pixel_size_m";
    double value = pixel_m;
    if (canvas.Pixels(std::max(pixel_m, ImagingConfig{}.pixel_size_m)) > l.max_tile_pixels) {
      if (canvas.reach_m >= canvas.spacing_term_m && canvas.reach_m >= k.margin_m) {
        key = RadarKey(c.radars, canvas.reach_sensor) + ".max_range_m";
        value = c.radars[canvas.reach_sensor].max_range_m;
      } else if (k.margin_m >= canvas.spacing_term_m) {
        key = "keyframe.margin_m", value = k.margin_m;
      } else {
        key = "keyframe.tile_spacing_m", value = k.tile_spacing_m;
      }
    }
    RequireWithin(pixels, l.max_tile_pixels, src, key, value,
                  "one tile canvas (pixels, at imaging.pixel_size_m " + Num(pixel_m) + " m)",
                  "max_tile_pixels");
  }
  return canvas;
}

}  // namespace

/// Sizes the imaging and map settings imply, checked against `limits:` before any work
/// (see KeyframeBuilder and GlobalMap for what they allocate). Runs after the plain range
/// checks, so every size here is positive.
void ValidateLimits(const SystemConfig& c, const std::string& src) {
  const LimitsConfig& l = c.limits;
  for (const auto& [key, value] : {std::make_pair("max_tile_pixels", l.max_tile_pixels),
                                   std::make_pair("max_imaging_memory_mb", l.max_imaging_memory_mb),
                                   std::make_pair("max_keyframes_per_m", l.max_keyframes_per_m),
                                   std::make_pair("max_range_samples", l.max_range_samples),
                                   std::make_pair("max_image_pixels", l.max_image_pixels),
                                   std::make_pair("max_map_image_pixels", l.max_map_image_pixels),
                                   std::make_pair("tile_cache_mb", l.tile_cache_mb),
                                   std::make_pair("max_navigation_rays", l.max_navigation_rays),
                                   std::make_pair("max_input_file_mb", l.max_input_file_mb)}) {
    Require(value > 0, src, std::string("limits.") + key, "must be > 0");
  }
  ValidateRangeSamples(c, src);
  const KeyframeConfig& k = c.keyframe;
  RequireWithin(1.0 / k.tile_spacing_m, l.max_keyframes_per_m, src, "keyframe.tile_spacing_m",
                k.tile_spacing_m, "keyframes per metre", "max_keyframes_per_m");
  const SegmentCanvas canvas = ValidateSegmentCanvas(c, src);
  const double segments = std::round(k.tile_length_m / k.tile_spacing_m);
  const double canvas_mb = canvas.Pixels(c.imaging.pixel_size_m) *
                           (c.imaging.coherent() ? 8.0 : 4.0) / (1024.0 * 1024.0);
  // Per-radar matching images each radar into a canvas of its own (keyframe_builder.h).
  const double layers = c.place_recognition.per_radar.enabled && c.radars.size() >= 2
                            ? static_cast<double>(c.radars.size())
                            : 1.0;
  RequireWithin((segments + 1.0) * layers * canvas_mb, l.max_imaging_memory_mb, src,
                "keyframe.tile_length_m", k.tile_length_m,
                "the segment canvases alive at once (MB)", "max_imaging_memory_mb");
  // A tile spans its segments' canvases; the map warps it at slam.map_resolution_m (the
  // tile is never upsampled, so a finer map still costs the footprint at map resolution).
  const double tile_side_m = 2.0 * canvas.half_m() + (segments - 1.0) * canvas.spacing_term_m;
  const double map_m = c.slam.map_resolution_m;
  RequireWithin(tile_side_m * tile_side_m / (map_m * map_m), l.max_tile_pixels, src,
                "slam.map_resolution_m", map_m, "one tile's footprint in the map (pixels)",
                "max_tile_pixels");
  ValidateNavigationRays(c, src);  // after the tile's budgets, which name tile_length_m first
}

void CheckWholeRunImage(const ImageGrid& grid, const LimitsConfig& limits,
                        const std::string& what) {
  const double pixels = static_cast<double>(grid.rows) * static_cast<double>(grid.cols);
  if (grid.rows >= 0 && grid.cols >= 0 && pixels <= limits.max_image_pixels) return;
  std::ostringstream msg;
  msg.precision(3);
  msg << what << " of this run would be " << grid.cols << " x " << grid.rows << " pixels ("
      << pixels << ") at " << grid.resolution_m
      << " m (imaging.pixel_size_m / --resolution), more than limits.max_image_pixels ("
      << limits.max_image_pixels << ")";
  throw InputError(msg.str());
}

}  // namespace uwbsar
