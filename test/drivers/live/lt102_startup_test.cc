// The LT102 start-up sequence against the emulated module: the exact bytes of the default
// sequence, every request's payload within the vendor table's values (a query only where
// the table defines a query value), and for every step a missing answer (retried once, then the
// open fails naming the command) and a wrong echo (a configuration error naming the command and
// both values, or the actual value taken where the radar may adjust it); CRC detection and the
// carrier check.
#include "drivers/live/lt102_startup.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "lt102_test_util.h"
#include "slam/app_config.h"

namespace uwbsar::live {
namespace {

Config TestConfig() {
  Config config;
  config.live.lt102.answer_timeout_s = 0.1;  // missing answers are waited for quickly
  return config;
}

struct StartupRun {
  Lt102Setup setup;
  Lt102ExchangeCounts counts;
  std::string error;  ///< what() of the exception, if any
  bool config_error = false;
};

StartupRun Startup(const EmulatedLt102& radar, const Config& config, FaultLog* faults) {
  StartupRun run;
  SerialPort port;
  port.Open(radar.path(), 115200);
  Lt102Exchange exchange("radar left", config.live.lt102, faults);
  try {
    run.setup = RunLt102Startup(port, exchange, config, "radar left");
  } catch (const Lt102ConfigError& e) {
    run.error = e.what();
    run.config_error = true;
  } catch (const SerialError& e) {
    run.error = e.what();
  }
  run.counts = exchange.counts();
  return run;
}

TEST(Lt102StartupTest, DefaultSequenceSendsExactlyTheseBytes) {
  // Hand-written: 0xFF, command, payload (0xFF/0x00/0x80 escaped as 0x80 0xFE/0x01/0x81), 0x00.
  const std::vector<std::uint8_t> expected = {
      0xFF, 0x01, 0x00,              // firmware version
      0xFF, 0x6F, 0x00,              // 'o' stop
      0xFF, 0x65, 0x80, 0x01, 0x00,  // 'e' 0: raw
      0xFF, 0x62, 0x80, 0x01, 0x00,  // 'b' 0: output last reading
      0xFF, 0x24, 0x80, 0x01, 0x00,  // '$' 0: channel 0
      0xFF, 0x0A, 0x01, 0x00,        // 0x0A 1: Q15
      0xFF, 0x78, 0x80, 0x01, 0x80, 0x01, 0x80, 0x01, 0x80, 0x01, 0x00,  // 'x' 0.0f
      0xFF, 0x58, 0xA4, 0x70, 0xCD, 0x40, 0x00,                          // 'X' 6.42f
      0xFF, 0x30, 0x80, 0xFE, 0x80, 0xFE, 0x80, 0xFE, 0x80, 0xFE, 0x00,  // '0' query (i32 -1)
      0xFF, 0x66, 0x64, 0x80, 0x01, 0x00,                                // 'f' 100 (u16)
      0xFF, 0x0B, 0x80, 0xFE, 0x80, 0xFE, 0x00,  // 0x0B query (0xFFFF): carrier
      0xFF, 0x0C, 0x80, 0xFE, 0x80, 0xFE, 0x00,  // 0x0C query: bandwidth
      0xFF, 0x70, 0x80, 0xFE, 0x00,              // 'p' query: TX power
      0xFF, 0x05, 0x80, 0xFE, 0x80, 0xFE, 0x00,  // 0x05 query: ADC frequency
      0xFF, 0x73, 0x00,                          // 's' start
  };
  EmulatedLt102 radar("transcript");
  FaultLog faults;
  const StartupRun run = Startup(radar, TestConfig(), &faults);
  ASSERT_TRUE(run.error.empty()) << run.error;
  EXPECT_EQ(radar.received(), expected);
  EXPECT_TRUE(WaitUntil([&] { return radar.started(); }));
  EXPECT_FALSE(run.setup.crc);
  EXPECT_EQ(run.setup.version.hardware, 102);
  EXPECT_EQ(run.setup.samples_per_scan, 1000);
  EXPECT_DOUBLE_EQ(run.setup.range_min_m, 0.0);
  EXPECT_NEAR(run.setup.range_max_m, 999 * 299792458.0 / (2 * 23.328e9), 1e-6);
  EXPECT_EQ(run.setup.frame_rate_fps, 100);
  EXPECT_EQ(run.setup.output, 0);
  EXPECT_DOUBLE_EQ(run.setup.offset_m, 0.0);
  EXPECT_EQ(run.setup.carrier_mhz, 7290);
  EXPECT_EQ(run.setup.bandwidth_mhz, 1400);
  EXPECT_EQ(run.setup.adc_frequency, 23328);
  EXPECT_EQ(run.counts.requests, 15);
  EXPECT_EQ(run.counts.retries, 0);
}

/// The request payloads the vendor table (the command table of ARIA Sensing's public toolbox,
/// docs/live.md) defines for each command the start-up may send; a command missing here may
/// not be sent at all. Query values (0xFF, 0xFFFF, i32 -1) appear only where the table gives
/// one.
bool AllowedByTheVendorTable(std::uint8_t code, const std::vector<std::uint8_t>& p,
                             std::string* why) {
  auto u8_in = [&](int lo, int hi, bool query) {
    return p.size() == 1 && ((p[0] >= lo && p[0] <= hi) || (query && p[0] == 0xFF));
  };
  auto u16 = [&] { return p.size() == 2 ? p[0] | (p[1] << 8) : -1; };
  auto f32_or_query = [&] {
    if (p.size() != 4) return false;
    if (p == std::vector<std::uint8_t>(4, 0xFF)) return true;  // i32 -1
    float f;
    std::memcpy(&f, p.data(), 4);
    return std::isfinite(f) && f >= 0.0f;
  };
  bool ok = false;
  switch (code) {
    case lt102::kVersion:
    case lt102::kStop:
    case lt102::kStart:
      ok = p.empty();
      break;
    case lt102::kProcessing:  // 0 raw ... 4 targets; no query value
      ok = u8_in(0, 4, false);
      break;
    case lt102::kOutput:  // 0 last reading, 1 filtered, 2 evaluated; 0xFF query
      ok = u8_in(0, 2, true);
      break;
    case lt102::kChannel:  // 0-3 one, 4 combined, 5 all; 0xFF query
      ok = u8_in(0, 5, true);
      break;
    case lt102::kFormat:  // 0 Q7 ... 4 F16; 0xFF query
      ok = u8_in(0, 4, true);
      break;
    case lt102::kTxPower:  // 0-7; 0xFF query
      ok = u8_in(0, 7, true);
      break;
    case lt102::kRangeMin:
    case lt102::kRangeMax:
    case lt102::kOffset:
      ok = f32_or_query();
      break;
    case lt102::kFrameRate:  // u16 fps, 0xFFFF query
      ok = u16() >= 1;
      break;
    case lt102::kCarrier:
    case lt102::kBandwidth:
      ok = u16() >= 0;
      break;
    case lt102::kAdcFrequency:  // u16 0xFFFF only
      ok = u16() == 0xFFFF;
      break;
    default:  // e.g. `v` (no query value; a setting we do not make) or `q` (undocumented)
      ok = false;
  }
  if (!ok) {
    *why = Lt102CommandLabel(code) + " with a " + std::to_string(p.size()) +
           "-byte payload outside the vendor table";
  }
  return ok;
}

TEST(Lt102StartupTest, EveryRequestPayloadIsOneTheVendorTableDefines) {
  for (const bool crc : {false, true}) {
    Lt102EmulatorOptions options;
    options.crc = crc;
    EmulatedLt102 radar(crc ? "allowed_crc" : "allowed", options);
    FaultLog faults;
    const StartupRun run = Startup(radar, TestConfig(), &faults);
    ASSERT_TRUE(run.error.empty()) << run.error;
    std::vector<Lt102Frame> frames;
    Lt102FrameDecoder decoder;
    const std::vector<std::uint8_t> bytes = radar.received();
    decoder.Push(bytes.data(), bytes.size(), &frames);
    ASSERT_EQ(frames.size(), 15u);
    for (std::size_t i = 0; i < frames.size(); ++i) {
      Lt102Frame f = frames[i];
      if (crc && i > 0) f.payload.pop_back();  // after the version answer, requests carry one
      std::string why;
      EXPECT_TRUE(AllowedByTheVendorTable(f.code, f.payload, &why))
          << "request " << i << ": " << why;
    }
  }
  // And the table itself: a query is encoded only for commands with a query value.
  for (const Lt102Command& c : Lt102Commands()) {
    if (c.code == lt102::kPrfDivider || c.code == lt102::kDecimation ||
        c.code == lt102::kProcessing) {
      EXPECT_FALSE(c.queryable) << c.name;
    }
  }
}

TEST(Lt102StartupTest, AnActualFrameRateOtherThanAskedIsTakenAndLogged) {
  Lt102EmulatorOptions options;
  options.actual_frame_rate_fps = 50;
  EmulatedLt102 radar("actual_rate", options);
  FaultLog faults;
  const StartupRun run = Startup(radar, TestConfig(), &faults);
  ASSERT_TRUE(run.error.empty()) << run.error;
  EXPECT_EQ(run.setup.frame_rate_fps, 50);
  EXPECT_EQ(run.setup.frame_rate_requested_fps, 100);
  EXPECT_NE(run.setup.Describe().find("frame rate 50 fps (100 asked)"), std::string::npos)
      << run.setup.Describe();
  EXPECT_TRUE(WaitUntil([&] { return radar.started(); }));
}

class Lt102StartupStepTest : public ::testing::TestWithParam<int> {};

TEST_P(Lt102StartupStepTest, AMissingAnswerIsRetriedOnceAndTwiceFailsTheOpenNamingTheCommand) {
  const auto code = static_cast<std::uint8_t>(GetParam());
  const std::string label = Lt102CommandLabel(code);
  for (const int times : {1, 2}) {
    Lt102EmulatorOptions options;
    options.missing_answer_code = code;
    options.missing_answer_times = times;
    EmulatedLt102 radar("missing_" + std::to_string(code) + "_" + std::to_string(times), options);
    FaultLog faults;
    const StartupRun run = Startup(radar, TestConfig(), &faults);
    std::printf("step %s, %d missing: %s\n", label.c_str(), times,
                run.error.empty() ? "started after a retry" : run.error.c_str());
    EXPECT_EQ(faults.Count("radar left: missing answers"), times);
    EXPECT_EQ(run.counts.retries, 1);
    if (times == 1) {
      EXPECT_TRUE(run.error.empty()) << run.error;
      EXPECT_TRUE(WaitUntil([&] { return radar.started(); }));
    } else {
      EXPECT_FALSE(run.config_error);
      EXPECT_NE(run.error.find("no answer to " + label), std::string::npos) << run.error;
      EXPECT_NE(run.error.find("after a resync and one retry"), std::string::npos);
      EXPECT_EQ(run.error.find('\n'), std::string::npos);
      EXPECT_FALSE(radar.started());
    }
  }
}

TEST_P(Lt102StartupStepTest, AWrongEchoIsAConfigurationErrorOrTheActualValue) {
  const auto code = static_cast<std::uint8_t>(GetParam());
  Lt102EmulatorOptions options;
  options.wrong_echo_code = code;
  EmulatedLt102 radar("echo_" + std::to_string(code), options);
  FaultLog faults;
  const StartupRun run = Startup(radar, TestConfig(), &faults);
  std::printf("step %s, wrong echo: %s\n", Lt102CommandLabel(code).c_str(),
              run.error.empty() ? run.setup.Describe().c_str() : run.error.c_str());
  const double bin_m = 299792458.0 / (2 * 23.328e9);
  switch (code) {
    case lt102::kProcessing:
    case lt102::kOutput:
    case lt102::kChannel:
    case lt102::kFormat: {
      ASSERT_TRUE(run.config_error) << run.error;
      const std::string sent = code == lt102::kFormat ? "1" : "0";
      const std::string echoed = code == lt102::kFormat ? "2" : "1";
      EXPECT_EQ(run.error, "radar left: configuration error: " + Lt102CommandLabel(code) +
                               " sent " + sent + ", the radar echoed " + echoed);
      EXPECT_FALSE(radar.started());
      break;
    }
    case lt102::kRangeMin:  // the actual value is taken: sample 0 one bin out, one sample less
      ASSERT_TRUE(run.error.empty()) << run.error;
      EXPECT_NEAR(run.setup.range_min_m, bin_m, 1e-6);
      EXPECT_EQ(run.setup.samples_per_scan, 999);
      break;
    case lt102::kRangeMax:
      ASSERT_TRUE(run.error.empty()) << run.error;
      EXPECT_EQ(run.setup.samples_per_scan, 1001);
      break;
    case lt102::kCarrier:  // 7291 MHz: within 1 % of pulse.center_frequency_hz
      ASSERT_TRUE(run.error.empty()) << run.error;
      EXPECT_EQ(run.setup.carrier_mhz, 7291);
      break;
    case lt102::kBandwidth:
      EXPECT_EQ(run.setup.bandwidth_mhz, 1401);
      break;
    case lt102::kFrameRate:  // the actual rate: taken, it paces the polling
      ASSERT_TRUE(run.error.empty()) << run.error;
      EXPECT_EQ(run.setup.frame_rate_fps, 101);
      break;
    case lt102::kOffset:  // queried, logged
      ASSERT_TRUE(run.error.empty()) << run.error;
      EXPECT_NEAR(run.setup.offset_m, bin_m, 1e-6);
      break;
    case lt102::kTxPower:
      EXPECT_EQ(run.setup.tx_power, 8);
      break;
    case lt102::kAdcFrequency:
      EXPECT_EQ(run.setup.adc_frequency, 23329);
      break;
    default:  // version, stop, start: no value to echo
      EXPECT_TRUE(run.error.empty()) << run.error;
      EXPECT_TRUE(WaitUntil([&] { return radar.started(); }));
      break;
  }
}

std::vector<int> StartupCodes() {
  std::vector<int> codes;
  for (const Lt102Request& r : Lt102StartupRequests(Lt102Config{})) codes.push_back(r.code);
  return codes;
}

INSTANTIATE_TEST_SUITE_P(EveryStep, Lt102StartupStepTest, ::testing::ValuesIn(StartupCodes()),
                         [](const ::testing::TestParamInfo<int>& info) {
                           char name[16];
                           std::snprintf(name, sizeof(name), "code_0x%02X", info.param);
                           return std::string(name);
                         });

TEST(Lt102StartupTest, AnAnswerStartingWithTheWrongByteIsResyncedAndRetried) {
  Lt102EmulatorOptions options;
  options.wrong_code_code = lt102::kStart;  // 's' answered 'R' once, then 'r'
  EmulatedLt102 radar("wrong_code", options);
  FaultLog faults;
  const StartupRun run = Startup(radar, TestConfig(), &faults);
  ASSERT_TRUE(run.error.empty()) << run.error;
  EXPECT_EQ(run.counts.wrong_answers, 1);
  EXPECT_EQ(run.counts.retries, 1);
  EXPECT_EQ(faults.Count("radar left: wrong answers"), 1);
  EXPECT_TRUE(WaitUntil([&] { return radar.started(); }));
}

TEST(Lt102StartupTest, CrcIsDetectedFromTheVersionAnswerAndUsedOnEveryFrame) {
  Lt102EmulatorOptions options;
  options.crc = true;
  EmulatedLt102 radar("crc_auto", options);
  FaultLog faults;
  const StartupRun run = Startup(radar, TestConfig(), &faults);
  ASSERT_TRUE(run.error.empty()) << run.error;
  EXPECT_TRUE(run.setup.crc);
  EXPECT_EQ(run.setup.samples_per_scan, 1000);
  // Requests after the version carry the CRC byte: 'o' + CRC-8('o').
  const std::vector<std::uint8_t> bytes = radar.received();
  const std::uint8_t o = 'o';
  const std::vector<std::uint8_t> stop = {0xFF, 'o', Lt102Crc8(&o, 1, 0x07, 0), 0x00};
  EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin() + 3, bytes.begin() + 7), stop);
}

