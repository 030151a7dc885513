// GPIO output lines behind a small interface: the robot's libgpiod (v1 C++ API,
// gpiod::chip + line.request) backend; the tests' chip that records every change is
// test/drivers/live/fake_gpio_chip.h. v2 of libgpiod differs; only gpio.cc knows the API.
#pragma once

#include <memory>
#include <string>

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

}  // namespace uwbsar::live
