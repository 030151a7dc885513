#include "core/plain_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace uwbsar {

std::string FileKindName(mode_t mode) {
  if (S_ISREG(mode)) return "a regular file";
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "a device";
}

int OpenRegularFile(const std::string& path, int flags, std::string* why, int* error) {
  struct stat st {};
  // Looked at first, so that a FIFO is never opened; O_NOFOLLOW and the fstat below hold
  // against a file replaced in between.
  if (::lstat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    *why = "is " + FileKindName(st.st_mode) + ", not a regular file";
    *error = 0;
    return -1;
  }
  const int fd = ::open(path.c_str(), flags | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
  if (fd < 0) {
    *error = errno;
    *why = *error == ELOOP ? "is a symbolic link, not a regular file" : std::strerror(*error);
    return -1;
  }
  if (::fstat(fd, &st) != 0) {
    *error = errno;
    *why = std::strerror(*error);
    ::close(fd);
    return -1;
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    *why = "is " + FileKindName(st.st_mode) + ", not a regular file";
    *error = 0;
    return -1;
  }
  return fd;
}

}  // namespace uwbsar
