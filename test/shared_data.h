// Data made by others (public pose-graph data sets, the paper's LiDAR map, real radar
// measurements) is never copied into the repository: tests read it where it lies, in the
// `shared/data` folder beside the project root (`<source>/../shared/data`), or wherever
// $UWBSAR_SHARED_DATA points. On a machine without it a test that needs it is skipped with
// one line naming the file; with UWBSAR_REQUIRE_SHARED_DATA=1 (set by .ci/run) the same
// line is a failure, so CI never passes by skipping.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

namespace uwbsar::testing {

/// The shared data folder: $UWBSAR_SHARED_DATA, else <source tree>/../shared/data.
inline std::string SharedDataDir() {
  const char* env = std::getenv("UWBSAR_SHARED_DATA");
  if (env != nullptr && *env != '\0') return env;
  return (std::filesystem::path(UWBSAR_SOURCE_DIR).parent_path() / "shared" / "data").string();
}

/// `relative` (e.g. "maps/seed_lab/my_map.yaml") inside the shared data folder.
inline std::string SharedDataPath(const std::string& relative) {
  return (std::filesystem::path(SharedDataDir()) / relative).string();
}

/// Empty when the file exists; otherwise the one line that says what is missing.
inline std::string MissingSharedData(const std::string& relative) {
  const std::string path = SharedDataPath(relative);
  if (std::filesystem::exists(path)) return {};
  return "needs shared data " + relative + " (not found at " + path +
         "; set UWBSAR_SHARED_DATA to the shared data folder)";
}

/// True when a missing shared file must fail the test (CI) instead of skipping it.
inline bool SharedDataRequired() {
  const char* env = std::getenv("UWBSAR_REQUIRE_SHARED_DATA");
  return env != nullptr && std::string(env) == "1";
}

/// The paper's LiDAR grid of its test room (map_server YAML).
inline std::string SeedLabLidarMap() { return SharedDataPath("maps/seed_lab/my_map.yaml"); }

}  // namespace uwbsar::testing

/// Skips (or, under UWBSAR_REQUIRE_SHARED_DATA=1, fails) the current test when a shared
/// file is missing. Use at the top of a test body, SetUp() or SetUpTestSuite().
#define UWBSAR_NEED_SHARED_DATA(relative)                                               \
  do {                                                                                  \
    const std::string uwbsar_missing_ = ::uwbsar::testing::MissingSharedData(relative); \
    if (!uwbsar_missing_.empty()) {                                                     \
      if (::uwbsar::testing::SharedDataRequired()) {                                    \
        GTEST_FAIL() << uwbsar_missing_;                                                \
      } else {                                                                          \
        GTEST_SKIP() << uwbsar_missing_;                                                \
      }                                                                                 \
    }                                                                                   \
  } while (0)

/// The seed_lab LiDAR map, for tests that simulate in the paper's room.
#define UWBSAR_NEED_SEED_LAB_MAP() UWBSAR_NEED_SHARED_DATA("maps/seed_lab/my_map.yaml")
