// A SAR image from disk, as `uwbsar match`, `uwbsar loops --images` and `uwbsar compare`
// take it: an 8- or 16-bit PNG/PGM (the detected, enhanced image of another tool, e.g. the
// paper's published figures: positive image, blurred, min-max normalised), or a float
// TIFF as `uwbsar image` and `uwbsar map` write it (1 page real, 2 pages re and im), with
// its pixel geometry from a grid YAML (imaging/sar_grid_metadata.h) when one is found.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "core/limits_config.h"
#include "imaging/image_grid.h"

namespace uwbsar {

struct SarImageFile {
  std::string path;       ///< the image file
  std::string grid_yaml;  ///< the grid YAML that gave `grid`; empty when there was none
  cv::Mat image;  ///< CV_8UC1 (enhanced input; 16-bit scaled to 8 by its full scale: a PGM's
                  ///< maxval, else the image's maximum), CV_32FC1 or CV_32FC2 (NaN/inf -> 0)
  bool enhanced = false;           ///< true for 8/16-bit input: already the paper's feature image
  ImageGrid grid;                  ///< from the grid YAML, else x0 = y0 = 0 at the given resolution
  cv::Mat observed;                ///< CV_8UC1, 255 where the image holds a measurement (non-zero)
  long long nonfinite_values = 0;  ///< NaN/inf values of a float image, read as 0
};

/// The grid YAML that describes `image_path`, if one exists beside it:
/// `<stem>_grid.yaml`, or `<prefix>_grid.yaml` for `<prefix>_float.tif`. Empty otherwise.
std::string FindGridYaml(const std::string& image_path);

/// Reads `path`: an image file (grid YAML found by FindGridYaml wins over
/// `default_resolution_m`), or a grid YAML whose `image` key names the image. Throws
/// InputError naming the file on a missing or undecodable file, an unsupported pixel type,
/// a size that disagrees with the grid YAML, an image without any measurement (all 0, or every
/// float value NaN/inf), or a uniform one. NaN/inf pixels of a float image are read as not
/// measured (0), with one warning giving their count.
/// An image declaring more than `max_pixels` (limits.max_map_image_pixels) is refused from
/// its header, before decoding.
SarImageFile ReadSarImageFile(const std::string& path, double default_resolution_m,
                              double max_pixels = LimitsConfig{}.max_map_image_pixels);

}  // namespace uwbsar