TEST(Lt102StartupTest, AModuleAnsweringWithCrcWhileWeExpectNoneFailsTheOpenSayingSo) {
  Lt102EmulatorOptions options;
  options.crc = true;
  EmulatedLt102 radar("crc_unexpected", options);
  Config config = TestConfig();
  config.live.lt102.crc = "off";
  FaultLog faults;
  const StartupRun run = Startup(radar, config, &faults);
  std::printf("CRC while none expected: %s\n", run.error.c_str());
  EXPECT_NE(run.error.find("answer to firmware version (0x01) has 9 payload bytes, expected 8: "
                           "the module appends a CRC byte (set live.lt102.crc: auto or on)"),
            std::string::npos)
      << run.error;
  EXPECT_EQ(faults.Count("radar left: wrong answers"), 2);
}

TEST(Lt102StartupTest, ACrcWithOtherParametersIsAMismatchNamingTheSettings) {
  Lt102EmulatorOptions options;
  options.crc = true;
  options.crc_polynomial = 0x31;  // the module's CRC-8 is not the configured one
  EmulatedLt102 radar("crc_poly", options);
  FaultLog faults;
  const StartupRun run = Startup(radar, TestConfig(), &faults);
  std::printf("CRC mismatch: %s\n", run.error.c_str());
  EXPECT_NE(run.error.find("CRC mismatch on the answer to firmware version"), std::string::npos);
  EXPECT_NE(run.error.find("live.lt102.crc_polynomial and crc_init"), std::string::npos);
}

