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

void WriteHolder(int fd) {
  const std::string text = HolderText();
  if (::ftruncate(fd, 0) != 0) return;  // the text is a courtesy: the flock is the lock
  if (::pwrite(fd, text.data(), text.size(), 0) < 0) return;
}

/// The holder named in the lock file, when that process still exists.
std::string ReadHolder(const std::string& lock_path) {
  std::ifstream in(lock_path);
  std::string line;
  std::getline(in, line);
  long pid = 0;
  if (std::sscanf(line.c_str(), "pid %ld:", &pid) != 1 || pid <= 0) return {};
  if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) return {};
  return line;
}

[[noreturn]] void RefuseHeld(const std::string& dir, const std::string& lock_path) {
  const std::string holder = ReadHolder(lock_path);
  throw InputError(dir + ": in use by another uwbsar process (" +
                   (holder.empty() ? std::string("holder unknown") : holder) +
                   "); run again when it has finished");
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
    held.fd = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (held.fd < 0) held.fd = ::open(lock_path.c_str(), O_RDONLY | O_CLOEXEC);
    if (held.fd >= 0 && !TryFlock(held.fd, mode)) {
      ::close(held.fd);
      RefuseHeld(dir, lock_path);
    }
    if (held.fd >= 0 && mode == Mode::kExclusive) WriteHolder(held.fd);
    it = Registry().emplace(canonical.string(), held).first;
  } else if (mode == Mode::kExclusive && it->second.exclusive == 0 && it->second.fd >= 0) {
    // Upgrade in place. flock(2) drops the shared lock before it tries the exclusive one, so
    // on refusal the shared lock is taken again for the holds that remain.
    if (!TryFlock(it->second.fd, Mode::kExclusive)) {
      TryFlock(it->second.fd, Mode::kShared);
      RefuseHeld(dir, lock_path);
    }
    WriteHolder(it->second.fd);
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
