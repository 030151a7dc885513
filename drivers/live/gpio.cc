#include "drivers/live/gpio.h"

#include <gpiod.hpp>
#include <system_error>

namespace uwbsar::live {
namespace {

class GpiodOutput : public GpioOutput {
 public:
  GpiodOutput(gpiod::line line, std::string what)
      : line_(std::move(line)), what_(std::move(what)) {}
  ~GpiodOutput() override {
    try {
      line_.release();
    } catch (const std::exception&) {
    }
  }
  void Set(bool high) override {
    try {
      line_.set_value(high ? 1 : 0);
    } catch (const std::exception& e) {
      throw GpioError(what_ + ": cannot set: " + e.what());
    }
  }

 private:
  gpiod::line line_;
  std::string what_;
};

class GpiodChip : public GpioChip {
 public:
  explicit GpiodChip(const std::string& name) : name_(name) {
    try {
      chip_.open(name, gpiod::chip::OPEN_LOOKUP);
    } catch (const std::exception& e) {
      throw GpioError("GPIO chip '" + name + "': cannot open: " + e.what() +
                      " (set live.gpio_chip to \"\" to run without GPIO)");
    }
    if (!chip_) {
      throw GpioError("GPIO chip '" + name +
                      "': no such chip (set live.gpio_chip to \"\" to "
                      "run without GPIO)");
    }
  }
  std::unique_ptr<GpioOutput> RequestOutput(int offset, const std::string& role,
                                            bool initial) override {
    const std::string what =
        "GPIO chip '" + name_ + "' line " + std::to_string(offset) + " (" + role + ")";
    if (offset < 0 || static_cast<unsigned>(offset) >= chip_.num_lines()) {
      throw GpioError(what + ": no such line (the chip has " + std::to_string(chip_.num_lines()) +
                      " lines)");
    }
    try {
      gpiod::line line = chip_.get_line(static_cast<unsigned>(offset));
      line.request({"uwbsar " + role, gpiod::line_request::DIRECTION_OUTPUT, 0}, initial ? 1 : 0);
      return std::make_unique<GpiodOutput>(std::move(line), what);
    } catch (const std::exception& e) {
      throw GpioError(what + ": cannot request as output: " + e.what());
    }
  }
  const std::string& name() const override { return name_; }

 private:
  std::string name_;
  gpiod::chip chip_;
};

}  // namespace

std::unique_ptr<GpioChip> OpenGpiodChip(const std::string& name) {
  return std::make_unique<GpiodChip>(name);
}

}  // namespace uwbsar::live
