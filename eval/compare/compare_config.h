// Configuration of map comparison (`uwbsar compare`, `uwbsar export-pcd`).
// Part of the configuration; fields are read and written by the generic loader.
#pragma once

#include <string>
#include <vector>

#include "core/named_enum.h"

namespace uwbsar {

/// compare.align: ICP between the occupied cells (from the map origins or --init), or
/// the map origins trusted.
enum class CompareAlign { kIcp, kOrigin };
template <>
struct EnumNames<CompareAlign> {
  static constexpr std::pair<CompareAlign, const char*> kNames[] = {
      {CompareAlign::kIcp, "icp"}, {CompareAlign::kOrigin, "origin"}};
};

/// Map comparison against a LiDAR occupancy grid (`uwbsar compare`) and PCD export
/// (`uwbsar export-pcd`). Evaluation rule: see eval/compare/map_metrics.h.
struct CompareConfig {
  CompareAlign align = CompareAlign::kIcp;    ///< icp (from the map origins or --init) or origin
  std::string icp_method = "point_to_plane";  ///< point_to_plane (2-D normals) or point_to_point
  std::vector<double> icp_max_correspondence_m = {
      1.0, 0.5, 0.25, 0.1};                  ///< coarse-to-fine
                                             ///< ICP stages: pairs farther apart are ignored
  int icp_max_iterations = 50;               ///< ICP iterations per stage
  double icp_transformation_epsilon = 1e-9;  ///< a stage stops when the transform changes less
                                             ///< (PCL: squared translation + rotation change)
  int icp_normal_neighbours = 6;             ///< point_to_plane: cells used for each normal
  double icp_min_inlier_fraction = 0.3;      ///< fewer SAR cells within the last stage's
                                             ///< distance: ICP rejected, initial transform kept
  bool grey_205_unknown = true;              ///< trinary maps: grey 205 is unknown even where
                                             ///< the YAML's free_thresh (Nav2: 0.25) says free
  int tolerance_cells = 1;                   ///< precision / recall / F1 match distance
                                             ///< (cells, 8-neighbourhood)
  int overlay_pixels_per_cell = 4;           ///< overlay.png scale
  double pcd_peak_fraction = 0.2;            ///< export-pcd of a float SAR map: peaks weaker
                                             ///< than this fraction of the strongest are dropped
  double pcd_peak_radius_m = 0.05;           ///< export-pcd: a peak is the maximum within this

  template <class V>
  void Visit(V& v) {
    v("align", align);
    v("icp_method", icp_method);
    v("icp_max_correspondence_m", icp_max_correspondence_m);
    v("icp_max_iterations", icp_max_iterations);
    v("icp_transformation_epsilon", icp_transformation_epsilon);
    v("icp_normal_neighbours", icp_normal_neighbours);
    v("icp_min_inlier_fraction", icp_min_inlier_fraction);
    v("grey_205_unknown", grey_205_unknown);
    v("tolerance_cells", tolerance_cells);
    v("overlay_pixels_per_cell", overlay_pixels_per_cell);
    v("pcd_peak_fraction", pcd_peak_fraction);
    v("pcd_peak_radius_m", pcd_peak_radius_m);
  }
};

/// Semantic checks of compare.* (ranges, names, consistency); throws ConfigError naming the
/// dotted key and `source_name`.
void Validate(const CompareConfig& config, const std::string& source_name);

}  // namespace uwbsar
