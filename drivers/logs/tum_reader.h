// Reading TUM trajectories (`t x y z qx qy qz qw`, seconds; '#' comments), e.g. a
// simulator's ground_truth.tum given to `uwbsar map --ground-truth`.
#pragma once

#include <string>
#include <vector>

#include "core/errors.h"
#include "core/types.h"

namespace uwbsar {

/// Planar poses (yaw from the quaternion) with their stamps, in file order.
/// Throws InputError naming the file and line on a malformed line or an empty file.
std::vector<OdometrySample> ReadTum(const std::string& path);

}  // namespace uwbsar
