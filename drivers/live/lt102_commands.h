// The LT102 command set as data (from ARIA Sensing's public
// toolbox protocol): each command's byte, the type of its request value, the byte and value type
// of its answer and how the answer relates to the request. Requests and answers are
// byte-stuffed frames (lt102_protocol.h) with an optional trailing CRC-8 byte over
// command byte + payload. Values are little-endian, f32 is IEEE single. The raw-data
// answer of `d` is decoded in code (lt102_protocol.h: DecodeLt102RawData).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace uwbsar::live {

/// The type of a request or answer value.
enum class Lt102Value { kNone, kU8, kI8, kU16, kI16, kF32, kVersion, kRawData };

/// How an answer's value relates to the request's.
enum class Lt102Echo {
  kNone,    ///< no value (or not compared: version, raw data)
  kExact,   ///< must equal the value sent; anything else is a configuration error
  kActual,  ///< the value the radar applied (e.g. the range snapped to its sample grid)
  kQuery,   ///< the request asked (query value); the answer is the current setting
};

struct Lt102Command {
  const char* name;  ///< e.g. "range minimum"
  std::uint8_t code;
  Lt102Value request;
  std::uint8_t answer_code;
  Lt102Value answer;
  Lt102Echo echo;
  /// The vendor table defines a query value for this command (0xFF, 0xFFFF or i32 -1 in
  /// place of the setting); a command without one is never sent as a query.
  bool queryable;
};

/// Command bytes (the table's rows).
namespace lt102 {
constexpr std::uint8_t kStart = 's', kStarted = 'r', kStop = 'o', kReset = '!', kReadFrame = 'd',
                       kRangeMin = 'x', kRangeMax = 'X', kOffset = '0', kFrameRate = 'f',
                       kPrfDivider = 'v', kFormat = 0x0A, kChannel = '$', kDecimation = 'q',
                       kCarrier = 0x0B, kBandwidth = 0x0C, kTxPower = 'p', kOutput = 'b',
                       kProcessing = 'e', kVersion = 0x01, kAdcFrequency = 0x05;
}  // namespace lt102

/// The whole table.
const std::vector<Lt102Command>& Lt102Commands();
/// The row of `code`; nullptr for an unknown byte.
const Lt102Command* FindLt102Command(std::uint8_t code);
/// "range minimum (X)" style label of a command byte for messages.
std::string Lt102CommandLabel(std::uint8_t code);

/// Payload bytes of a value type (0 for none; raw data is variable: 0).
std::size_t Lt102ValueSize(Lt102Value type);
/// Appends `value` encoded as `type` (integers rounded and range-checked by the caller).
void AppendLt102Value(Lt102Value type, double value, std::vector<std::uint8_t>* out);
/// Appends the query value of `type`: 0xFF, 0xFFFF, or i32 -1 in place of an f32.
void AppendLt102Query(Lt102Value type, std::vector<std::uint8_t>* out);
/// Reads a value of `type` (the caller checked the size).
double ReadLt102Value(Lt102Value type, const std::uint8_t* p);
/// Prints a value as the log and error messages show it (f32 with 4 decimals).
std::string FormatLt102Value(Lt102Value type, double value);

/// A request: the command and its value (or a query).
struct Lt102Request {
  std::uint8_t code = 0;
  bool query = false;
  double value = 0.0;
};
/// The body (command byte + payload) of a request. A query of a command without a query
/// value is a programmer error (asserted).
std::vector<std::uint8_t> Lt102RequestBody(const Lt102Request& request);

/// The CRC-8 used on the link: whether frames carry it, and its parameters.
struct Lt102CrcMode {
  bool enabled = false;
  std::uint8_t polynomial = 0x07;
  std::uint8_t init = 0x00;
};
/// The stuffed frame of `body` (+ CRC when enabled).
std::vector<std::uint8_t> EncodeLt102Body(const std::vector<std::uint8_t>& body,
                                          const Lt102CrcMode& crc);

/// The firmware version answer (0x01).
struct Lt102Version {
  int customer = 0, hardware = 0, firmware = 0, feature_set = 0, sub_version = 0;
  std::string ToString() const;
};
Lt102Version ReadLt102Version(const std::uint8_t* p);
void AppendLt102Version(const Lt102Version& v, std::vector<std::uint8_t>* out);

}  // namespace uwbsar::live
