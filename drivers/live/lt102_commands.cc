#include "drivers/live/lt102_commands.h"

#include <cassert>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "drivers/live/lt102_protocol.h"

namespace uwbsar::live {
namespace {

using V = Lt102Value;
using E = Lt102Echo;

void PutU16(std::vector<std::uint8_t>* out, unsigned v) {
  out->push_back(static_cast<std::uint8_t>(v & 0xFF));
  out->push_back(static_cast<std::uint8_t>((v >> 8) & 0xFF));
}
unsigned GetU16(const std::uint8_t* p) { return static_cast<unsigned>(p[0] | (p[1] << 8)); }

}  // namespace

const std::vector<Lt102Command>& Lt102Commands() {
  // The toolbox's command bytes, each with its LT102-relevant use.
  static const std::vector<Lt102Command> table = {
      {"start acquisition", lt102::kStart, V::kNone, lt102::kStarted, V::kNone, E::kNone, false},
      {"stop acquisition", lt102::kStop, V::kNone, lt102::kStop, V::kNone, E::kNone, false},
      {"reset to defaults", lt102::kReset, V::kNone, lt102::kReset, V::kNone, E::kNone, false},
      {"read one raw frame", lt102::kReadFrame, V::kNone, lt102::kReadFrame, V::kRawData, E::kNone,
       false},
      {"range minimum", lt102::kRangeMin, V::kF32, lt102::kRangeMin, V::kF32, E::kActual, true},
      {"range maximum", lt102::kRangeMax, V::kF32, lt102::kRangeMax, V::kF32, E::kActual, true},
      {"first-sample offset", lt102::kOffset, V::kF32, lt102::kOffset, V::kF32, E::kActual, true},
      // "f + i16 actual": the rate the radar runs at, which may differ from the one asked.
      {"frame rate", lt102::kFrameRate, V::kU16, lt102::kFrameRate, V::kI16, E::kActual, true},
      {"PRF divider", lt102::kPrfDivider, V::kU8, lt102::kPrfDivider, V::kI8, E::kExact, false},
      {"sample format", lt102::kFormat, V::kU8, lt102::kFormat, V::kI8, E::kExact, true},
      {"data channel", lt102::kChannel, V::kU8, lt102::kChannel, V::kI8, E::kExact, true},
      {"decimation", lt102::kDecimation, V::kU8, lt102::kDecimation, V::kI8, E::kExact, false},
      {"carrier frequency", lt102::kCarrier, V::kU16, lt102::kCarrier, V::kI16, E::kActual, true},
      {"pulse bandwidth", lt102::kBandwidth, V::kU16, lt102::kBandwidth, V::kI16, E::kActual, true},
      {"TX power", lt102::kTxPower, V::kU8, lt102::kTxPower, V::kI8, E::kActual, true},
      {"output", lt102::kOutput, V::kU8, lt102::kOutput, V::kI8, E::kExact, true},
      {"processing", lt102::kProcessing, V::kU8, lt102::kProcessing, V::kI8, E::kExact, false},
      {"firmware version", lt102::kVersion, V::kNone, lt102::kVersion, V::kVersion, E::kNone,
       false},
      {"ADC frequency", lt102::kAdcFrequency, V::kU16, lt102::kAdcFrequency, V::kI16, E::kQuery,
       true},
  };
  return table;
}

const Lt102Command* FindLt102Command(std::uint8_t code) {
  for (const Lt102Command& c : Lt102Commands()) {
    if (c.code == code) return &c;
  }
  return nullptr;
}

std::string Lt102CommandLabel(std::uint8_t code) {
  const Lt102Command* c = FindLt102Command(code);
  char hex[8];
  std::snprintf(hex, sizeof(hex), "0x%02X", code);
  std::string label = c ? std::string(c->name) + " (" : std::string("unknown command (");
  if (code == lt102::kStarted) label = "acquisition started (";  // the answer to 's'

  if (code >= 0x21 && code < 0x7F) label += std::string("'") + static_cast<char>(code) + "' ";
  return label + hex + ")";
}

std::size_t Lt102ValueSize(Lt102Value type) {
  switch (type) {
    case V::kU8:
    case V::kI8:
      return 1;
    case V::kU16:
    case V::kI16:
      return 2;
    case V::kF32:
      return 4;
    case V::kVersion:
      return 8;
    case V::kNone:
    case V::kRawData:
      return 0;
  }
  return 0;
}

void AppendLt102Value(Lt102Value type, double value, std::vector<std::uint8_t>* out) {
  const long long n = std::llround(value);
  switch (type) {
    case V::kU8:
    case V::kI8:
      out->push_back(static_cast<std::uint8_t>(n & 0xFF));
      return;
    case V::kU16:
    case V::kI16:
      PutU16(out, static_cast<unsigned>(n & 0xFFFF));
      return;
    case V::kF32: {
      const float f = static_cast<float>(value);
      std::uint8_t b[4];
      std::memcpy(b, &f, 4);  // the link and every supported host are little-endian
      out->insert(out->end(), b, b + 4);
      return;
    }
    default:
      return;
  }
}

void AppendLt102Query(Lt102Value type, std::vector<std::uint8_t>* out) {
  const std::size_t n = type == V::kF32 ? 4 : Lt102ValueSize(type);  // i32 -1 for an f32
  out->insert(out->end(), n, 0xFF);
}

double ReadLt102Value(Lt102Value type, const std::uint8_t* p) {
  switch (type) {
    case V::kU8:
      return p[0];
    case V::kI8:
      return static_cast<std::int8_t>(p[0]);
    case V::kU16:
      return GetU16(p);
    case V::kI16:
      return static_cast<std::int16_t>(static_cast<std::uint16_t>(GetU16(p)));
    case V::kF32: {
      float f;
      std::memcpy(&f, p, 4);
      return f;
    }
    default:
      return 0.0;
  }
}

std::string FormatLt102Value(Lt102Value type, double value) {
  char text[32];
  if (type == V::kF32) {
    std::snprintf(text, sizeof(text), "%.4f", value);
  } else {
    std::snprintf(text, sizeof(text), "%lld", std::llround(value));
  }
  return text;
}

std::vector<std::uint8_t> Lt102RequestBody(const Lt102Request& request) {
  std::vector<std::uint8_t> body = {request.code};
  const Lt102Command* c = FindLt102Command(request.code);
  if (c == nullptr || c->request == V::kNone) return body;
  if (request.query) {
    assert(c->queryable && "the vendor table defines no query value for this command");
    AppendLt102Query(c->request, &body);
  } else {
    AppendLt102Value(c->request, request.value, &body);
  }
  return body;
}

std::vector<std::uint8_t> EncodeLt102Body(const std::vector<std::uint8_t>& body,
                                          const Lt102CrcMode& crc) {
  std::vector<std::uint8_t> payload(body.begin() + 1, body.end());
  if (crc.enabled) payload.push_back(Lt102Crc8(body.data(), body.size(), crc.polynomial, crc.init));
  std::vector<std::uint8_t> out;
  EncodeLt102Frame(body[0], payload.data(), payload.size(), &out);
  return out;
}

std::string Lt102Version::ToString() const {
  return "customer " + std::to_string(customer) + ", hardware " + std::to_string(hardware) +
         ", firmware " + std::to_string(firmware) + ", feature set " + std::to_string(feature_set) +
         ", sub-version " + std::to_string(sub_version);
}

Lt102Version ReadLt102Version(const std::uint8_t* p) {
  Lt102Version v;
  v.customer = static_cast<int>(GetU16(p));
  v.hardware = static_cast<int>(GetU16(p + 2));
  v.firmware = p[4];
  v.feature_set = p[5];
  v.sub_version = static_cast<int>(GetU16(p + 6));
  return v;
}

void AppendLt102Version(const Lt102Version& v, std::vector<std::uint8_t>* out) {
  PutU16(out, static_cast<unsigned>(v.customer));
  PutU16(out, static_cast<unsigned>(v.hardware));
  out->push_back(static_cast<std::uint8_t>(v.firmware));
  out->push_back(static_cast<std::uint8_t>(v.feature_set));
  PutU16(out, static_cast<unsigned>(v.sub_version));
}

}  // namespace uwbsar::live
