// Reading TUM trajectories (`t x y z qx qy qz qw`, seconds; '#' comments), e.g. a
// simulator's ground_truth.tum given to `uwbsar map --ground-truth`.
#pragma once

#include <string>
#include <vector>

#include "core/errors.h"
#include "core/limits_config.h"
#include "core/types.h"

namespace uwbsar {

/// Planar poses (yaw from the quaternion) with their stamps, in file order.
/// Throws InputError naming the file and line on a malformed line or an empty file, and
/// naming the file when it is not a regular file of at most `max_mb` MiB
/// (limits.max_input_file_mb). A stamp outside what uwbsar's outputs hold (core/stamp_range.h)
/// is refused naming the line. `lines` (optional) receives each pose's line number.
std::vector<OdometrySample> ReadTum(const std::string& path,
                                    double max_mb = LimitsConfig{}.max_input_file_mb,
                                    std::vector<int>* lines = nullptr);

}  // namespace uwbsar
