#include "drivers/live/device_link.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include "core/log.h"
#include "drivers/live/thread_priority.h"

namespace uwbsar::live {

DeviceLink::DeviceLink(std::string name, std::string path, LinkPolicy policy,
                       LinkProtocol* protocol, FaultLog* faults, std::function<void()> power_cycle)
    : name_(std::move(name)),
      path_(std::move(path)),
      policy_(policy),
      protocol_(protocol),
      faults_(faults),
      power_cycle_(std::move(power_cycle)) {}

void DeviceLink::Start() {
  stop_ = false;
  thread_ = std::thread([this] { Loop(); });
}

void DeviceLink::RequestStop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
}

void DeviceLink::Stop() {
  RequestStop();
  if (thread_.joinable()) thread_.join();
}

bool DeviceLink::Wait(double s) {
  std::unique_lock<std::mutex> lock(mutex_);
  wake_.wait_for(lock, std::chrono::duration<double>(s), [this] { return stop_.load(); });
  return !stop_;
}

void DeviceLink::Loop() {
  RequestRealtimeOrWarn(policy_.realtime_priority, name_);
  SerialPort port;
  std::vector<std::uint8_t> buffer(1 << 16);
  Retry retry;
  retry.backoff_s = policy_.reconnect_initial_s;
  bool ever_connected = false;
  while (!stop_) {
    if (!Connect(&port, &retry)) {
      if (!Wait(retry.backoff_s)) break;
      retry.backoff_s = std::min(retry.backoff_s * 2.0, policy_.reconnect_max_s);
      continue;
    }
    if (ever_connected) {
      Log(LogLevel::kInfo, name_ + ": reconnected on " + path_ + " after " +
                               std::to_string(retry.failures) + " failed attempts");
    }
    ever_connected = true;
    ++counters_.connects;
    connected_ = true;
    const bool delivered = ReadUntilLost(&port, &buffer, &retry);
    connected_ = false;
    if (stop_) {
      protocol_->OnStop(port);
      port.Close();
      break;
    }
    if (!delivered) NoteFailure(&port, &retry);
    port.Close();
    protocol_->OnLost();
    if (!Wait(retry.backoff_s)) break;
    if (!delivered) retry.backoff_s = std::min(retry.backoff_s * 2.0, policy_.reconnect_max_s);
  }
}

bool DeviceLink::Connect(SerialPort* port, Retry* retry) {
  try {
    port->Open(path_, policy_.baud);
    if (!protocol_->OnOpen(*port)) throw SerialError(path_ + ": start commands not accepted");
    return true;
  } catch (const SerialError& e) {
    ++counters_.open_failures;
    faults_->Report(name_ + ": cannot connect", e.what());
    NoteFailure(port, retry);
    port->Close();
    return false;
  }
}

bool DeviceLink::ReadUntilLost(SerialPort* port, std::vector<std::uint8_t>* buffer, Retry* retry) {
  bool delivered = false;
  using Clock = std::chrono::steady_clock;
  auto last_data = Clock::now();
  constexpr double kPollS = 0.05;
  while (!stop_) {
    const double wait_s = std::clamp(protocol_->OnPoll(*port), 0.0, kPollS);
    std::size_t n = 0;
    const auto status = port->Read(buffer->data(), buffer->size(), wait_s, &n);
    if (status == SerialPort::ReadStatus::kData) {
      counters_.bytes += static_cast<long long>(n);
      last_data = Clock::now();
      if (!delivered) {
        delivered = true;
        retry->failures = 0;
        retry->backoff_s = policy_.reconnect_initial_s;
      }
      protocol_->OnBytes(buffer->data(), n);
    } else if (status == SerialPort::ReadStatus::kTimeout) {
      if (std::chrono::duration<double>(Clock::now() - last_data).count() >=
          policy_.read_timeout_s) {
        ++counters_.timeouts;
        faults_->Report(name_ + ": silent", "no bytes for " +
                                                std::to_string(policy_.read_timeout_s) + " s on " +
                                                path_ + ", reconnecting");
        break;
      }
    } else {
      ++counters_.disconnects;
      faults_->Report(name_ + ": unplugged", path_ + " disappeared, reconnecting with backoff");
      break;
    }
  }
  return delivered;
}

void DeviceLink::NoteFailure(SerialPort* port, Retry* retry) {
  ++retry->failures;
  if (power_cycle_ && retry->failures % policy_.power_cycle_after_failures == 0) {
    if (port->is_open()) protocol_->OnStop(*port);  // stopped before its power goes
    port->Close();
    ++counters_.power_cycles;
    faults_->Report(name_ + ": power cycled",
                    "after " + std::to_string(retry->failures) + " failed connections in a row");
    power_cycle_();
  }
}

}  // namespace uwbsar::live
