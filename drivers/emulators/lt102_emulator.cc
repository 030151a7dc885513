#include "drivers/emulators/lt102_emulator.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace uwbsar::live {

Lt102Emulator::Lt102Emulator(std::string link_path, Lt102EmulatorOptions options)
    : device_(std::move(link_path)), options_(options), rng_state_(options.seed) {
  ResetState();
}

void Lt102Emulator::ResetState() {
  started_ = d_waiting_ = have_frame_ = frame_handed_ = handed_any_ = false;
  range_min_m_ = 0.0;
  range_max_m_ = 999 * options_.bin_m;
  format_ = 1;
  channel_ = 0;
  frame_rate_ = 100;
  processing_ = output_ = decimation_ = 0;
  decoder_.Reset();
}

void Lt102Emulator::Unplug() {
  device_.Unplug();
  ResetState();
}

void Lt102Emulator::Plug() { device_.Plug(); }

std::vector<std::uint8_t> Lt102Emulator::received() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return received_;
}

Lt102EmulatorCounts Lt102Emulator::counts() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counts_;
}

int Lt102Emulator::SampleCount() const {
  return static_cast<int>(std::llround((range_max_m_ - range_min_m_) / options_.bin_m)) + 1;
}

void Lt102Emulator::Serve() {
  const std::vector<std::uint8_t> bytes = device_.ReadAvailable();
  if (bytes.empty()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    received_.insert(received_.end(), bytes.begin(), bytes.end());
  }
  std::vector<Lt102Frame> frames;
  decoder_.Push(bytes.data(), bytes.size(), &frames);
  for (Lt102Frame& frame : frames) {
    const Lt102Command* command = FindLt102Command(frame.code);
    if (command == nullptr) continue;  // unknown commands go unanswered
    // The host may or may not append a CRC byte; a request one byte long checks it.
    const std::size_t size = Lt102ValueSize(command->request);
    if (frame.payload.size() == size + 1) {
      std::vector<std::uint8_t> body = {frame.code};
      body.insert(body.end(), frame.payload.begin(), frame.payload.end());
      if (Lt102Crc8(body.data(), body.size(), options_.crc_polynomial, options_.crc_init) != 0) {
        continue;
      }
      frame.payload.pop_back();
    } else if (frame.payload.size() != size) {
      continue;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++counts_.requests;
    }
    if (frame.code == options_.missing_answer_code && withheld_ < options_.missing_answer_times) {
      ++withheld_;
      std::lock_guard<std::mutex> lock(mutex_);
      ++counts_.answers_withheld;
      continue;
    }
    Handle(frame);
  }
}

void Lt102Emulator::Handle(const Lt102Frame& request) {
  if (HandleControl(request.code)) return;
  const Lt102Command& command = *FindLt102Command(request.code);
  const std::size_t size = Lt102ValueSize(command.request);
  const bool query = command.queryable && size > 0 &&
                     std::all_of(request.payload.begin(), request.payload.end(),
                                 [](std::uint8_t b) { return b == 0xFF; });
  const double value = size > 0 ? ReadLt102Value(command.request, request.payload.data()) : 0.0;
  if (HandleRange(command, query, value)) return;
  if (request.code == lt102::kAdcFrequency) return SendValue(command, options_.adc_frequency);
  if (request.code == lt102::kFrameRate && !query && options_.actual_frame_rate_fps > 0) {
    frame_rate_ = options_.actual_frame_rate_fps;  // the rate it can run at
    return SendValue(command, frame_rate_);
  }
  if (int* field = SettingField(request.code)) {
    if (!query) *field = static_cast<int>(value);
    SendValue(command, *field);
  }
}

bool Lt102Emulator::HandleControl(std::uint8_t code) {
  switch (code) {
    case lt102::kVersion: {
      std::vector<std::uint8_t> payload;
      AppendLt102Version(options_.version, &payload);
      SendAnswer(lt102::kVersion, payload);
      return true;
    }
    case lt102::kStart:
      started_ = true;
      have_frame_ = frame_handed_ = handed_any_ = d_waiting_ = false;
      SendAnswer(lt102::kStarted, {});
      return true;
    case lt102::kStop:
      started_ = d_waiting_ = have_frame_ = frame_handed_ = handed_any_ = false;
      SendAnswer(lt102::kStop, {});
      return true;
    case lt102::kReset:
      ResetState();
      SendAnswer(lt102::kReset, {});
      return true;
    case lt102::kReadFrame:
      if (!started_) return true;  // not acquiring: nothing to hand out
      if (have_frame_ && !(frame_handed_ && options_.hold_d_until_next_frame)) {
        SendFrame();  // the latest frame, again if it was handed out already
      } else {
        d_waiting_ = true;  // the first frame of the acquisition (or, holding, the next)
      }
      return true;
    default:
      return false;
  }
}

bool Lt102Emulator::HandleRange(const Lt102Command& command, bool query, double value) {
  switch (command.code) {
    case lt102::kRangeMin:
      if (!query) {
        range_min_m_ = std::max(0.0, std::round(value / options_.bin_m) * options_.bin_m);
        range_max_m_ = std::max(range_max_m_, range_min_m_ + options_.bin_m);
      }
      SendValue(command, range_min_m_);
      return true;
    case lt102::kRangeMax:
      if (!query) {
        const long long bins = std::max(1LL, std::llround((value - range_min_m_) / options_.bin_m));
        range_max_m_ = range_min_m_ + static_cast<double>(bins) * options_.bin_m;
      }
      SendValue(command, range_max_m_);
      return true;
    case lt102::kOffset:
      SendValue(command, range_min_m_);
      return true;
    default:
      return false;
  }
}

