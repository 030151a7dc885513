#include "test/drivers/live/fake_gpio_chip.h"

namespace uwbsar::live {
namespace {

class FakeOutput : public GpioOutput {
 public:
  FakeOutput(FakeGpioChip* chip, int offset) : chip_(chip), offset_(offset) {}
  void Set(bool high) override { chip_->Record(offset_, high); }

 private:
  FakeGpioChip* chip_;
  int offset_;
};

}  // namespace

std::unique_ptr<GpioOutput> FakeGpioChip::RequestOutput(int offset, const std::string& role,
                                                        bool initial) {
  const std::string what =
      "GPIO chip '" + name_ + "' line " + std::to_string(offset) + " (" + role + ")";
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (offset < 0 || offset >= num_lines_) {
      throw GpioError(what + ": no such line (the chip has " + std::to_string(num_lines_) +
                      " lines)");
    }
    if (!requested_.insert(offset).second) throw GpioError(what + ": line is busy");
  }
  Record(offset, initial);
  return std::make_unique<FakeOutput>(this, offset);
}

std::vector<FakeGpioChip::Event> FakeGpioChip::events() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return events_;
}

void FakeGpioChip::Record(int offset, bool high) {
  std::lock_guard<std::mutex> lock(mutex_);
  events_.push_back({offset, high, std::chrono::steady_clock::now()});
}

}  // namespace uwbsar::live
