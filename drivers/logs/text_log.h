// A plain-text log of scans and odometry, for users without bags and for small
// fixtures. One record per line, '#' starts a comment:
//   odom <stamp_ns> <x_m> <y_m> <yaw_rad>
//   scan <stamp_ns> <sensor_id> <n> <s_0> ... <s_n-1>
// Records may come in any order; readers sort them by time.
#pragma once

#include <string>
#include <vector>

#include "core/errors.h"
#include "core/limits_config.h"
#include "core/types.h"

namespace uwbsar {

struct TextLog {
  std::vector<OdometrySample> odometry;
  std::vector<RadarScan> scans;
};

/// Throws InputError naming the file, line and field on any malformed record, and naming the
/// file when it is not a regular file of at most `max_mb` MiB (limits.max_input_file_mb).
TextLog ReadTextLog(const std::string& path, double max_mb = LimitsConfig{}.max_input_file_mb);
/// Writes atomically (temporary name, then rename).
void WriteTextLog(const std::string& path, const TextLog& log);

}  // namespace uwbsar
