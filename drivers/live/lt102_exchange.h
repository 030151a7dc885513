// One request and its answer on an LT102 link, as the vendor toolbox does it
// (lt102_commands.h): flush the input, send the framed request, wait up to the
// answer timeout for the first frame, and check it: its first byte must be the command's
// answer byte, its size the answer's (plus the CRC byte when frames carry one), its CRC
// must check. A wrong or missing answer is reported, the link resynchronised (input
// flushed, partial frame dropped) and the request sent once more; a second failure throws
// SerialError naming the command, which fails the open so the link's reconnect, backoff
// and power cycle take over. With crc "auto" the first answer decides whether frames
// carry a CRC: the firmware-version answer is 8 bytes without one and 9 with one.
#pragma once

#include <functional>
#include <string>

#include "drivers/live/fault_log.h"
#include "drivers/live/live_config.h"
#include "drivers/live/lt102_commands.h"
#include "drivers/live/lt102_protocol.h"
#include "drivers/live/serial_port.h"

namespace uwbsar::live {

/// The radar refused a setting (its echo differs from the request) or reports one that
/// contradicts the configuration: retrying cannot help. what() is one line naming the
/// radar, the command and both values.
class Lt102ConfigError : public SerialError {
 public:
  using SerialError::SerialError;
};

struct Lt102ExchangeCounts {
  long long requests = 0;
  long long wrong_answers = 0;    ///< wrong first byte, size or CRC
  long long missing_answers = 0;  ///< nothing within the answer timeout
  long long retries = 0;          ///< resynchronised and sent again
};

class Lt102Exchange {
 public:
  /// `name` labels faults ("radar left"). `crc` is live.lt102.crc's mode.
  Lt102Exchange(std::string name, const Lt102Config& config, FaultLog* faults);

  /// Sends `request` and returns its answer's payload (CRC byte removed); throws
  /// SerialError after a failed retry.
  std::vector<std::uint8_t> Ask(SerialPort& port, const Lt102Request& request);
  /// Sends without waiting for an answer; false if the port is gone.
  bool Send(SerialPort& port, const Lt102Request& request);
  /// The framed bytes of `request` (with a CRC byte when frames carry one).
  std::vector<std::uint8_t> Encode(const Lt102Request& request) const {
    return EncodeLt102Body(Lt102RequestBody(request), crc_);
  }
  /// Checks and strips the CRC of a received frame's payload; false (with `error`) when it
  /// does not check. No-op without CRC.
  bool StripCrc(const Lt102Frame& frame, std::vector<std::uint8_t>* payload,
                std::string* error) const;

  bool crc_enabled() const { return crc_.enabled; }
  const Lt102ExchangeCounts& counts() const { return counts_; }
  /// Forgets the auto-detected CRC mode (a new module may be behind the port).
  void Reset();

 private:
  bool Await(SerialPort& port, const Lt102Command& command, std::vector<std::uint8_t>* payload,
             std::string* why);
  void Flush(SerialPort& port);

  std::string name_;
  std::string crc_setting_;
  double timeout_s_;
  FaultLog* faults_;
  Lt102CrcMode crc_;
  bool crc_known_ = false;
  Lt102FrameDecoder decoder_;
  Lt102ExchangeCounts counts_;
};

}  // namespace uwbsar::live
