#include "pipeline/saved_session.h"

#include <filesystem>

#include "drivers/rosbag/bag_reader.h"
#include "pipeline/map_job.h"
#include "session/session_file.h"
#include "slam/commit_journal.h"
#include "slam/errors.h"

namespace uwbsar::pipeline {
namespace fs = std::filesystem;
namespace {

std::string FolderOf(const std::string& session_path) {
  const fs::path parent = fs::path(session_path).parent_path();
  return parent.empty() ? "." : parent.string();
}

/// A shared lock on `dir`, after completing a commit a dead process left there (which needs
/// the exclusive lock for a moment; a folder that cannot be written cannot be completed).
FolderLock LockForReading(const std::string& dir, const std::string& session_path) {
  if (HasInterruptedCommit(dir)) {
    const FolderLock exclusive(dir, FolderLock::Mode::kExclusive);
    try {
      RecoverInterruptedCommit(dir);
    } catch (const std::runtime_error& e) {
      throw InputError(session_path +
                       ": its folder holds an unfinished commit that cannot be "
                       "completed: " +
                       e.what());
    }
    return FolderLock(dir, FolderLock::Mode::kShared);  // held before the exclusive ends
  }
  return FolderLock(dir, FolderLock::Mode::kShared);
}

}  // namespace

SavedSession OpenSavedSession(const std::string& dir_or_file, const Config& config) {
  const std::string path = ResolveSessionPath(dir_or_file);
  std::error_code ec;
  const std::string dir = FolderOf(path);
  if (!fs::is_directory(dir, ec)) throw InputError(path + ": no session file there");
  FolderLock lock = LockForReading(dir, path);
  SessionData data = ReadSession(path, &config);
  return SavedSession{path, dir, std::move(lock), std::move(data)};
}

bool SamePlace(const std::string& a, const std::string& b) {
  std::error_code ec;
  return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec);
}

void RefuseToReplaceSavedMap(const std::string& out_dir,
                             const std::vector<std::string>& joined_dirs, bool overwrite,
                             const std::string& how) {
  const fs::path session = fs::path(out_dir) / kSessionFileName;
  std::error_code ec;
  if (overwrite || !fs::exists(fs::symlink_status(session, ec))) return;
  for (const std::string& dir : joined_dirs) {
    if (SamePlace(dir, out_dir)) return;
  }
  throw InputError(out_dir + ": holds a saved map (" + session.string() +
                   ") that this command would replace; " + how);
}

void RefuseMapFolderForLocalize(const std::string& out_dir) {
  const fs::path session = fs::path(out_dir) / kSessionFileName;
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(session, ec))) return;
  throw InputError(out_dir + ": holds a saved map (" + session.string() +
                   "): localisation never writes into a map's folder; give another --out, "
                   "e.g. " +
                   (fs::path(out_dir) / "localize").string());
}

void RefuseRunsAlreadyJoined(const SessionData& saved, const std::string& saved_path,
                             const std::vector<SessionTrajectory>& runs, const std::string& what) {
  for (const SessionTrajectory& run : runs) {
    if (run.fingerprint.empty()) continue;  // a session written before format version 3
    for (const SessionTrajectory& t : saved.trajectories) {
      if (t.fingerprint != run.fingerprint) continue;
      throw InputError(what + ": already in " + saved_path + " as run " + std::to_string(t.id) +
                       " (" + t.input + ", the same recording: " + t.fingerprint +
                       "); joining it again would count its data twice");
    }
  }
}

std::string BagFingerprint(const std::string& bag_path) {
  const rosbag::BagReader reader(bag_path);
  return RecordingFingerprint(reader.Info());
}

}  // namespace uwbsar::pipeline
