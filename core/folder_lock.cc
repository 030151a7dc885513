#include "core/folder_lock.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include "core/errors.h"
#include "core/plain_file.h"

namespace uwbsar {
namespace {

/// This process's locks, by canonical folder path: flock(2) locks belong to an open file
/// description, so a second open() of the same lock file in this process would conflict with
/// the first. Each folder has one descriptor here, counted by holds.
struct Held {
  pid_t pid = 0;  ///< the process that took it (a forked child holds none of its parent's)
  int fd = -1;    ///< -1: no lock file could be opened (nothing can write the folder)
  int exclusive = 0;
  int shared = 0;
};

std::mutex& RegistryMutex() {
  static std::mutex* mutex = new std::mutex;
  return *mutex;
}

std::map<std::string, Held>& Registry() {
  static auto* registry = new std::map<std::string, Held>;
  return *registry;
}

/// "pid 123: uwbsar map bag --out A, since 2026-11-26 10:00:00 UTC".
std::string HolderText() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string cmdline((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (char& c : cmdline) {
    if (c == '\0' || c == '\n') c = ' ';
  }
  while (!cmdline.empty() && cmdline.back() == ' ') cmdline.pop_back();
  if (cmdline.size() > 200) cmdline = cmdline.substr(0, 200) + "...";
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char when[32];
  std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S UTC", &utc);
  return "pid " + std::to_string(::getpid()) + ": " + cmdline + ", since " + when + "\n";
}

/// The first line of the lock file that names a live process other than this one; "" if none.
std::string LiveHolder(int fd) {
  std::string text(4096, '\0');
  const ssize_t n = ::pread(fd, text.data(), text.size(), 0);
  text.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    long pid = 0;
    if (std::sscanf(line.c_str(), "pid %ld:", &pid) != 1 || pid <= 0 || pid == ::getpid()) {
      continue;
    }
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) return line;
  }
  return {};
}

/// Names this process in the lock file (opened O_APPEND) once its flock is held: a writer
/// alone, a reader after the other readers still there (the file emptied first when none is,
/// so that it does not grow). The text is a courtesy: the flock is the lock.
void WriteHolder(int fd, FolderLock::Mode mode) {
  if (mode == FolderLock::Mode::kExclusive || LiveHolder(fd).empty()) {
    if (::ftruncate(fd, 0) != 0) return;
  }
  const std::string text = HolderText();
  if (::write(fd, text.data(), text.size()) < 0) return;
}

[[noreturn]] void RefuseHeld(const std::string& dir, const std::string& holder) {
  throw InputError(dir + ": in use by another uwbsar process (" +
                   (holder.empty() ? std::string("holder unknown") : holder) +
                   "); run again when it has finished");
}

/// Opens DIR's lock file, never through a link and never truncated (the holder line is written
/// once the flock is held). A reader on read-only media locks through an existing lock file,
/// or with none there not at all (-1: nothing can write the folder). Any other lock file that
/// cannot be opened is refused, naming it.
int OpenLockFile(const std::string& dir, const std::string& lock_path, FolderLock::Mode mode) {
  std::string why, why_read;
  int error = 0, error_read = 0;
  int fd = OpenRegularFile(lock_path, O_RDWR | O_CREAT | O_APPEND, &why, &error);
  if (fd < 0 && mode == FolderLock::Mode::kShared &&
      (error == EROFS || error == EACCES || error == EPERM)) {
    fd = OpenRegularFile(lock_path, O_RDONLY, &why_read, &error_read);
    if (fd < 0 && error == EROFS && error_read == ENOENT) return -1;
  }
  if (fd >= 0) return fd;
  const std::string shown = dir + "/" + kFolderLockName;
  if (error == 0) {
    throw InputError(shown + ": the folder's lock file " + why +
                     "; refused (remove it: uwbsar makes a new one)");
  }
  throw InputError(shown + ": cannot open the folder's lock file (" + why +
                   "), so the folder cannot be locked; refused");
}

bool TryFlock(int fd, FolderLock::Mode mode) {
  const int op = (mode == FolderLock::Mode::kExclusive ? LOCK_EX : LOCK_SH) | LOCK_NB;
  while (::flock(fd, op) != 0) {
    if (errno != EINTR) return false;
  }
  return true;
}

}  // namespace

FolderLock::FolderLock(const std::string& dir, Mode mode) : dir_(dir) {
  std::error_code ec;
  const std::filesystem::path canonical = std::filesystem::canonical(dir, ec);
  if (ec || !std::filesystem::is_directory(canonical, ec)) {
    throw InputError(dir + ": cannot lock: not a folder");
  }
  const std::string lock_path = (canonical / kFolderLockName).string();
  std::lock_guard<std::mutex> guard(RegistryMutex());
  auto it = Registry().find(canonical.string());
  if (it != Registry().end() && it->second.pid != ::getpid()) {
    if (it->second.fd >= 0) ::close(it->second.fd);  // the parent's lock stays the parent's
    Registry().erase(it);
    it = Registry().end();
  }
  if (it == Registry().end()) {
    Held held;
    held.pid = ::getpid();
    held.fd = OpenLockFile(dir, lock_path, mode);
    if (held.fd >= 0 && !TryFlock(held.fd, mode)) {
      const std::string holder = LiveHolder(held.fd);
      ::close(held.fd);
      RefuseHeld(dir, holder);
    }
    if (held.fd >= 0) WriteHolder(held.fd, mode);
    it = Registry().emplace(canonical.string(), held).first;
  } else if (mode == Mode::kExclusive && it->second.exclusive == 0) {
    if (it->second.fd < 0) throw InputError(dir + ": cannot lock for writing: read-only media");
    // Upgrade in place. flock(2) drops the shared lock before it tries the exclusive one, so
    // on refusal the shared lock is taken again for the holds that remain.
    if (!TryFlock(it->second.fd, Mode::kExclusive)) {
      TryFlock(it->second.fd, Mode::kShared);
      RefuseHeld(dir, LiveHolder(it->second.fd));
    }
    WriteHolder(it->second.fd, Mode::kExclusive);
  }
  (mode == Mode::kExclusive ? it->second.exclusive : it->second.shared) += 1;
  key_ = mode == Mode::kExclusive ? "x" + canonical.string() : "s" + canonical.string();
}

FolderLock::~FolderLock() {
  if (key_.empty()) return;
  std::lock_guard<std::mutex> guard(RegistryMutex());
  const bool exclusive = key_[0] == 'x';
  auto it = Registry().find(key_.substr(1));
  if (it == Registry().end()) return;
  Held& held = it->second;
  (exclusive ? held.exclusive : held.shared) -= 1;
  if (held.exclusive == 0 && held.shared == 0) {
    if (held.fd >= 0) ::close(held.fd);  // releases the flock
    Registry().erase(it);
  } else if (exclusive && held.exclusive == 0 && held.fd >= 0) {
    TryFlock(held.fd, Mode::kShared);  // the remaining holds are readers
  }
}

FolderLock::FolderLock(FolderLock&& other) noexcept
    : dir_(std::move(other.dir_)), key_(std::move(other.key_)) {
  other.key_.clear();
}

FolderLock& FolderLock::operator=(FolderLock&& other) noexcept {
  if (this != &other) {
    FolderLock released(std::move(*this));
    dir_ = std::move(other.dir_);
    key_ = std::move(other.key_);
    other.key_.clear();
  }
  return *this;
}

}  // namespace uwbsar
