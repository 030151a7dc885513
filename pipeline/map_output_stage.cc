// MapOutputStage: the staging folder of `uwbsar map` outputs (map_outputs.h), its
// creation before the work, the removal of staging folders left by dead processes, and
// removal on Ctrl-C. Commit, which writes the outputs, is in map_outputs.cc.
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "pipeline/map_outputs.h"
#include "pipeline/output_folder.h"
#include "slam/errors.h"

namespace uwbsar::pipeline {
namespace fs = std::filesystem;
namespace {

constexpr const char* kStagePrefix = ".uwbsar-partial-";

/// Removes the staging folders in `out_dir` whose process is gone (an interrupted run's).
void RemoveStaleStagingFolders(const std::string& out_dir) {
  std::error_code ec;
  for (fs::directory_iterator it(out_dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(kStagePrefix, 0) != 0) continue;
    const std::string digits = name.substr(std::strlen(kStagePrefix));
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos ||
        digits.size() > 9) {
      continue;
    }
    const pid_t pid = static_cast<pid_t>(std::stol(digits));
    if (pid == ::getpid() || ::kill(pid, 0) == 0 || errno != ESRCH) continue;
    std::error_code rm;
    fs::remove_all(it->path(), rm);
  }
}

}  // namespace

const std::vector<std::string>& AllMapOutputNames() {
  static const std::vector<std::string> names = {"trajectory.tum",
                                                 "odometry.tum",
                                                 "graph.g2o",
                                                 "loops.csv",
                                                 "map_float.tif",
                                                 "map_grid.yaml",
                                                 "map.png",
                                                 "map.yaml",
                                                 "map.pgm",
                                                 "report.html",
                                                 "ground_truth.tum",
                                                 "map_exact_float.tif",
                                                 "map_exact_grid.yaml",
                                                 "map_exact.png",
                                                 "session.uwbsar",
                                                 "summary.json"};
  return names;
}

MapOutputStage::MapOutputStage(const std::string& out_dir) : out_dir_(out_dir) {
  EnsureDirectory(out_dir);  // InputError naming DIR when it is not a writable folder
  RemoveStaleStagingFolders(out_dir);
  stage_ = (fs::path(out_dir) / (std::string(kStagePrefix) + std::to_string(::getpid()))).string();
  guard_ = std::make_unique<RemoveOnInterrupt>(stage_);
  std::error_code ec;
  fs::remove_all(stage_, ec);
  if (!fs::create_directory(stage_, ec)) {
    throw InputError(out_dir + ": cannot write into the output folder: " + ec.message());
  }
}

MapOutputStage::~MapOutputStage() {
  std::error_code ec;
  fs::remove_all(stage_, ec);
}

MapOutputs WriteMapOutputs(const MapRun& run, const std::string& out_dir,
                           const MapOutputOptions& options) {
  MapOutputStage stage(out_dir);
  return stage.Commit(run, options);
}

MapOutputs WriteMapOutputs(const MapState& state, const std::string& out_dir) {
  MapOutputStage stage(out_dir);
  return stage.Commit(state);
}

}  // namespace uwbsar::pipeline
