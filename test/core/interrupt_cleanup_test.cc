// Ctrl-C removes a command's private folder even while another thread is still writing into
// it (a stage being filled when the signal arrives): nothing the writer creates by name
// afterwards lands in a folder that outlives the process.
#include "core/interrupt_cleanup.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

namespace uwbsar {
namespace {

namespace fs = std::filesystem;

/// The number of entries in `dir` (0 when it is not there).
int Entries(const fs::path& dir) {
  std::error_code ec;
  int n = 0;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) ++n;
  return n;
}

TEST(InterruptCleanupTest, AFolderBeingWrittenWhenTheSignalArrivesIsRemoved) {
  const fs::path dir = fs::temp_directory_path() /
                       ("uwbsar_interrupt_" + std::to_string(::getpid())) / ".uwbsar-partial-1";
  for (int round = 0; round < 10; ++round) {
    fs::remove_all(dir.parent_path());
    fs::create_directories(dir);
    const pid_t pid = ::fork();
    if (pid == 0) {
      InstallInterruptCleanup();
      const RemoveOnInterrupt guard(dir.string());
      // A writer that never stops creating files in the folder, as fast as it can.
      std::thread([&dir] {
        for (long i = 0;; ++i) {
          const int fd = ::open((dir / std::to_string(i)).c_str(), O_WRONLY | O_CREAT, 0644);
          if (fd >= 0) ::close(fd);
        }
      }).detach();
      for (;;) ::pause();
    }
    // The signal arrives while the writer is busy (it has written a few hundred files).
    for (int wait = 0; wait < 5000 && Entries(dir) < 300; ++wait) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ::kill(pid, SIGINT);
    int status = 0;
    ::waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << "round " << round;
    EXPECT_EQ(Entries(dir.parent_path()), 0)
        << "round " << round << ": left " << Entries(dir) << " files";
  }
  fs::remove_all(dir.parent_path());
}

}  // namespace
}  // namespace uwbsar
