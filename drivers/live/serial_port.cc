#include "drivers/live/serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>

namespace uwbsar::live {

unsigned BaudConstant(int baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    case 460800:
      return B460800;
    case 921600:
      return B921600;
    case 1000000:
      return B1000000;
    case 2000000:
      return B2000000;
    case 3000000:
      return B3000000;
    default:
      break;
  }
  throw SerialError("unsupported baud rate " + std::to_string(baud));
}

void SerialPort::Open(const std::string& path, int baud) {
  Close();
  const unsigned speed = BaudConstant(baud);
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw SerialError(path + ": cannot open serial device: " + std::strerror(errno));
  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    throw SerialError(path + ": not a serial device: " + why);
  }
  ::cfmakeraw(&tio);
  tio.c_cflag |= CLOCAL | CREAD;
  tio.c_cflag &= ~static_cast<tcflag_t>(CRTSCTS | CSTOPB);
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  if (::cfsetispeed(&tio, speed) != 0 || ::cfsetospeed(&tio, speed) != 0 ||
      ::tcsetattr(fd, TCSANOW, &tio) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    throw SerialError(path + ": cannot configure " + std::to_string(baud) + " baud raw: " + why);
  }
  fd_ = fd;
  path_ = path;
}

void SerialPort::Close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

SerialPort::ReadStatus SerialPort::Read(std::uint8_t* buffer, std::size_t capacity,
                                        double timeout_s, std::size_t* num_read) {
  *num_read = 0;
  if (fd_ < 0) return ReadStatus::kDisconnected;
  pollfd p{fd_, POLLIN, 0};
  const int timeout_ms = static_cast<int>(std::ceil(std::max(0.0, timeout_s) * 1000.0));
  const int ready = ::poll(&p, 1, timeout_ms);
  if (ready < 0) return errno == EINTR ? ReadStatus::kTimeout : ReadStatus::kDisconnected;
  if (ready == 0) return ReadStatus::kTimeout;
  if (p.revents & POLLIN) {
    const ssize_t n = ::read(fd_, buffer, capacity);
    if (n > 0) {
      *num_read = static_cast<std::size_t>(n);
      return ReadStatus::kData;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) return ReadStatus::kTimeout;
    return ReadStatus::kDisconnected;  // EOF or EIO: the device went away
  }
  // POLLHUP / POLLERR / POLLNVAL without data.
  return ReadStatus::kDisconnected;
}

bool SerialPort::Write(const std::uint8_t* data, std::size_t size, double timeout_s) {
  if (fd_ < 0) return false;
  std::size_t done = 0;
  const int timeout_ms = static_cast<int>(std::ceil(std::max(0.0, timeout_s) * 1000.0));
  while (done < size) {
    const ssize_t n = ::write(fd_, data + done, size - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EINTR) return false;
    pollfd p{fd_, POLLOUT, 0};
    if (::poll(&p, 1, timeout_ms) <= 0 || (p.revents & (POLLERR | POLLHUP | POLLNVAL))) {
      return false;
    }
  }
  return true;
}

}  // namespace uwbsar::live
