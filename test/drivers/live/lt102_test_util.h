// An LT102 emulator on a pseudo-terminal driven by its own thread for the driver tests:
// it answers commands every millisecond and acquires a ramp frame (sample k = k / 2000,
// except sample 0, which counts the frames so that no two are alike, as noise makes a real
// radar's) at `period_ms` while started.
#pragma once

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "drivers/emulators/lt102_emulator.h"
#include "drivers/live/thread_priority.h"

namespace uwbsar::live {

inline std::string Lt102TempLink(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("uwbsar_lt102_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

inline bool WaitUntil(const std::function<bool()>& ok, double timeout_s = 5.0) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < end) {
    if (ok()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return ok();
}

/// The ramp the emulated radar acquires: sample k at range k * bin.
inline std::vector<float> Lt102Ramp() {
  std::vector<float> v(1200);
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = static_cast<float>(k) / 2000.0f;
  return v;
}

class EmulatedLt102 {
 public:
  /// `stall_every` > 0: every n-th frame is acquired a period late, together with the next
  /// (as an emulator whose thread was held up: that frame is overwritten unasked).
  /// `priority` > 0: the emulator's thread asks for SCHED_FIFO (hardware does not share the
  /// host's CPU); realtime() says whether it got it.
  explicit EmulatedLt102(const std::string& name, Lt102EmulatorOptions options = {},
                         int period_ms = 10, int stall_every = 0, int priority = 0)
      : emulator_(Lt102TempLink(name), options),
        period_ms_(period_ms),
        stall_every_(stall_every),
        priority_(priority),
        thread_([this] { Loop(); }) {}
  ~EmulatedLt102() {
    stop_ = true;
    thread_.join();
  }
  const std::string& path() const { return emulator_.link_path(); }
  std::vector<std::uint8_t> received() const { return emulator_.received(); }
  Lt102EmulatorCounts counts() const { return emulator_.counts(); }
  bool started() const { return started_; }
  bool realtime() const { return realtime_; }
  void SetPlugged(bool plugged) {
    want_plugged_ = plugged;
    WaitUntil([&] { return plugged_ == plugged; });
  }

 private:
  void Loop() {
    realtime_ = priority_ > 0 && SetCurrentThreadRealtime(priority_).empty();
    std::vector<float> ramp = Lt102Ramp();
    int frame = 0;
    auto next = std::chrono::steady_clock::now();
    while (!stop_) {
      if (want_plugged_ != emulator_.plugged()) {
        want_plugged_ ? emulator_.Plug() : emulator_.Unplug();
      }
      plugged_ = emulator_.plugged();
      emulator_.Serve();
      started_ = emulator_.started();
      if (std::chrono::steady_clock::now() >= next) {
        ramp[0] = static_cast<float>(++frame % 1000) / 2000.0f;
        next += std::chrono::milliseconds(period_ms_);
        if (stall_every_ > 0 && frame % stall_every_ == 0 && !stalled_) {
          stalled_ = true;  // this frame comes with the next one
          --frame;
          continue;
        }
        if (stalled_) {
          emulator_.Acquire(ramp, 0.0);
          ramp[0] = static_cast<float>(++frame % 1000) / 2000.0f;
          stalled_ = false;
        }
        emulator_.Acquire(ramp, 0.0);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }

  Lt102Emulator emulator_;
  int period_ms_;
  int stall_every_;
  int priority_;
  bool stalled_ = false;
  std::atomic<bool> realtime_{false};
  std::atomic<bool> stop_{false}, want_plugged_{true}, plugged_{true}, started_{false};
  std::thread thread_;
};

}  // namespace uwbsar::live
