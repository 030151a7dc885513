// An LT102 on a pseudo-terminal for tests and `uwbsar run --emulate`: it speaks the
// vendor's command protocol (lt102_commands.h) as the driver must expect it:
// every setting is echoed (`x` / `X` snapped to the sample grid, and that range sets the
// sample count and the range of sample 0 of the frames; `f` answered with the rate the radar
// runs at, which may differ from the one asked), a request holding a command's query value is
// answered with the setting only where the vendor table defines one (elsewhere, e.g. `v`
// 0xFF, the value is set), `s` is answered `r` and starts acquisition, `o` stops it. `d`
// follows the vendor fact ("with output 0 the radar returns its latest frame"): it is
// answered at once with the latest acquired frame, the same one again when polled before
// the next frame (counted repeated); only before the first frame after `s` does it wait.
// The option hold_d_until_next_frame gives the other behaviour the documentation does not
// exclude: a `d` finding the latest frame already handed out waits for the next one. A
// frame replaced before anyone asked for it is counted overwritten (and missed once a frame
// of this acquisition was handed out).
// Frames carry a CRC-8 byte when configured. Faults: a wrong echo, a missing answer, a
// raw-data answer of a bad size, corrupted bytes on the wire. Unplugging resets it, as a
// USB unplug does a module. One thread drives it (Serve and Acquire); the counts and
// the transcript of received bytes may be read from any thread.
#pragma once

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "drivers/emulators/pty_device.h"
#include "drivers/live/lt102_commands.h"
#include "drivers/live/lt102_protocol.h"

namespace uwbsar::live {

struct Lt102EmulatorOptions {
  double bin_m = 299792458.0 / (2.0 * 23.328e9);  ///< sample spacing c / (2 fs)
  int carrier_mhz = 7290, bandwidth_mhz = 1400, adc_frequency = 23328;
  int prf_divider = 1, tx_power = 7;
  Lt102Version version{1, 102, 3, 1, 0};
  bool crc = false;  ///< frames carry a CRC-8 byte
  /// `d` with the latest frame already handed out waits for the next frame instead of
  /// repeating it (not the documented behaviour; both are tested).
  bool hold_d_until_next_frame = false;
  int actual_frame_rate_fps = 0;  ///< the `f` answer (the rate it runs at); 0 = the rate asked
  std::uint8_t crc_polynomial = 0x07, crc_init = 0x00;
  // Faults.
  int wrong_echo_code = -1;       ///< this command's echo is off by one (or one bin)
  int missing_answer_code = -1;   ///< this command goes unanswered ...
  int missing_answer_times = 1;   ///< ... this many times
  int wrong_code_code = -1;       ///< this command's first answer starts with the wrong byte
  int bad_size_every = 0;         ///< every n-th `d` answer is two bytes short (0: never)
  double corrupt_fraction = 0.0;  ///< fraction of `d` answers garbled on the wire
  std::uint64_t seed = 7;
};

struct Lt102EmulatorCounts {
  long long requests = 0;            ///< well-formed requests received
  long long frames_acquired = 0;     ///< frames acquired while started
  long long frames_answered = 0;     ///< `d` answers sent
  long long frames_repeated = 0;     ///< `d` answers with a frame already handed out
  long long frames_overwritten = 0;  ///< acquired frames replaced before a `d` asked
  long long frames_missed = 0;       ///< of those, the ones after the first frame handed out since
                                     ///< `s` (the gaps a host polling this acquisition can see)
  long long frames_corrupted = 0;
  long long bad_size_frames = 0;
  long long answers_withheld = 0;  ///< missing-answer fault
  long long bytes_dropped = 0;     ///< the host did not read fast enough (or was unplugged)
};

class Lt102Emulator {
 public:
  Lt102Emulator(std::string link_path, Lt102EmulatorOptions options);

  /// Answers what the host has sent so far (does not wait).
  void Serve();
  /// A frame acquired: `samples[k]` lies at range_offset_m + k * bin_m. It is cropped to
  /// the range set with `x` / `X` (zeros outside) and answered at once if a `d` waits.
  void Acquire(const std::vector<float>& samples, double range_offset_m);
  void Unplug();
  void Plug();
  bool plugged() const { return device_.plugged(); }
  bool started() const { return started_; }
  const std::string& link_path() const { return device_.link_path(); }
  /// Every byte the host sent, in order.
  std::vector<std::uint8_t> received() const;
  Lt102EmulatorCounts counts() const;

 private:
  void ResetState();
  void Handle(const Lt102Frame& request);
  /// Version, start, stop, reset and frame requests; false for any other code.
  bool HandleControl(std::uint8_t code);
  /// Range settings (snapped to whole bins) and the offset query; false for other codes.
  bool HandleRange(const Lt102Command& command, bool query, double value);
  /// The integer setting a code sets and queries; nullptr if it is none.
  int* SettingField(std::uint8_t code);
  void SendAnswer(std::uint8_t code, std::vector<std::uint8_t> payload);
  void SendValue(const Lt102Command& command, double value);
  void SendFrame();
  int SampleCount() const;

  PtyDevice device_;
  Lt102EmulatorOptions options_;
  Lt102FrameDecoder decoder_;
  std::uint64_t rng_state_;
  // Module state.
  bool started_ = false;
  bool d_waiting_ = false;
  bool have_frame_ = false;    ///< a frame acquired since `s`
  bool frame_handed_ = false;  ///< the latest frame was answered to a `d`
  bool handed_any_ = false;    ///< a frame of this acquisition was answered
  std::vector<float> frame_;
  double range_min_m_ = 0.0, range_max_m_ = 0.0;
  int format_ = 1, channel_ = 0, frame_rate_ = 100, processing_ = 0, output_ = 0;
  int decimation_ = 0;
  int withheld_ = 0;
  bool wrong_code_sent_ = false;
  mutable std::mutex mutex_;  ///< counts_ and received_
  Lt102EmulatorCounts counts_;
  std::vector<std::uint8_t> received_;
};

}  // namespace uwbsar::live
