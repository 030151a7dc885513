#include "core/bounded_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "core/errors.h"
#include "core/plain_file.h"

namespace uwbsar {
namespace {

InputError TooBig(const std::string& path, const std::string& what, std::uintmax_t max_bytes,
                  const std::string& budget) {
  const std::string size = max_bytes < (1u << 20) ? std::to_string(max_bytes) + " bytes"
                                                  : std::to_string(max_bytes >> 20) + " MiB";
  return InputError(path + ": " + what + " file is larger than " +
                    (budget.empty() ? size : budget + " (" + size + ")") + "; refused");
}

}  // namespace

std::uintmax_t CheckInputFile(const std::string& path, const std::string& what,
                              std::uintmax_t max_bytes, const std::string& budget) {
  struct stat st {};
  if (path.empty() || ::stat(path.c_str(), &st) != 0) {
    const int error = path.empty() ? ENOENT : errno;
    throw InputError(path + ": cannot open " + what + " file" +
                     (error == ENOENT ? std::string() : std::string(": ") + std::strerror(error)));
  }
  if (S_ISDIR(st.st_mode)) throw InputError(path + ": " + what + " file is a folder");
  if (!S_ISREG(st.st_mode)) {
    throw InputError(path + ": " + what + " file is not a regular file (" +
                     FileKindName(st.st_mode) + ")");
  }
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  if (size > max_bytes) throw TooBig(path, what, max_bytes, budget);
  return size;
}

std::ifstream OpenInputFile(const std::string& path, const std::string& what,
                            std::uintmax_t max_bytes, const std::string& budget) {
  CheckInputFile(path, what, max_bytes, budget);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open " + what + " file: " + std::strerror(errno));
  return in;
}

std::uintmax_t MegabytesToBytes(double megabytes) {
  const double bytes = std::floor(megabytes * 1024.0 * 1024.0);
  if (!(bytes < static_cast<double>(kAnyFileSize))) return kAnyFileSize;
  return bytes > 0 ? static_cast<std::uintmax_t>(bytes) : 0;
}

std::ifstream OpenTextInput(const std::string& path, const std::string& what, double max_mb) {
  return OpenInputFile(path, what, MegabytesToBytes(max_mb), "limits.max_input_file_mb");
}

std::string ReadBoundedFile(const std::string& path, const std::string& what,
                            std::uintmax_t max_bytes) {
  std::ifstream in = OpenInputFile(path, what, max_bytes);
  // Read at most one byte past the cap: the size may change, or lie (/proc files say 0).
  std::string text(static_cast<std::size_t>(max_bytes) + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) throw InputError(path + ": cannot read " + what + " file");
  if (static_cast<std::uintmax_t>(in.gcount()) > max_bytes) {
    throw TooBig(path, what, max_bytes, "");
  }
  text.resize(static_cast<std::size_t>(in.gcount()));
  return text;
}

}  // namespace uwbsar
