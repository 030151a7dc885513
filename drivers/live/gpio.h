// GPIO output lines behind a small interface: the robot's libgpiod (v1 C++ API,
// gpiod::chip + line.request) backend, and a fake that records every change with
// its time so tests can check sequences. v2 of libgpiod differs; only gpio.cc
// knows the API.
#pragma once

#include <chrono>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.h"

namespace uwbsar::live {

/// A GPIO chip or line that cannot be used; what() names the chip, the line and its role.
/// An InputError: the configuration does not match the machine (CLI exit code 3).
class GpioError : public InputError {
 public:
  using InputError::InputError;
};

class GpioOutput {
 public:
  virtual ~GpioOutput() = default;
  virtual void Set(bool high) = 0;
};

class GpioChip {
 public:
  virtual ~GpioChip() = default;
  /// Requests line `offset` as an output driven to `initial`. `role` (e.g. "radar 0 power")
  /// is the consumer label and appears in errors. Throws GpioError.
  virtual std::unique_ptr<GpioOutput> RequestOutput(int offset, const std::string& role,
                                                    bool initial) = 0;
  virtual const std::string& name() const = 0;
};

/// Opens a chip by name, path or number through libgpiod. Throws GpioError naming it.
std::unique_ptr<GpioChip> OpenGpiodChip(const std::string& name);

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
