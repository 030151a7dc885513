// Pixel geometry of a SAR image: `<prefix>_grid.yaml` next to a float SAR image
// (slam/jobs/imaging_job.cc WriteStripOutputs, `map_grid.yaml` of `uwbsar map`), or a grid
// YAML written by hand for an image from another tool. Column = +x, row = -y in the world
// frame, (x0_m, y0_m) = the centre of pixel (row 0, col 0). Keys: x0_m, y0_m,
// resolution_m (required); rows, cols (optional: checked against the image when given);
// image (optional: the image file, relative to the YAML's folder); mode (optional).
// Read with core/yaml_file.h (the one YAML reader); imaging/image_grid.h holds the same
// numbers as an ImageGrid.
#pragma once

#include <string>

namespace uwbsar {

/// The pixel sizes a grid YAML may declare: a SAR image's pixel is millimetres to centimetres;
/// outside this a value is a typo (or a hostile file) whose extent would be kilometres.
constexpr double kMinGridResolutionM = 1e-6;
constexpr double kMaxGridResolutionM = 10.0;

struct SarGridMetadata {
  double x0_m = 0.0;          ///< x of the centre of column 0
  double y0_m = 0.0;          ///< y of the centre of row 0 (the top row)
  double resolution_m = 0.0;  ///< pixel size, > 0
  int rows = 0;               ///< 0 = not given (the image's own size)
  int cols = 0;               ///< ...
  std::string mode;   ///< "paper" (real image) or "coherent" (two pages: re, im); may be empty
  std::string image;  ///< the image's path (resolved against the YAML's folder); may be empty
};

/// Reads a grid YAML. Throws InputError naming the file, line and key on a missing or
/// unreadable file, a missing key, a non-finite value, a resolution outside
/// [kMinGridResolutionM, kMaxGridResolutionM] or rows/cols < 1.
SarGridMetadata LoadSarGridMetadata(const std::string& yaml_path);

}  // namespace uwbsar
