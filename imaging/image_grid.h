// Pixel geometry of an image in a metric frame (world or a tile's anchor frame).
// Convention (the whole project's): column = +x, row = -y; pixel (row 0, col 0) is the
// top-left pixel and its centre sits at (x0_m, y0_m). All pixel <-> metric
// conversions of the project go through here.
#pragma once

#include <cmath>

#include "core/pose2.h"

namespace uwbsar {

struct ImageGrid {
  double x0_m = 0.0;  ///< x of the centre of column 0
  double y0_m = 0.0;  ///< y of the centre of row 0 (the top row)
  double resolution_m = 0.005;
  int rows = 0;
  int cols = 0;

  /// A grid whose pixels cover [x_min, x_max] x [y_min, y_max] (rounded outwards).
  static ImageGrid Covering(double x_min_m, double x_max_m, double y_min_m, double y_max_m,
                            double resolution_m) {
    ImageGrid g;
    g.resolution_m = resolution_m;
    g.cols = static_cast<int>(std::ceil((x_max_m - x_min_m) / resolution_m));
    g.rows = static_cast<int>(std::ceil((y_max_m - y_min_m) / resolution_m));
    g.x0_m = x_min_m + 0.5 * resolution_m;
    g.y0_m = y_max_m - 0.5 * resolution_m;
    return g;
  }

  double ColToX(double col) const { return x0_m + col * resolution_m; }
  double RowToY(double row) const { return y0_m - row * resolution_m; }
  double XToCol(double x_m) const { return (x_m - x0_m) / resolution_m; }
  double YToRow(double y_m) const { return (y0_m - y_m) / resolution_m; }
  Point2 PixelToMetric(double col, double row) const { return {ColToX(col), RowToY(row)}; }

  /// The grid of this image resized to cols x rows (cv::resize, INTER_AREA): output
  /// pixel 0 averages input pixels [0, f), so its centre is at input (f - 1) / 2.
  ImageGrid Resized(int new_cols, int new_rows) const {
    ImageGrid g;
    const double fx = static_cast<double>(cols) / new_cols;
    const double fy = static_cast<double>(rows) / new_rows;
    g.resolution_m = resolution_m * fx;
    g.cols = new_cols;
    g.rows = new_rows;
    g.x0_m = ColToX(0.5 * (fx - 1.0));
    g.y0_m = RowToY(0.5 * (fy - 1.0));
    return g;
  }

  double width_m() const { return cols * resolution_m; }
  double height_m() const { return rows * resolution_m; }
  bool Contains(double col, double row) const {
    return col >= -0.5 && row >= -0.5 && col < cols - 0.5 && row < rows - 0.5;
  }
};

}  // namespace uwbsar
