#include "slam/outputs/map_output_stage.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "core/commit_journal.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/shortest_number.h"
#include "imaging/image_io.h"
#include "slam/outputs/map_outputs.h"
#include "slam/outputs/output_folder.h"

namespace uwbsar::slam {
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

/// trajectory_<digits>.tum or ground_truth_<digits>.tum: one run of a joined session
/// (slam/outputs/session_outputs.h, slam/outputs/session_files.h).
bool IsRunTrajectoryName(const std::string& name) {
  const std::string suffix = ".tum";
  for (const std::string prefix : {"trajectory_", "ground_truth_"}) {
    if (name.size() <= prefix.size() + suffix.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
      continue;
    }
    const std::string digits =
        name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    if (digits.find_first_not_of("0123456789") == std::string::npos) return true;
  }
  return false;
}

/// Output names that exist in `out_dir` as folders: found before the work, not after it.
void RefuseFolderOutputs(const std::string& out_dir) {
  std::error_code ec;
  for (const std::string& name : AllMapOutputNames()) {
    const fs::path path = fs::path(out_dir) / name;
    if (fs::is_directory(fs::symlink_status(path, ec))) {
      throw InputError(path.string() + ": output file is a folder");
    }
  }
}

}  // namespace

std::vector<std::string> EarlierOutputsNotIn(const std::string& out_dir,
                                             const std::vector<std::string>& names) {
  auto written = [&names](const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  std::vector<std::string> earlier;
  std::error_code ec;
  for (const std::string& name : AllMapOutputNames()) {
    // A saved map is replaced by a commit that writes one, never removed by one that does not
    // (the commands refuse such a folder first: RefuseToReplaceSavedMap).
    if (name == "session.uwbsar") continue;
    if (!written(name) && fs::exists(fs::symlink_status(fs::path(out_dir) / name, ec))) {
      earlier.push_back(name);
    }
  }
  for (fs::directory_iterator it(out_dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (IsRunTrajectoryName(name) && !written(name)) earlier.push_back(name);
  }
  return earlier;
}

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
                                                 "results.mcap",
                                                 "report.html",
                                                 "ground_truth.tum",
                                                 kAlignedTrajectoryName,
                                                 "map_exact_float.tif",
                                                 "map_exact_grid.yaml",
                                                 "map_exact.png",
                                                 "session.uwbsar",
                                                 "localize.csv",
                                                 "live.json",
                                                 "summary.json"};
  return names;
}

namespace {

/// Commits `names` (and summary.json, last) from `stage` into `out_dir` as one set
/// (core/commit_journal.h), removing the outputs of an earlier run this run does not write (a
/// committed folder holds one run's files). Appends the final paths to `files`.
void CommitStagedOutputs(const fs::path& stage, const std::string& out_dir,
                         std::vector<std::string> names, std::vector<std::string>* files) {
  names.push_back("summary.json");
  CommitPlan plan;
  plan.stage_name = stage.filename().string();
  plan.publish = names;
  plan.remove = EarlierOutputsNotIn(out_dir, names);
  CommitFolder(out_dir, plan);
  for (const std::string& name : names) files->push_back((fs::path(out_dir) / name).string());
}

/// `path` does not exist (and no error says otherwise).
bool Missing(const std::string& path) {
  std::error_code ec;
  return !fs::exists(path, ec) && !ec;
}

}  // namespace

MapOutputStage::MapOutputStage(const std::string& out_dir)
    : out_dir_(out_dir), created_dir_(Missing(out_dir)), lock_(LockOutputFolder(out_dir)) {
  RefuseFolderOutputs(out_dir);
  stage_ = (fs::path(out_dir) / (std::string(kStagePrefix) + std::to_string(::getpid()))).string();
  // Registered and made as one step: a Ctrl-C watcher that has already removed the registered
  // paths cannot see a stage made after it (DeferInterrupts does not return then).
  const DeferInterrupts hold_signals;
  guard_ = std::make_unique<RemoveOnInterrupt>(stage_);
  std::error_code ec;
  fs::remove_all(stage_, ec);
  if (!fs::create_directory(stage_, ec)) {
    throw InputError(out_dir + ": cannot write into the output folder: " + ec.message());
  }
}

MapOutputStage::~MapOutputStage() {
  std::error_code ec;
  // A commit that failed past its commit point leaves its journal: the stage is what the next
  // command completes it from.
  if (!HasInterruptedCommit(out_dir_)) fs::remove_all(stage_, ec);
  // A run that failed leaves no empty folder it created behind (nothing was committed: it
  // holds only its lock file). The lock is still held here, so no other command is in it.
  if (!created_dir_) return;
  for (const fs::directory_entry& e : fs::directory_iterator(out_dir_, ec)) {
    if (e.path().filename() != kFolderLockName) return;
  }
  if (ec) return;
  fs::remove(fs::path(out_dir_) / kFolderLockName, ec);
  fs::remove(out_dir_, ec);
}

MapOutputs MapOutputStage::Commit(const MapRun& run, const MapOutputOptions& options) {
  return CommitState(CaptureMapState(run), options.exact ? &run : nullptr);
}

MapOutputs MapOutputStage::Commit(const MapState& state) { return CommitState(state, nullptr); }

MapOutputs MapOutputStage::CommitState(const MapState& run, const MapRun* exact_from) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::string> names;
  MapOutputs result = WriteMapFiles(run, stage_, exact_from, mosaic_, &names);
  if (extra_outputs_) {
    for (const std::string& name : extra_outputs_(stage_)) names.push_back(name);
  }
  WriteTextAtomic((fs::path(stage_) / "summary.json").string(), result.summary.dump(2) + "\n");
  CommitStagedOutputs(stage_, out_dir_, names, &result.files);
  Log(LogLevel::kDebug,
      "stage outputs: " +
          ShortestNumber(RoundToDigits(
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 3)) +
          " s, " + std::to_string(result.files.size()) + " files committed to " + out_dir_);
  return result;
}

std::vector<std::string> MapOutputStage::CommitWritten(const ExtraOutputs& write) {
  std::vector<std::string> names = write(stage_);
  names.erase(std::remove(names.begin(), names.end(), "summary.json"), names.end());
  if (!fs::exists(fs::path(stage_) / "summary.json")) {
    throw std::logic_error("CommitWritten: the writer wrote no summary.json");
  }
  std::vector<std::string> files;
  CommitStagedOutputs(stage_, out_dir_, names, &files);
  return files;
}

FolderLock LockOutputFolder(const std::string& out_dir) {
  EnsureDirectory(out_dir);  // InputError naming DIR when it is not a writable folder
  FolderLock lock(out_dir, FolderLock::Mode::kExclusive);
  RecoverInterruptedCommit(out_dir);  // a commit a dead process began is completed first
  RemoveStaleStagingFolders(out_dir);
  return lock;
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

}  // namespace uwbsar::slam
