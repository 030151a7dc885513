#include "slam/outputs/output_folder.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/errors.h"

namespace uwbsar::slam {

namespace {

/// Creates and removes a file in `dir`; the error text ("" when it worked).
std::string ProbeWritable(const std::string& dir) {
  const std::string probe = dir + "/.uwbsar-write-test-" + std::to_string(::getpid());
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) return std::strerror(errno);
  ::close(fd);
  ::unlink(probe.c_str());
  return {};
}

}  // namespace

void EnsureDirectory(const std::string& dir) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec)) {
    throw InputError(dir + ": output folder is a file");
  }
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    throw InputError(dir + ": cannot create output folder: " + ec.message());
  }
  const std::string error = ProbeWritable(dir);
  if (!error.empty()) throw InputError(dir + ": output folder is not writable: " + error);
}

void CheckOutputFolder(const std::string& dir) {
  std::error_code ec;
  std::filesystem::path p = std::filesystem::absolute(dir, ec);
  while (!std::filesystem::exists(p, ec) && p.has_parent_path() && p != p.parent_path()) {
    p = p.parent_path();
  }
  if (!std::filesystem::is_directory(p, ec)) {
    throw InputError(dir + ": output folder " +
                     (p.string() == std::filesystem::absolute(dir, ec).string()
                          ? std::string("is a file")
                          : "cannot be created: " + p.string() + " is a file"));
  }
  const std::string error = ProbeWritable(p.string());
  if (!error.empty()) throw InputError(dir + ": output folder is not writable: " + error);
}

namespace {

/// `path` absolute, links resolved as far as it exists, without a trailing '/' ("" when it
/// cannot be resolved).
std::filesystem::path Canonical(const std::string& path) {
  std::error_code ec;
  std::filesystem::path p = std::filesystem::weakly_canonical(path, ec);
  if (ec) return {};
  while (!p.has_filename() && p.has_relative_path()) p = p.parent_path();
  return p;
}

/// `inner` is `outer` or lies inside it (both canonical).
bool WithinOrSame(const std::filesystem::path& inner, const std::filesystem::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

}  // namespace

void RefuseOutputOnInput(const std::string& option, const std::string& path,
                         const std::vector<CommandInput>& inputs) {
  if (path.empty()) return;
  const std::filesystem::path out = Canonical(path);
  if (out.empty()) return;  // unresolvable: the output checks name it
  for (const CommandInput& input : inputs) {
    if (input.path.empty()) continue;
    const std::filesystem::path in = Canonical(input.path);
    if (in.empty() || !WithinOrSame(out, in)) continue;
    const bool same = out == in;
    if (input.may_hold_output && !same) continue;
    throw InputError(option + " " + path + (same ? " is " : " lies inside ") + input.what + " " +
                     input.path + ": writing there would change an input; give another " + option);
  }
}

void CheckOutputFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(path + ": output file is a folder");
  }
  std::string parent = std::filesystem::path(path).parent_path().string();
  if (parent.empty()) parent = ".";
  if (!std::filesystem::is_directory(parent, ec)) {
    throw InputError(path + ": output file's folder " + parent + " does not exist");
  }
  const std::string error = ProbeWritable(parent);
  if (!error.empty()) throw InputError(path + ": output file cannot be written: " + error);
}

}  // namespace uwbsar::slam
