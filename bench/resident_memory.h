// The process's resident memory now, for benchmarks that trace it over a run.
#pragma once

#include <fstream>
#include <string>

namespace uwbsar {

/// Current resident set size (VmRSS of /proc/self/status) in MiB; 0 if unreadable.
inline double ResidentMiB() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      double kib = 0.0;
      status >> kib;
      return kib / 1024.0;
    }
    status.ignore(1 << 12, '\n');
  }
  return 0.0;
}

}  // namespace uwbsar
