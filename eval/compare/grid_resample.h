// One occupancy grid seen in another grid's cells (differing resolution, origin or
// orientation), the step that puts a SAR map and a LiDAR grid on common cells.
#pragma once

#include "core/pose2.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar {

struct ResampledGrid {
  OccupancyGrid grid;                  ///< the target's geometry, the source's evidence
  long long source_known_cells = 0;    ///< source cells that are not unknown
  long long source_known_outside = 0;  ///< ... whose centre falls outside the target grid
};

/// Resamples `source` onto the cells of `target` (its values are ignored; only its geometry
/// is used). `T_target_source` maps the source's world frame into the target's. Each target
/// cell takes the MAXIMUM value (unknown -1 < free 0 < ... < occupied 100) of
///  (a) every source cell whose centre falls inside it, and
///  (b) the source cell holding the target cell's centre,
/// so a finer source is max-pooled (a thin wall is never lost), a coarser source is sampled
/// at every target cell (no holes), and equal grids under the identity are copied exactly.
ResampledGrid ResampleOnto(const OccupancyGrid& source, const Pose2& T_target_source,
                           const OccupancyGrid& target);

}  // namespace uwbsar
