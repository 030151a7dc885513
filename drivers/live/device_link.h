// One serial device kept alive on its own thread: open, let the protocol run its
// start-up, read with a timeout and hand the bytes to the protocol (a polled device sends
// its requests from OnPoll, on the same thread, between reads); when the
// device disappears (unplug) or stays silent longer than the read timeout, close it
// and reopen with exponential backoff. After `power_cycle_after_failures` failed
// attempts in a row the optional power-cycle hook runs (radar power through GPIO), after
// the protocol's stop (OnStop) where the port is still open.
// Every fault goes to the FaultLog under "<name>: <what>". The reading thread never
// waits on anything but the device: the protocol's sinks must not block.
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "drivers/live/fault_log.h"
#include "drivers/live/serial_port.h"

namespace uwbsar::live {

struct LinkPolicy {
  int baud = 115200;
  double read_timeout_s = 1.0;
  double reconnect_initial_s = 0.2;
  double reconnect_max_s = 5.0;
  int power_cycle_after_failures = 3;
  int realtime_priority = 0;  ///< SCHED_FIFO priority of the link thread; 0 = normal
};

/// What a device speaks.
class LinkProtocol {
 public:
  virtual ~LinkProtocol() = default;
  /// Called after each (re)open: the start-up. false, or a SerialError naming the reason,
  /// fails the open (reconnect with backoff).
  virtual bool OnOpen(SerialPort& /*port*/) { return true; }
  /// Called on the link thread before each read: a polled device sends its requests here.
  /// Returns how long the link may wait for bytes before calling it again (seconds).
  virtual double OnPoll(SerialPort& /*port*/) { return 0.05; }
  virtual void OnBytes(const std::uint8_t* data, std::size_t size) = 0;
  /// Called before a deliberate close (stop) and before a power cycle: stop the device.
  virtual void OnStop(SerialPort& /*port*/) {}
  /// Called after the link was lost: forget partial frames.
  virtual void OnLost() {}
};

struct LinkCounters {
  std::atomic<long long> connects{0};
  std::atomic<long long> disconnects{0};
  std::atomic<long long> open_failures{0};
  std::atomic<long long> timeouts{0};
  std::atomic<long long> power_cycles{0};
  std::atomic<long long> bytes{0};
};

class DeviceLink {
 public:
  DeviceLink(std::string name, std::string path, LinkPolicy policy, LinkProtocol* protocol,
             FaultLog* faults, std::function<void()> power_cycle = {});
  ~DeviceLink() { Stop(); }

  void Start();
  /// Asks the thread to stop without waiting (stop several links at once, then Stop()).
  void RequestStop();
  /// Stops the thread (sends the protocol's stop commands if connected); idempotent.
  void Stop();
  bool connected() const { return connected_; }
  const LinkCounters& counters() const { return counters_; }
  const std::string& name() const { return name_; }

 private:
  /// Reconnection state of Loop(): failed connections in a row and the next backoff.
  struct Retry {
    int failures = 0;
    double backoff_s = 0.0;
  };

  void Loop();
  /// Opens the port and sends the start commands; false (counted, reported) if that fails.
  bool Connect(SerialPort* port, Retry* retry);
  /// Reads until the device goes away, falls silent or the link stops; true if any byte
  /// arrived (which resets `retry`).
  bool ReadUntilLost(SerialPort* port, std::vector<std::uint8_t>* buffer, Retry* retry);
  /// Counts a failed connection (a failed open, or one that ended without a byte) and
  /// power-cycles the device every policy_.power_cycle_after_failures of them.
  void NoteFailure(SerialPort* port, Retry* retry);
  /// Sleeps up to `s` seconds; false when stopping.
  bool Wait(double s);

  std::string name_, path_;
  LinkPolicy policy_;
  LinkProtocol* protocol_;
  FaultLog* faults_;
  std::function<void()> power_cycle_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> connected_{false};
  std::mutex mutex_;
  std::condition_variable wake_;
  LinkCounters counters_;
};

}  // namespace uwbsar::live
