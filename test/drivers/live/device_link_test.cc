#include "drivers/live/device_link.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <thread>

#include "drivers/emulators/pty_device.h"
#include "drivers/live/kobuki_driver.h"

namespace uwbsar::live {
namespace {

std::string TempLink(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("uwbsar_link_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

bool WaitFor(const std::function<bool()>& ok, double timeout_s = 5.0) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < end) {
    if (ok()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return ok();
}

TEST(SerialPortTest, MissingDeviceErrorNamesThePath) {
  SerialPort port;
  try {
    port.Open("/dev/uwbsar_no_such_tty", 115200);
    FAIL();
  } catch (const SerialError& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/uwbsar_no_such_tty"), std::string::npos);
  }
  EXPECT_THROW(BaudConstant(12345), SerialError);
}

TEST(DeviceLinkTest, ReconnectsAfterUnplugAndPowerCyclesAfterRepeatedFailures) {
  PtyDevice device(TempLink("kobuki"));
  LiveConfig config;
  FaultLog faults;
  std::atomic<int> samples{0};
  KobukiDriver driver(
      config, &faults, [] { return std::int64_t{0}; }, [&](OdometrySample&&) { ++samples; });
  LinkPolicy policy;
  policy.reconnect_initial_s = 0.01;
  policy.reconnect_max_s = 0.04;
  policy.power_cycle_after_failures = 3;
  std::atomic<int> power_cycles{0};
  DeviceLink link("kobuki", device.link_path(), policy, &driver, &faults, [&] { ++power_cycles; });
  link.Start();
  ASSERT_TRUE(WaitFor([&] { return link.connected(); }));
  KobukiBasicSensorData d;
  for (int k = 0; k < 3; ++k) {
    d.left_encoder = d.right_encoder = static_cast<std::uint16_t>(k);
    device.Write(EncodeKobukiPacket(d));
  }
  ASSERT_TRUE(WaitFor([&] { return samples == 2; }));  // the first packet sets the reference
  device.Unplug();
  ASSERT_TRUE(WaitFor([&] { return power_cycles >= 1; }));
  EXPECT_GE(faults.Count("kobuki: unplugged"), 1);
  EXPECT_GE(faults.Count("kobuki: cannot connect"), 3);
  device.Plug();
  ASSERT_TRUE(WaitFor([&] { return link.connected(); }));
  d.left_encoder = d.right_encoder = 3;
  device.Write(EncodeKobukiPacket(d));
  ASSERT_TRUE(WaitFor([&] { return samples == 3; }));  // odometry continues after the replug
  EXPECT_GE(link.counters().connects.load(), 2);
  link.Stop();
}

TEST(DeviceLinkTest, SilentDeviceIsReportedAndReconnected) {
  PtyDevice device(TempLink("silent"));
  LiveConfig config;
  FaultLog faults;
  KobukiDriver driver(
      config, &faults, [] { return std::int64_t{0}; }, [](OdometrySample&&) {});
  LinkPolicy policy;
  policy.read_timeout_s = 0.1;
  policy.reconnect_initial_s = 0.01;
  DeviceLink link("kobuki", device.link_path(), policy, &driver, &faults);
  link.Start();
  ASSERT_TRUE(WaitFor([&] { return link.counters().connects >= 2; }));
  EXPECT_GE(faults.Count("kobuki: silent"), 1);
  link.Stop();
}

}  // namespace
}  // namespace uwbsar::live
