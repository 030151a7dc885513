#include "drivers/emulators/pty_device.h"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace uwbsar::live {

PtyDevice::PtyDevice(std::string link_path) : link_path_(std::move(link_path)) { Plug(); }

PtyDevice::~PtyDevice() { Unplug(); }

void PtyDevice::Plug() {
  if (master_ >= 0) return;
  termios tio{};
  ::cfmakeraw(&tio);
  char name[256] = {0};
  int master = -1, slave = -1;
  if (::openpty(&master, &slave, name, &tio, nullptr) != 0) {
    throw std::runtime_error(std::string("openpty: ") + std::strerror(errno));
  }
  ::fcntl(master, F_SETFL, ::fcntl(master, F_GETFL) | O_NONBLOCK);
  ::fcntl(master, F_SETFD, FD_CLOEXEC);
  ::fcntl(slave, F_SETFD, FD_CLOEXEC);
  const std::string tmp = link_path_ + ".tmp";
  ::unlink(tmp.c_str());
  if (::symlink(name, tmp.c_str()) != 0 || ::rename(tmp.c_str(), link_path_.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::close(master);
    ::close(slave);
    throw std::runtime_error(link_path_ + ": cannot link to " + name + ": " + why);
  }
  master_ = master;
  slave_ = slave;
}

void PtyDevice::Unplug() {
  if (master_ < 0) return;
  ::unlink(link_path_.c_str());
  ::close(slave_);
  ::close(master_);
  master_ = slave_ = -1;
}

std::size_t PtyDevice::Write(const std::uint8_t* data, std::size_t size, double timeout_s) {
  if (master_ < 0) return 0;
  std::size_t done = 0;
  const int timeout_ms = static_cast<int>(std::ceil(timeout_s * 1000.0));
  while (done < size) {
    const ssize_t n = ::write(master_, data + done, size - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EINTR) break;
    pollfd p{master_, POLLOUT, 0};
    if (::poll(&p, 1, timeout_ms) <= 0) break;
  }
  return done;
}

std::vector<std::uint8_t> PtyDevice::ReadAvailable() {
  std::vector<std::uint8_t> out;
  if (master_ < 0) return out;
  std::uint8_t buffer[4096];
  while (true) {
    const ssize_t n = ::read(master_, buffer, sizeof(buffer));
    if (n <= 0) break;
    out.insert(out.end(), buffer, buffer + n);
  }
  return out;
}

}  // namespace uwbsar::live
