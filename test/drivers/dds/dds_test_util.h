// Helpers for the drivers/dds tests: a loopback-only DDS configuration on a domain
// of this test process (parallel ctest processes do not hear each other), waiting,
// collecting events, and running the independent Python peer (ros2_peer.py).
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "drivers/dds/dds_config.h"
#include "drivers/dds/dds_events.h"
#include "drivers/dds/participant.h"
#include "drivers/dds/ros2_subscriber.h"

namespace uwbsar::dds::testing {

/// Domain 1..230 derived from the process id: each ctest test is its own process.
inline int TestDomainId() { return 1 + static_cast<int>(::getpid() % 230); }

/// DDS restricted to the loopback interface (unicast discovery), on TestDomainId().
inline DdsConfig LoopbackConfig() {
  DdsConfig config;
  config.domain_id = TestDomainId();
  config.network_interface = "lo";
  return config;
}

/// Polls `done` every 5 ms until it holds or `timeout_s` passes; returns its last value.
inline bool WaitFor(const std::function<bool()>& done, double timeout_s = 10.0) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return done();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

/// Thread-safe record of the events a subscriber reported.
class EventLog {
 public:
  void Add(const DdsEvent& e) {
    std::lock_guard<std::mutex> lock(mutex_);
    events_.push_back(e);
  }
  int Count(DdsEventKind kind) const {
    std::lock_guard<std::mutex> lock(mutex_);
    int n = 0;
    for (const DdsEvent& e : events_) n += e.kind == kind ? 1 : 0;
    return n;
  }
  /// The detail of the first event of `kind`, "" if none.
  std::string Detail(DdsEventKind kind) const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const DdsEvent& e : events_) {
      if (e.kind == kind) return e.detail;
    }
    return "";
  }

 private:
  mutable std::mutex mutex_;
  std::vector<DdsEvent> events_;
};

/// A fixture whose Ros2Subscriber collects everything it delivers.
class CollectingSubscriberTest : public ::testing::Test {
 protected:
  void SubscribeOn(Participant& participant, const DdsConfig& config,
                   const std::vector<std::string>& radar, const std::string& odom) {
    Ros2Subscriber::Callbacks callbacks;
    callbacks.on_radar = [this](RadarMessage&& m) {
      std::lock_guard<std::mutex> lock(mutex_);
      radar_.push_back(std::move(m));
    };
    callbacks.on_odometry = [this](OdometryMessage&& m) {
      std::lock_guard<std::mutex> lock(mutex_);
      odometry_.push_back(std::move(m));
    };
    callbacks.on_event = [this](const DdsEvent& e) { events_.Add(e); };
    subscriber_ = std::make_unique<Ros2Subscriber>(participant, config, radar, odom, callbacks);
  }
  // Before the derived fixture's participants go: the subscriber must not outlive them.
  void TearDown() override { subscriber_.reset(); }
  std::size_t NumRadar() {
    std::lock_guard<std::mutex> lock(mutex_);
    return radar_.size();
  }
  std::size_t NumOdometry() {
    std::lock_guard<std::mutex> lock(mutex_);
    return odometry_.size();
  }

  std::mutex mutex_;
  std::vector<RadarMessage> radar_;
  std::vector<OdometryMessage> odometry_;
  EventLog events_;
  std::unique_ptr<Ros2Subscriber> subscriber_;
};

/// $UWBSAR_VENV/bin/python, or "" when UWBSAR_VENV is unset (`make test` sets it).
inline std::string VenvPython() {
  const char* venv = std::getenv("UWBSAR_VENV");
  if (venv == nullptr || *venv == '\0') return "";
  return std::string(venv) + "/bin/python";
}

/// The shell command running a Python DDS peer `script` (a path from the source root) in
/// `mode` on the test domain, pinned to loopback with the same Cyclone configuration as
/// LoopbackConfig().
inline std::string PythonPeerCommand(const std::string& python, const std::string& script,
                                     const std::string& mode, const std::string& args = "") {
  return "CYCLONEDDS_URI='" + CycloneXmlConfig("lo") + "' " + python + " " UWBSAR_SOURCE_DIR "/" +
         script + " " + mode + " --domain " + std::to_string(TestDomainId()) + " " + args + " 2>&1";
}

/// PythonPeerCommand for test/drivers/dds/ros2_peer.py.
inline std::string PeerCommand(const std::string& python, const std::string& mode,
                               const std::string& args = "") {
  return PythonPeerCommand(python, "test/drivers/dds/ros2_peer.py", mode, args);
}

/// A command running in the background; Finish() waits for it and returns its output.
class BackgroundCommand {
 public:
  explicit BackgroundCommand(const std::string& command) : pipe_(::popen(command.c_str(), "r")) {}
  ~BackgroundCommand() {
    if (pipe_ != nullptr) ::pclose(pipe_);
  }
  bool started() const { return pipe_ != nullptr; }
  /// Reads everything the command prints, then its exit status (-1 if it did not exit).
  std::string Finish(int* exit_status) {
    std::string out;
    char buf[4096];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof(buf), pipe_)) > 0) out.append(buf, n);
    const int status = ::pclose(pipe_);
    pipe_ = nullptr;
    *exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return out;
  }

 private:
  FILE* pipe_;
};

}  // namespace uwbsar::dds::testing
