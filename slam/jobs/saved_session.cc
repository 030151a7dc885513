#include "slam/jobs/saved_session.h"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>

#include "core/commit_journal.h"
#include "core/errors.h"
#include "core/log.h"
#include "drivers/rosbag/bag_reader.h"
#include "slam/session/session_file.h"

namespace uwbsar::slam {
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
  const auto start = std::chrono::steady_clock::now();
  SessionData data = ReadSession(path, &config);
  Log(LogLevel::kDebug,
      "session read: " + path + ", " + std::to_string(data.keyframes.size()) + " keyframes in " +
          std::to_string(
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()) +
          " s");
  return SavedSession{path, dir, std::move(lock), std::move(data), {}};
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
  rosbag::BagReader reader(bag_path);
  const rosbag::BagInfo& info = reader.Info();
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a
  const auto mix = [&hash](const void* data, std::size_t size) {
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    for (std::size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 1099511628211ull;
  };
  rosbag::BagMessage message;
  for (int n = 0; n < 256 && reader.Next(&message); ++n) {
    const std::string& topic = info.topics[static_cast<std::size_t>(message.topic)].name;
    mix(topic.data(), topic.size());
    mix(&message.log_time_ns, sizeof message.log_time_ns);
    mix(message.data, message.size);
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash));
  return "bag " + info.storage_identifier + " " + std::to_string(info.start_ns) + " " +
         std::to_string(info.end_ns) + " " + std::to_string(info.message_count) + " " + hex;
}

}  // namespace uwbsar::slam