TEST(Lt102StartupTest, ACarrierMoreThanOnePercentFromTheConfigIsAConfigurationError) {
  Lt102EmulatorOptions options;
  options.carrier_mhz = 7900;  // the toolbox's stored waveform is centred near 7.9 GHz
  EmulatedLt102 radar("carrier", options);
  FaultLog faults;
  const StartupRun run = Startup(radar, TestConfig(), &faults);
  EXPECT_TRUE(run.config_error);
  EXPECT_EQ(run.error,
            "radar left: configuration error: the radar's carrier is 7900 MHz, "
            "pulse.center_frequency_hz is 7290 MHz (8.4 % apart, more than 1 %): set "
            "pulse.center_frequency_hz to 7900e6 to image with this radar");
  EXPECT_FALSE(radar.started());
}

TEST(Lt102StartupTest, TheEchoedRangeSetsTheSampleCount) {
  EmulatedLt102 radar("range");
  Config config = TestConfig();
  config.live.lt102.range_min_m = 0.5;
  config.live.lt102.range_max_m = 3.0;
  FaultLog faults;
  const StartupRun run = Startup(radar, config, &faults);
  ASSERT_TRUE(run.error.empty()) << run.error;
  const double bin_m = 299792458.0 / (2 * 23.328e9);
  EXPECT_NEAR(run.setup.range_min_m, 78 * bin_m, 1e-6);  // 0.5 m snapped to the grid
  EXPECT_EQ(run.setup.samples_per_scan, 390);            // (3.0 - 0.5012) / bin + 1
}

}  // namespace
}  // namespace uwbsar::live
