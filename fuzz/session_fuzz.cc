// libFuzzer target: the session reader (session.uwbsar: an sqlite3 database of tables read by
// column name, range-checked, with zstd blobs) on arbitrary bytes, written to a temporary file
// and read back. Contract under test: bad input throws InputError naming the file; no other
// exception escapes and nothing crashes, leaks or allocates past the budgets (libFuzzer's
// -rss_limit_mb=2048 in `make fuzz-smoke` catches a size that is not checked before
// allocation); what is accepted holds only finite poses and tiles, and references that exist.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <set>
#include <string>

#include "core/errors.h"
#include "slam/session/session_file.h"

namespace {

bool Finite(const uwbsar::Pose2& p) {
  return std::isfinite(p.x_m) && std::isfinite(p.y_m) && std::isfinite(p.yaw_rad);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path =
      "/tmp/uwbsar_session_fuzz_" + std::to_string(::getpid()) + ".uwbsar";
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) __builtin_trap();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) __builtin_trap();
  std::fclose(f);
  try {
    const uwbsar::SessionData d = uwbsar::ReadSession(path);
    std::set<int> ids;
    for (const uwbsar::SessionKeyframe& k : d.keyframes) {
      if (!Finite(k.T_map_anchor) || !Finite(k.T_odom_anchor) || !Finite(k.T_odom_robot) ||
          k.detected.empty() || !cv::checkRange(k.detected.Load()) ||
          !(k.detected_grid.resolution_m > 0) || !(k.features.grid.resolution_m > 0)) {
        __builtin_trap();
      }
      ids.insert(k.id);
    }
    for (const uwbsar::SessionEdge& e : d.edges) {
      if (!ids.count(e.edge.from_id) || !ids.count(e.edge.to_id)) __builtin_trap();
    }
    for (const uwbsar::SessionLoop& l : d.loops) {
      if (!ids.count(l.query_id) || !ids.count(l.match_id)) __builtin_trap();
    }
    for (const uwbsar::SessionOdometry& o : d.odometry) {
      if (!Finite(o.T_odom_robot)) __builtin_trap();
    }
  } catch (const uwbsar::InputError& e) {
    if (std::string(e.what()).rfind(path, 0) != 0) __builtin_trap();  // names the file
  }
  std::remove(path.c_str());
  return 0;
}
