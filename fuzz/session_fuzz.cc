// libFuzzer target: the session reader (session.uwbsar: an sqlite3 database of tables read by
// column name, range-checked, with zstd blobs) on arbitrary bytes, written into a map folder
// and read back as every command reads a saved map: the folder locked for reading, after
// completing a commit journal found there. The input's last two bytes also choose what a user
// may have left in the folder: the lock file's kind (none, regular, unreadable, a link to the
// session, to a file outside, to nothing, a FIFO, a folder), the journal's (none, regular, a
// link, a FIFO, a folder) and its stage's (a folder, missing, a link to another map, a folder
// holding a link); the journal's text is the input from "uwbsar-commit" on, or a sound one.
// Contract under test: bad input throws InputError naming the folder; no other exception
// escapes and nothing crashes, hangs, leaks or allocates past the budgets (libFuzzer's
// -rss_limit_mb=2048 in `make fuzz-smoke` catches a size that is not checked before
// allocation); what is accepted holds only finite poses and tiles, and references that exist;
// a lock file or journal that is not a regular file is refused, a refused journal leaves the
// folder as it was, and nothing outside the folder ever changes.
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "core/commit_journal.h"
#include "core/errors.h"
#include "core/folder_lock.h"
#include "slam/session/session_file.h"

namespace {

namespace fs = std::filesystem;

bool Finite(const uwbsar::Pose2& p) {
  return std::isfinite(p.x_m) && std::isfinite(p.y_m) && std::isfinite(p.yaw_rad);
}

void Write(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string Bytes(const fs::path& path) {
  std::ostringstream out;
  out << std::ifstream(path, std::ios::binary).rdbuf();
  return out.str();
}

/// Every entry under `dir` (links not followed): its name, kind and size, and a regular file's
/// bytes; the lock file only when `with_lock`.
std::string Snapshot(const fs::path& dir, bool with_lock) {
  std::ostringstream out;
  std::error_code ec;
  for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!with_lock && it->path().filename() == uwbsar::kFolderLockName) continue;
    struct stat st {};
    if (::lstat(it->path().c_str(), &st) != 0) continue;
    out << it->path().string() << ' ' << st.st_mode << ' ' << st.st_size << '\n';
    if (S_ISREG(st.st_mode) && (st.st_mode & 0400) != 0) out << Bytes(it->path()) << '\n';
  }
  return out.str();
}

/// The input's last two bytes.
unsigned Choice(const std::uint8_t* data, std::size_t size) {
  return size < 2 ? 0u : data[size - 2] | static_cast<unsigned>(data[size - 1]) << 8;
}

void CheckAccepted(const uwbsar::SessionData& d) {
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
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const fs::path root = "/tmp/uwbsar_session_fuzz_" + std::to_string(::getpid());
  const fs::path dir = root / "map", other = root / "other", outside = root / "outside.txt";
  const fs::path lock = dir / uwbsar::kFolderLockName, journal = dir / uwbsar::kCommitJournalName;
  const fs::path stage = dir / ".uwbsar-partial-1";
  std::error_code ec;
  fs::remove_all(root, ec);
  fs::create_directories(dir);
  fs::create_directories(other);
  Write(outside, "not uwbsar's");
  Write(other / "summary.json", "another map's");
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const std::string path = (dir / "session.uwbsar").string();
  Write(path, bytes);

  const unsigned choice = Choice(data, size);
  const unsigned lock_kind = choice % 8, journal_kind = choice / 8 % 5,
                 stage_kind = choice / 40 % 4;
  switch (lock_kind) {
    case 1:
      Write(lock, "pid 1: uwbsar map, since then\n");
      break;
    case 2:
      Write(lock, "");
      ::chmod(lock.c_str(), 0);
      break;
    case 3:
      fs::create_symlink("session.uwbsar", lock);
      break;
    case 4:
      fs::create_symlink(outside, lock);
      break;
    case 5:
      fs::create_symlink(root / "nothing", lock);
      break;
    case 6:
      ::mkfifo(lock.c_str(), 0644);
      break;
    case 7:
      fs::create_directory(lock);
      break;
    default:
      break;  // none: the reader makes one
  }
  const std::size_t at = bytes.find("uwbsar-commit");
  const std::string text = at != std::string::npos ? bytes.substr(at)
                                                   : "uwbsar-commit 1\nstage .uwbsar-partial-1\n"
                                                     "remove trajectory.tum\npublish summary.json\n"
                                                     "end\n";
  switch (journal_kind) {
    case 1:
      Write(journal, text);
      break;
    case 2:
      Write(root / "journal", text);
      fs::create_symlink(root / "journal", journal);
      break;
    case 3:
      ::mkfifo(journal.c_str(), 0644);
      break;
    case 4:
      fs::create_directory(journal);
      break;
    default:
      break;
  }
  Write(dir / "trajectory.tum", "old");
  if (stage_kind == 2) fs::create_directory_symlink(other, stage);
  if (stage_kind == 0 || stage_kind == 3) {
    fs::create_directory(stage);
    if (stage_kind == 0) Write(stage / "summary.json", "new");
    if (stage_kind == 3) fs::create_symlink(outside, stage / "summary.json");
  }
  // The lock file as the reader found it, when it is one it may write its name into.
  const bool with_lock = lock_kind >= 3;
  const std::string outside_before = Snapshot(other, true) + Bytes(outside);
  const std::string before = Snapshot(dir, with_lock);

  bool locked = false, recovered = false;
  try {
    if (uwbsar::HasInterruptedCommit(dir.string())) {
      const uwbsar::FolderLock writer(dir.string(), uwbsar::FolderLock::Mode::kExclusive);
      locked = true;
      recovered = uwbsar::RecoverInterruptedCommit(dir.string());
    }
    const uwbsar::FolderLock reader(dir.string(), uwbsar::FolderLock::Mode::kShared);
    locked = true;
    CheckAccepted(uwbsar::ReadSession(path));
  } catch (const uwbsar::InputError& e) {
    const std::string what = e.what();
    if (what.rfind(dir.string(), 0) != 0) __builtin_trap();  // names the folder or a file in it
    // Refused before anything moved: the lock file, or the journal, which is left in place.
    const bool lock_refused = what.rfind(lock.string(), 0) == 0;
    const bool journal_refused = what.rfind(journal.string(), 0) == 0;
    if ((lock_refused || journal_refused) && Snapshot(dir, with_lock) != before) {
      __builtin_trap();
    }
  } catch (const std::runtime_error& e) {  // an I/O failure while completing: names the folder
    if (std::string(e.what()).rfind(dir.string(), 0) != 0) __builtin_trap();
  }
  // A lock file or journal that is not a regular file is never used, a journal whose stage is
  // missing or a link never completed, and nothing outside the folder changes.
  if (locked && (lock_kind >= 3 || (lock_kind == 2 && ::geteuid() != 0))) __builtin_trap();
  if (recovered && (journal_kind >= 2 || stage_kind == 1 || stage_kind == 2)) __builtin_trap();
  if (Snapshot(other, true) + Bytes(outside) != outside_before) __builtin_trap();
  fs::remove_all(root, ec);
  return 0;
}
