// The recording layer after a crash: a recording process killed with SIGKILL leaves
// a `<dir>.partial` bag whose storage file opens and holds every message written up to
// the last flush, which the live recorder makes at least every second. For both
// storages: sqlite3 commits on flush; an MCAP file cut short has no footer, and the
// reader recovers it by a linear scan up to the last chunk the flush closed.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "drivers/rosbag/bag_reader.h"
#include "drivers/rosbag/bag_writer.h"

namespace uwbsar::live {
namespace {

namespace fs = std::filesystem;

// The child writes one message per millisecond stamped with the wall clock, flushing
// every 0.5 s, and reports nothing: the parent reads what survived.
void RecordUntilKilled(const std::string& dir, const std::string& storage) {
  rosbag::BagWriterOptions options;
  options.storage = storage;
  options.flush_period_s = 0.5;
  rosbag::BagWriter writer(dir, options);
  const int topic = writer.AddTopic("/UWBradar0/readings", "std_msgs/msg/Float32MultiArray");
  writer.Flush();
  rosbag::Float32MultiArray msg;
  msg.data.assign(1000, 0.5f);
  while (true) {
    const auto now = std::chrono::system_clock::now().time_since_epoch();
    writer.WriteMessage(topic, std::chrono::duration_cast<std::chrono::nanoseconds>(now).count(),
                        msg);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

void KillMidRecordingAndCheck(const std::string& storage, const std::string& extension) {
  const fs::path dir =
      fs::temp_directory_path() / ("uwbsar_crash_" + storage + "_" + std::to_string(::getpid()));
  fs::remove_all(dir.string() + ".partial");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    RecordUntilKilled(dir.string(), storage);
    ::_exit(0);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(2300));
  const auto kill_time = std::chrono::system_clock::now().time_since_epoch();
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  const std::int64_t kill_ns =
      std::chrono::duration_cast<std::chrono::nanoseconds>(kill_time).count();
  const fs::path file =
      fs::path(dir.string() + ".partial") / (dir.filename().string() + "_0." + extension);
  ASSERT_TRUE(fs::exists(file)) << file;
  rosbag::BagReader reader(file.string());
  rosbag::BagMessage msg;
  std::int64_t last = 0;
  long long n = 0;
  while (reader.Next(&msg)) {
    last = msg.log_time_ns;
    ++n;
  }
  EXPECT_GT(n, 500);
  EXPECT_GT(last, kill_ns - 1000000000LL) << "more than 1 s lost before the kill";
  fs::remove_all(dir.string() + ".partial");
}

struct Storage {
  std::string id, extension;
};

class RecordingCrashTest : public ::testing::TestWithParam<Storage> {};

TEST_P(RecordingCrashTest, RecordingKilledWithSigkillHoldsEverythingUpToOneSecondBefore) {
  KillMidRecordingAndCheck(GetParam().id, GetParam().extension);
}

INSTANTIATE_TEST_SUITE_P(Storages, RecordingCrashTest,
                         ::testing::Values(Storage{"sqlite3", "db3"}, Storage{"mcap", "mcap"}),
                         [](const auto& p) { return p.param.id; });

}  // namespace
}  // namespace uwbsar::live
