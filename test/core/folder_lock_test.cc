// The folder lock: a second process is refused naming the holder, a writer or a reader; a lock
// file that is not a plain file uwbsar can open (a link, to a file or to nothing, a folder, a
// FIFO) is refused without being followed, truncated or waited on.
#include "core/folder_lock.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/errors.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;

fs::path FreshFolder(const std::string& tag) {
  const fs::path dir =
      fs::temp_directory_path() / ("uwbsar_lock_" + tag + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string TextOf(const fs::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// Tries to lock `dir` in a child process: 0 when granted, 3 when refused (the message goes
/// to `message`).
int LockInChild(const fs::path& dir, FolderLock::Mode mode, std::string* message) {
  int fds[2];
  if (::pipe(fds) != 0) return -1;
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    try {
      const FolderLock lock(dir.string(), mode);
      ::_exit(0);
    } catch (const InputError& e) {
      const std::string text = e.what();
      if (::write(fds[1], text.data(), text.size()) < 0) ::_exit(4);
      ::_exit(3);
    }
  }
  ::close(fds[1]);
  char buf[512];
  message->clear();
  for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) message->append(buf, n);
  ::close(fds[0]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(FolderLockTest, ASecondProcessIsRefusedNamingTheHolder) {
  const fs::path dir = FreshFolder("lock");
  std::string message;
  {
    const FolderLock lock(dir.string(), FolderLock::Mode::kExclusive);
    const FolderLock again(dir.string(), FolderLock::Mode::kShared);  // same process: granted
    EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kShared, &message), 3);
    EXPECT_NE(message.find("in use by another uwbsar process (pid " + std::to_string(::getpid())),
              std::string::npos)
        << message;
    EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kExclusive, &message), 3);
  }
  {
    const FolderLock reader(dir.string(), FolderLock::Mode::kShared);
    EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kShared, &message), 0);  // readers share
    EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kExclusive, &message), 3);
    {
      const FolderLock writer(dir.string(), FolderLock::Mode::kExclusive);  // upgraded
      EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kShared, &message), 3);
    }
    EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kShared, &message), 0);  // back to shared
  }
  EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kExclusive, &message), 0);  // all released
  fs::remove_all(dir);
}

TEST(FolderLockTest, AReaderIsNamedAsTheHolder) {
  const fs::path dir = FreshFolder("reader");
  std::string message;
  // An earlier writer, gone: its line in the lock file names no one now.
  ASSERT_EQ(LockInChild(dir, FolderLock::Mode::kExclusive, &message), 0);
  const FolderLock reader(dir.string(), FolderLock::Mode::kShared);
  EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kShared, &message), 0);  // a second reader
  EXPECT_EQ(LockInChild(dir, FolderLock::Mode::kExclusive, &message), 3);
  EXPECT_NE(message.find("in use by another uwbsar process (pid " + std::to_string(::getpid())),
            std::string::npos)
      << message;
  fs::remove_all(dir);
}

TEST(FolderLockTest, ALockFileThatIsNotAPlainFileIsRefusedAndNotFollowed) {
  const fs::path dir = FreshFolder("kinds");
  const fs::path lock = dir / kFolderLockName, target = dir / "session.uwbsar";
  std::ofstream(target) << "the saved map";
  const auto expect_refused = [&](const std::string& kind) {
    for (const auto mode : {FolderLock::Mode::kExclusive, FolderLock::Mode::kShared}) {
      try {
        const FolderLock held(dir.string(), mode);
        ADD_FAILURE() << kind << ": granted";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(lock.string()), std::string::npos) << e.what();
      }
    }
    EXPECT_EQ(TextOf(target), "the saved map") << kind;
    fs::remove_all(lock);
  };
  fs::create_symlink("session.uwbsar", lock);
  expect_refused("a link to the session");
  fs::create_symlink(dir / "nothing", lock);
  expect_refused("a link to nothing");
  EXPECT_FALSE(fs::exists(dir / "nothing"));
  fs::create_directory(lock);
  expect_refused("a folder");
  ASSERT_EQ(::mkfifo(lock.c_str(), 0644), 0);
  expect_refused("a FIFO");
  if (::geteuid() != 0) {  // root opens a file of mode 000
    std::ofstream(lock) << "";
    fs::permissions(lock, fs::perms::none);
    expect_refused("unreadable");
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace uwbsar