int* Lt102Emulator::SettingField(std::uint8_t code) {
  switch (code) {
    case lt102::kFrameRate:
      return &frame_rate_;
    case lt102::kFormat:
      return &format_;
    case lt102::kChannel:
      return &channel_;
    case lt102::kProcessing:
      return &processing_;
    case lt102::kOutput:
      return &output_;
    case lt102::kDecimation:
      return &decimation_;
    case lt102::kPrfDivider:
      return &options_.prf_divider;
    case lt102::kCarrier:
      return &options_.carrier_mhz;
    case lt102::kBandwidth:
      return &options_.bandwidth_mhz;
    case lt102::kTxPower:
      return &options_.tx_power;
    default:
      return nullptr;
  }
}

void Lt102Emulator::SendValue(const Lt102Command& command, double value) {
  if (command.code == options_.wrong_echo_code) {
    value += command.answer == Lt102Value::kF32 ? options_.bin_m : 1.0;
  }
  std::vector<std::uint8_t> payload;
  AppendLt102Value(command.answer, value, &payload);
  SendAnswer(command.answer_code, payload);
}

void Lt102Emulator::SendAnswer(std::uint8_t code, std::vector<std::uint8_t> payload) {
  const Lt102Command* command = FindLt102Command(code);
  if (!wrong_code_sent_ && options_.wrong_code_code >= 0 &&
      (code == options_.wrong_code_code || (command && command->code == options_.wrong_code_code) ||
       (code == lt102::kStarted && options_.wrong_code_code == lt102::kStart))) {
    wrong_code_sent_ = true;
    code ^= 0x20;  // e.g. 'R' for 'r'
  }
  if (options_.crc) {
    std::vector<std::uint8_t> body = {code};
    body.insert(body.end(), payload.begin(), payload.end());
    payload.push_back(
        Lt102Crc8(body.data(), body.size(), options_.crc_polynomial, options_.crc_init));
  }
  std::vector<std::uint8_t> frame;
  EncodeLt102Frame(code, payload.data(), payload.size(), &frame);
  const std::size_t written = device_.Write(frame);
  std::lock_guard<std::mutex> lock(mutex_);
  counts_.bytes_dropped += static_cast<long long>(frame.size() - written);
}

void Lt102Emulator::Acquire(const std::vector<float>& samples, double range_offset_m) {
  if (!device_.plugged() || !started_) return;
  const int n = SampleCount();
  const long long first = std::llround((range_min_m_ - range_offset_m) / options_.bin_m);
  frame_.assign(static_cast<std::size_t>(n), 0.0f);
  for (int j = 0; j < n; ++j) {
    const long long k = first + j;
    if (k >= 0 && k < static_cast<long long>(samples.size())) {
      frame_[static_cast<std::size_t>(j)] = samples[static_cast<std::size_t>(k)];
    }
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++counts_.frames_acquired;
    if (have_frame_ && !frame_handed_) {
      ++counts_.frames_overwritten;
      if (handed_any_) ++counts_.frames_missed;
    }
  }
  have_frame_ = true;
  frame_handed_ = false;
  if (d_waiting_) SendFrame();
}

void Lt102Emulator::SendFrame() {
  const std::vector<float> q(frame_.size(), 0.0f);
  std::vector<std::uint8_t> payload =
      EncodeLt102RawData(format_, static_cast<int>(frame_.size()), 250, frame_, q);
  const bool repeated = frame_handed_;
  frame_handed_ = handed_any_ = true;
  d_waiting_ = false;
  long long answered = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    answered = ++counts_.frames_answered;
    if (repeated) ++counts_.frames_repeated;
  }
  const bool bad_size = options_.bad_size_every > 0 && answered % options_.bad_size_every == 0;
  if (bad_size) payload.resize(payload.size() - 2);
  if (options_.crc) {
    std::vector<std::uint8_t> body = {lt102::kReadFrame};
    body.insert(body.end(), payload.begin(), payload.end());
    payload.push_back(
        Lt102Crc8(body.data(), body.size(), options_.crc_polynomial, options_.crc_init));
  }
  std::vector<std::uint8_t> frame;
  EncodeLt102Frame(lt102::kReadFrame, payload.data(), payload.size(), &frame);
  std::mt19937_64 rng(rng_state_++);
  const bool corrupt =
      std::uniform_real_distribution<double>(0, 1)(rng) < options_.corrupt_fraction;
  if (corrupt) {
    switch (rng() % 3) {
      case 0: {  // garbage before the frame, and the frame cut short
        std::vector<std::uint8_t> garbage(20);
        for (auto& b : garbage) b = static_cast<std::uint8_t>(rng() & 0x7F);
        frame.insert(frame.begin(), garbage.begin(), garbage.end());
        frame.resize(frame.size() / 2);
        break;
      }
      case 1:  // truncated: the end byte never comes
        frame.resize(frame.size() / 2);
        break;
      default:  // an invalid escape in the middle
        frame[frame.size() / 2] = 0x80;
        frame[frame.size() / 2 + 1] = 0x42;
        break;
    }
  }
  const std::size_t written = device_.Write(frame);
  std::lock_guard<std::mutex> lock(mutex_);
  if (corrupt) ++counts_.frames_corrupted;
  if (bad_size) ++counts_.bad_size_frames;
  counts_.bytes_dropped += static_cast<long long>(frame.size() - written);
}

}  // namespace uwbsar::live
