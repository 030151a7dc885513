// A GPIO chip for tests (drivers/live/gpio.h): it records every level change with its time, so
// that tests can check power and reset sequences without a robot.
#pragma once

#include <chrono>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "drivers/live/gpio.h"

namespace uwbsar::live {

/// A chip with `num_lines` lines that records every level change.
class FakeGpioChip : public GpioChip {
 public:
  struct Event {
    int offset = 0;
    bool high = false;
    std::chrono::steady_clock::time_point time;
  };
  explicit FakeGpioChip(std::string name = "fakechip0", int num_lines = 64)
      : name_(std::move(name)), num_lines_(num_lines) {}
  std::unique_ptr<GpioOutput> RequestOutput(int offset, const std::string& role,
                                            bool initial) override;
  const std::string& name() const override { return name_; }
  std::vector<Event> events() const;
  void Record(int offset, bool high);

 private:
  std::string name_;
  int num_lines_;
  mutable std::mutex mutex_;
  std::set<int> requested_;
  std::vector<Event> events_;
};

}  // namespace uwbsar::live
