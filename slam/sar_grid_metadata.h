// Pixel geometry of a float SAR image written next to it as `<prefix>_grid.yaml`
// (tools/imaging_job.cc WriteStripOutputs): column = +x, row = -y in the world frame,
// (x0_m, y0_m) = the centre of pixel (row 0, col 0). Read here because YAML is parsed
// in slam/ only; frontend/image_grid.h holds the same numbers as an ImageGrid.
#pragma once

#include <string>

namespace uwbsar {

struct SarGridMetadata {
  double x0_m = 0.0;          ///< x of the centre of column 0
  double y0_m = 0.0;          ///< y of the centre of row 0 (the top row)
  double resolution_m = 0.0;  ///< pixel size, > 0
  int rows = 0;
  int cols = 0;
  std::string mode;  ///< "paper" (real image) or "coherent" (two pages: re, im); may be empty
};

/// Reads a `_grid.yaml`. Throws InputError naming the file, line and key on a missing or
/// unreadable file, a missing key, a non-finite value, resolution <= 0 or rows/cols < 1.
SarGridMetadata LoadSarGridMetadata(const std::string& yaml_path);

}  // namespace uwbsar
