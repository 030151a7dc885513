#include "drivers/live/lt102_exchange.h"

#include <chrono>
#include <cstdio>

namespace uwbsar::live {

Lt102Exchange::Lt102Exchange(std::string name, const Lt102Config& config, FaultLog* faults)
    : name_(std::move(name)),
      crc_setting_(config.crc),
      timeout_s_(config.answer_timeout_s),
      faults_(faults) {
  crc_.polynomial = static_cast<std::uint8_t>(config.crc_polynomial);
  crc_.init = static_cast<std::uint8_t>(config.crc_init);
  Reset();
}

void Lt102Exchange::Reset() {
  crc_.enabled = crc_setting_ == "on";
  crc_known_ = crc_setting_ != "auto";
  decoder_.Reset();
}

void Lt102Exchange::Flush(SerialPort& port) {
  std::uint8_t buffer[4096];
  std::size_t n = 0;
  while (port.Read(buffer, sizeof(buffer), 0.0, &n) == SerialPort::ReadStatus::kData) {
  }
  decoder_.Reset();
}

bool Lt102Exchange::Send(SerialPort& port, const Lt102Request& request) {
  const std::vector<std::uint8_t> bytes = Encode(request);
  ++counts_.requests;
  return port.Write(bytes.data(), bytes.size(), timeout_s_);
}

bool Lt102Exchange::StripCrc(const Lt102Frame& frame, std::vector<std::uint8_t>* payload,
                             std::string* error) const {
  *payload = frame.payload;
  if (!crc_.enabled) return true;
  if (payload->empty()) {
    *error = "answer " + Lt102CommandLabel(frame.code) + " has no CRC byte";
    return false;
  }
  std::vector<std::uint8_t> body = {frame.code};
  body.insert(body.end(), payload->begin(), payload->end());
  if (Lt102Crc8(body.data(), body.size(), crc_.polynomial, crc_.init) != 0) {
    *error = "CRC mismatch on the answer to " + Lt102CommandLabel(frame.code) +
             " (with a real module: check live.lt102.crc_polynomial and crc_init)";
    return false;
  }
  payload->pop_back();
  return true;
}

bool Lt102Exchange::Await(SerialPort& port, const Lt102Command& command,
                          std::vector<std::uint8_t>* payload, std::string* why) {
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s_);
  std::vector<Lt102Frame> frames;
  std::uint8_t buffer[4096];
  while (frames.empty()) {
    const double left = std::chrono::duration<double>(deadline - Clock::now()).count();
    if (left <= 0) {
      ++counts_.missing_answers;
      char within[32];
      std::snprintf(within, sizeof(within), " within %g s", timeout_s_);
      *why = "no answer to " + Lt102CommandLabel(command.code) + within;
      faults_->Report(name_ + ": missing answers", *why);
      return false;
    }
    std::size_t n = 0;
    const auto status = port.Read(buffer, sizeof(buffer), left, &n);
    if (status == SerialPort::ReadStatus::kDisconnected) {
      throw SerialError(name_ + ": " + port.path() + " disappeared during start-up");
    }
    if (status == SerialPort::ReadStatus::kData) decoder_.Push(buffer, n, &frames);
  }
  const Lt102Frame& answer = frames.front();  // the first frame is the answer
  auto wrong = [&](const std::string& text) {
    ++counts_.wrong_answers;
    *why = text;
    faults_->Report(name_ + ": wrong answers", text);
    return false;
  };
  if (answer.code != command.answer_code) {
    return wrong("answer to " + Lt102CommandLabel(command.code) + " starts with " +
                 Lt102CommandLabel(answer.code) + ", expected " +
                 Lt102CommandLabel(command.answer_code));
  }
  const std::size_t size = Lt102ValueSize(command.answer);
  bool detecting = false;
  if (!crc_known_) {  // auto: the first answer's length tells whether a CRC byte follows
    if (answer.payload.size() == size || answer.payload.size() == size + 1) {
      crc_.enabled = answer.payload.size() == size + 1;
      crc_known_ = detecting = true;
    }
  }
  const std::size_t expected = size + (crc_.enabled ? 1 : 0);
  if (command.answer != Lt102Value::kRawData && answer.payload.size() != expected) {
    std::string text = "answer to " + Lt102CommandLabel(command.code) + " has " +
                       std::to_string(answer.payload.size()) + " payload bytes, expected " +
                       std::to_string(expected);
    if (!crc_.enabled && answer.payload.size() == size + 1) {
      text += ": the module appends a CRC byte (set live.lt102.crc: auto or on)";
    } else if (crc_.enabled && answer.payload.size() == size) {
      text += ": the module sends no CRC byte (set live.lt102.crc: auto or off)";
    }
    return wrong(text);
  }
  std::string error;
  if (!StripCrc(answer, payload, &error)) {
    if (detecting) crc_known_ = crc_.enabled = false;  // the retry asks as the first try did
    return wrong(error);
  }
  return true;
}

std::vector<std::uint8_t> Lt102Exchange::Ask(SerialPort& port, const Lt102Request& request) {
  const Lt102Command* command = FindLt102Command(request.code);
  if (command == nullptr) throw SerialError(name_ + ": " + Lt102CommandLabel(request.code));
  std::string why;
  for (int attempt = 0; attempt < 2; ++attempt) {
    if (attempt > 0) ++counts_.retries;
    Flush(port);
    if (!Send(port, request)) {
      throw SerialError(name_ + ": cannot send " + Lt102CommandLabel(request.code) + " to " +
                        port.path());
    }
    std::vector<std::uint8_t> payload;
    if (Await(port, *command, &payload, &why)) return payload;
  }
  Flush(port);
  throw SerialError(name_ + ": " + why + " (after a resync and one retry)");
}

}  // namespace uwbsar::live
