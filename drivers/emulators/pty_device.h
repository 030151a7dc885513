// A pseudo-terminal that plays a serial device for tests and demos: the emulator
// holds the master side, a driver opens the slave through a stable symlink (as udev
// gives /dev/kobuki), and "unplugging" closes the master and removes the link, so
// the driver sees exactly what a USB unplug does (EIO/HUP, then a missing path).
// Plugging back in creates a fresh pty behind the same link.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace uwbsar::live {

class PtyDevice {
 public:
  /// Creates the pty (raw, no echo) and the symlink `link_path` to its slave.
  /// Throws std::runtime_error when the pty or the link cannot be made.
  explicit PtyDevice(std::string link_path);
  ~PtyDevice();
  PtyDevice(const PtyDevice&) = delete;
  PtyDevice& operator=(const PtyDevice&) = delete;

  void Unplug();
  void Plug();
  bool plugged() const { return master_ >= 0; }
  const std::string& link_path() const { return link_path_; }

  /// Writes bytes as a device would: waits up to `timeout_s` for buffer space, then drops
  /// the rest (a host that does not read loses data). Returns the bytes written.
  std::size_t Write(const std::uint8_t* data, std::size_t size, double timeout_s = 0.05);
  std::size_t Write(const std::vector<std::uint8_t>& bytes, double timeout_s = 0.05) {
    return Write(bytes.data(), bytes.size(), timeout_s);
  }
  /// Bytes the host sent, without waiting.
  std::vector<std::uint8_t> ReadAvailable();

 private:
  std::string link_path_;
  int master_ = -1;
  int slave_ = -1;  ///< kept open so the pty survives while no host has it open
};

}  // namespace uwbsar::live
