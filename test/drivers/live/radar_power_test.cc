#include "drivers/live/radar_power.h"

#include <gtest/gtest.h>

#include "test/drivers/live/fake_gpio_chip.h"

namespace uwbsar::live {
namespace {

LiveConfig WiredConfig() {
  LiveConfig c;
  c.gpio_chip = "fakechip0";
  c.radar_power_lines = {17, 27};
  c.radar_reset_lines = {22, 23};
  c.status_led_line = 24;
  c.reset_pulse_s = 0.02;
  c.power_settle_s = 0.01;
  c.power_off_s = 0.03;
  return c;
}

double Seconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

TEST(RadarPowerTest, StartUpPowersThenPulsesResetLowForThePulseWidth) {
  auto chip = std::make_unique<FakeGpioChip>();
  FakeGpioChip* fake = chip.get();
  std::vector<std::string> events;
  RadarPower power(std::move(chip), WiredConfig(),
                   [&](const std::string& e) { events.push_back(e); });
  // Requested: power off, reset released (high), LED off.
  auto requested = fake->events();
  ASSERT_EQ(requested.size(), 5u);
  EXPECT_EQ(requested[0].offset, 17);
  EXPECT_FALSE(requested[0].high);
  EXPECT_TRUE(requested[2].high);  // reset line 22 starts released
  power.StartUp();
  const auto e = fake->events();
  // After the requests: power 17 high, 27 high, then reset 22 low/high, 23 low/high.
  ASSERT_EQ(e.size(), 5u + 6u);
  EXPECT_EQ(e[5].offset, 17);
  EXPECT_TRUE(e[5].high);
  EXPECT_EQ(e[6].offset, 27);
  EXPECT_TRUE(e[6].high);
  EXPECT_EQ(e[7].offset, 22);
  EXPECT_FALSE(e[7].high);
  EXPECT_EQ(e[8].offset, 22);
  EXPECT_TRUE(e[8].high);
  EXPECT_GE(Seconds(e[7].time - e[6].time), 0.01);  // settle after power-on
  EXPECT_GE(Seconds(e[8].time - e[7].time), 0.02);  // reset pulse width
  EXPECT_EQ(e[9].offset, 23);
  EXPECT_EQ(events.front(), "radar 0 power high");
}

TEST(RadarPowerTest, PowerCycleHoldsPowerOffThenResetsOnlyThatRadar) {
  auto chip = std::make_unique<FakeGpioChip>();
  FakeGpioChip* fake = chip.get();
  RadarPower power(std::move(chip), WiredConfig());
  const std::size_t before = fake->events().size();
  power.PowerCycle(1);
  const auto all = fake->events();
  const std::vector<FakeGpioChip::Event> e(all.begin() + static_cast<std::ptrdiff_t>(before),
                                           all.end());
  ASSERT_EQ(e.size(), 4u);
  EXPECT_EQ(e[0].offset, 27);
  EXPECT_FALSE(e[0].high);
  EXPECT_EQ(e[1].offset, 27);
  EXPECT_TRUE(e[1].high);
  EXPECT_GE(Seconds(e[1].time - e[0].time), 0.03);
  EXPECT_EQ(e[2].offset, 23);
  EXPECT_FALSE(e[2].high);
  EXPECT_EQ(e[3].offset, 23);
  EXPECT_TRUE(e[3].high);
}

TEST(RadarPowerTest, MissingLineErrorNamesChipLineAndRole) {
  LiveConfig c = WiredConfig();
  c.radar_reset_lines = {22, 99};
  try {
    RadarPower power(std::make_unique<FakeGpioChip>("fakechip0", 64), c);
    FAIL() << "expected GpioError";
  } catch (const GpioError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'fakechip0'"), std::string::npos) << what;
    EXPECT_NE(what.find("line 99"), std::string::npos) << what;
    EXPECT_NE(what.find("radar 1 reset"), std::string::npos) << what;
  }
}

TEST(RadarPowerTest, MissingChipErrorNamesTheChipAndTheNoGpioSetting) {
  try {
    OpenGpiodChip("uwbsar_no_such_chip");
    FAIL() << "expected GpioError";
  } catch (const GpioError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'uwbsar_no_such_chip'"), std::string::npos) << what;
    EXPECT_NE(what.find("live.gpio_chip"), std::string::npos) << what;
  }
}

TEST(RadarPowerTest, NoGpioConfigurationIsANoOp) {
  LiveConfig c;  // defaults: gpio_chip ""
  EXPECT_EQ(OpenConfiguredChip(c), nullptr);
  RadarPower power(nullptr, c);
  EXPECT_FALSE(power.has_gpio());
  EXPECT_FALSE(power.can_power_cycle(0));
  power.StartUp();
  power.PowerCycle(0);
  power.SetStatusLed(true);
}

}  // namespace
}  // namespace uwbsar::live
