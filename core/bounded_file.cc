#include "core/bounded_file.h"

#include <filesystem>
#include <fstream>

#include "core/errors.h"

namespace uwbsar {

std::string ReadBoundedFile(const std::string& path, const std::string& what,
                            std::uintmax_t max_bytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw InputError(path + ": cannot open " + what + " file");
  if (fs::is_directory(status)) throw InputError(path + ": " + what + " file is a folder");
  if (!fs::is_regular_file(status)) {
    throw InputError(path + ": " + what + " file is not a regular file (a device, FIFO or folder)");
  }
  const auto too_big = [&] {
    return InputError(path + ": " + what + " file is larger than " +
                      std::to_string(max_bytes >> 20) + " MiB; refused");
  };
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > max_bytes) throw too_big();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open " + what + " file");
  // Read at most one byte past the cap: the size may change, or lie (/proc files say 0).
  std::string text(static_cast<std::size_t>(max_bytes) + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) throw InputError(path + ": cannot read " + what + " file");
  if (static_cast<std::uintmax_t>(in.gcount()) > max_bytes) throw too_big();
  text.resize(static_cast<std::size_t>(in.gcount()));
  return text;
}

}  // namespace uwbsar
