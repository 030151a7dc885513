// A POSIX serial port (termios): raw 8N1, a configured baud rate, non-blocking
// file descriptor with reads and writes bounded by timeouts (poll), and a clear
// distinction between "no data yet" and "the device is gone" (USB unplug, pty
// master closed), which the reconnect logic in device_link.h relies on.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace uwbsar::live {

/// A serial device that cannot be opened or configured; what() names the device.
class SerialError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SerialPort {
 public:
  enum class ReadStatus { kData, kTimeout, kDisconnected };

  SerialPort() = default;
  ~SerialPort() { Close(); }
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  /// Opens `path` raw (no echo, no line editing, no flow control) at `baud`.
  /// Throws SerialError naming the path and the reason (missing, busy, no such baud).
  void Open(const std::string& path, int baud);
  void Close();
  bool is_open() const { return fd_ >= 0; }
  const std::string& path() const { return path_; }

  /// Waits up to `timeout_s` for bytes; reads at most `capacity` of them into `buffer`.
  ReadStatus Read(std::uint8_t* buffer, std::size_t capacity, double timeout_s,
                  std::size_t* num_read);
  /// Writes all bytes within `timeout_s`; false if the device is gone or too slow.
  bool Write(const std::uint8_t* data, std::size_t size, double timeout_s);

 private:
  int fd_ = -1;
  std::string path_;
};

/// The termios speed constant of a baud rate; throws SerialError if there is none.
unsigned BaudConstant(int baud);

}  // namespace uwbsar::live
