#include "drivers/rosbag/bag_reader.h"

#include <unistd.h>
#include <zstd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "core/bounded_file.h"
#include "core/errors.h"
#include "core/interrupt_cleanup.h"
#include "drivers/rosbag/bag_metadata.h"

namespace uwbsar::rosbag {
namespace fs = std::filesystem;

namespace {

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Decompresses a rosbag2 file-compressed storage (`x.db3.zstd`) in one streaming pass to a
// private temporary file in $TMPDIR, removed when the reader closes, on every error and on
// Ctrl-C (core/interrupt_cleanup.h). The output may not exceed `cap_bytes` (from the
// metadata's message count): a small file of zeros must not fill the disk. A failed write
// names the temporary file and its cause (no space left on device), not the input.
std::string DecompressFileToTemp(const std::string& path, std::uint64_t cap_bytes,
                                 std::unique_ptr<RemoveOnInterrupt>* guard) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open");
  const char* tmpdir = std::getenv("TMPDIR");
  std::string templ =
      (fs::path(tmpdir && *tmpdir ? tmpdir : "/tmp") / "uwbsar_bag_XXXXXX").string();
  const int fd = ::mkstemp(templ.data());
  if (fd < 0) {
    throw std::runtime_error(templ + ": cannot create a temporary file to decompress " + path +
                             " into: " + std::strerror(errno));
  }
  *guard = std::make_unique<RemoveOnInterrupt>(templ);
  const auto fail = [&](const auto& error) {
    ::close(fd);
    std::remove(templ.c_str());
    guard->reset();
    throw error;
  };
  std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> ctx(ZSTD_createDCtx(), &ZSTD_freeDCtx);
  std::vector<char> ibuf(ZSTD_DStreamInSize()), obuf(ZSTD_DStreamOutSize());
  std::size_t last = 0;
  std::uint64_t written = 0;
  bool any = false;
  while (in) {
    in.read(ibuf.data(), static_cast<std::streamsize>(ibuf.size()));
    const auto n = static_cast<std::size_t>(in.gcount());
    if (n == 0) break;
    any = true;
    ZSTD_inBuffer input{ibuf.data(), n, 0};
    while (input.pos < input.size) {
      ZSTD_outBuffer output{obuf.data(), obuf.size(), 0};
      last = ZSTD_decompressStream(ctx.get(), &output, &input);
      if (ZSTD_isError(last)) {
        fail(InputError(path + ": corrupt zstd file: " + ZSTD_getErrorName(last)));
      }
      written += output.pos;
      if (written > cap_bytes) {
        fail(InputError(path + ": decompresses to more than " + std::to_string(cap_bytes) +
                        " bytes, the most its metadata's message count allows"));
      }
      for (std::size_t done = 0; done < output.pos;) {
        const ssize_t w = ::write(fd, obuf.data() + done, output.pos - done);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) {
          fail(std::runtime_error(templ + ": cannot write the decompressed copy of " + path + ": " +
                                  std::strerror(w < 0 ? errno : ENOSPC) +
                                  " (set TMPDIR to a folder with more space)"));
        }
        done += static_cast<std::size_t>(w);
      }
    }
  }
  if (::close(fd) != 0) {
    const int error = errno;
    std::remove(templ.c_str());
    guard->reset();
    throw std::runtime_error(templ + ": cannot write the decompressed copy of " + path + ": " +
                             std::strerror(error));
  }
  if (!any || last != 0) {
    std::remove(templ.c_str());
    guard->reset();
    throw InputError(path + ": truncated zstd file (the compressed data ends mid-frame)");
  }
  return templ;
}

}  // namespace

std::uint64_t DecompressedSizeCap(std::uint64_t message_count) {
  constexpr std::uint64_t kBase = 64ull << 20;       // schema, indexes, page slack
  constexpr std::uint64_t kPerMessage = 1ull << 20;  // one message at most 1 MiB
  constexpr std::uint64_t kMax = 1ull << 40;         // and never more than 1 TiB
  return std::min(kMax, kBase + std::min(message_count, kMax / kPerMessage) * kPerMessage);
}

struct BagReader::File {
  std::unique_ptr<StorageReader> storage;
  std::vector<int> topic_map;  // storage topic index -> BagInfo topic index
  StorageMessage current;
  std::string temp_path;  // decompressed copy to delete, if any
  std::unique_ptr<RemoveOnInterrupt> temp_guard;
  ~File() {
    storage.reset();
    if (!temp_path.empty()) std::remove(temp_path.c_str());
  }
};

std::string DetectStorage(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[16] = {};
  in.read(head, sizeof(head));
  if (in.gcount() >= 8 && std::memcmp(head, "\x89MCAP0\r\n", 8) == 0) return "mcap";
  if (in.gcount() == 16 && std::memcmp(head, "SQLite format 3", 16) == 0) return "sqlite3";
  return {};
}

BagReader::BagReader(const std::string& path, const BagReadOptions& options) : options_(options) {
  info_.path = path;
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    OpenDirectory(path);
  } else if (fs::exists(path, ec)) {
    OpenBareFile(path);
  } else {
    throw InputError(path + ": no such bag directory or file");
  }
  for (std::size_t i = 0; i < files_.size(); ++i) {
    info_.size_bytes += fs::file_size(info_.files[i], ec);
    if (Advance(i)) heap_.push_back(i);
  }
  std::make_heap(heap_.begin(), heap_.end(), [this](std::size_t a, std::size_t b) {
    const auto ta = files_[a]->current.log_time_ns, tb = files_[b]->current.log_time_ns;
    return ta != tb ? ta > tb : a > b;
  });
}

BagReader::~BagReader() = default;

int BagReader::FindTopic(const std::string& name) const {
  for (std::size_t i = 0; i < info_.topics.size(); ++i) {
    if (info_.topics[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

int BagReader::MergeTopic(const TopicInfo& t) {
  for (std::size_t i = 0; i < info_.topics.size(); ++i) {
    TopicInfo& known = info_.topics[i];
    if (known.name == t.name && known.type == t.type) {
      if (known.message_definition.empty()) {
        known.message_definition = t.message_definition;
        known.definition_encoding = t.definition_encoding;
      }
      if (known.offered_qos_profiles.empty()) known.offered_qos_profiles = t.offered_qos_profiles;
      return static_cast<int>(i);
    }
  }
  info_.topics.push_back(t);
  return static_cast<int>(info_.topics.size() - 1);
}

void BagReader::OpenDirectory(const std::string& dir) {
  const std::string meta_path = (fs::path(dir) / "metadata.yaml").string();
  if (!fs::exists(meta_path)) {
    throw InputError(meta_path +
                     ": missing: not a rosbag2 bag directory (pass a .db3 or .mcap file "
                     "directly, or recreate it with `ros2 bag reindex`)");
  }
  const BagMetadata m = ReadBagMetadata(meta_path);
  if (m.storage_identifier != "sqlite3" && m.storage_identifier != "mcap") {
    throw InputError(meta_path + ": field 'storage_identifier': unknown storage id '" +
                     m.storage_identifier + "' (supported: sqlite3, mcap)");
  }
  const std::string mode = Lower(m.compression_mode);
  if (!mode.empty() && mode != "none") {
    if (m.compression_format != "zstd") {
      throw InputError(meta_path + ": field 'compression_format': '" + m.compression_format +
                       "' is not supported (only zstd)");
    }
    if (mode != "file" && mode != "message") {
      throw InputError(meta_path + ": field 'compression_mode': unknown mode '" +
                       m.compression_mode + "' (FILE or MESSAGE)");
    }
  }
  message_compression_ = mode == "message";
  info_.storage_identifier = m.storage_identifier;
  info_.metadata_version = m.version;
  info_.ros_distro = m.ros_distro;
  info_.compression_format = m.compression_format;
  info_.compression_mode = m.compression_mode;
  info_.message_count = m.message_count;
  info_.start_ns = m.starting_time_ns;
  info_.end_ns = m.starting_time_ns + m.duration_ns;
  for (const TopicInfo& t : m.topics) MergeTopic(t);
  if (m.relative_file_paths.empty()) {
    throw InputError(meta_path + ": field 'relative_file_paths': lists no storage file");
  }
  for (const std::string& rel : m.relative_file_paths) {
    // Foxy wrote paths relative to the bag's parent ("bag/bag_0.db3").
    fs::path p = fs::path(dir) / rel;
    if (!fs::exists(p)) p = fs::path(dir) / fs::path(rel).filename();
    if (!fs::exists(p)) {
      throw InputError(meta_path + ": lists storage file '" + rel + "' which does not exist");
    }
    CheckInputFile(p.string(), "bag storage");  // a FIFO would block the open
    auto file = std::make_unique<File>();
    std::string open_path = p.string();
    if (mode == "file") {
      // The storage file's message count (metadata version >= 5), else the bag's.
      std::uint64_t messages = m.message_count;
      for (const BagFileInfo& f : m.files) {
        if (f.path == rel) messages = f.message_count;
      }
      file->temp_path =
          DecompressFileToTemp(open_path, DecompressedSizeCap(messages), &file->temp_guard);
      open_path = file->temp_path;
    }
    try {
      file->storage = m.storage_identifier == "mcap" ? OpenMcapStorage(open_path, options_)
                                                     : OpenSqliteStorage(open_path);
    } catch (const InputError& e) {
      if (file->temp_path.empty()) throw;
      throw InputError(p.string() + " (decompressed): " + e.what());
    }
    info_.files.push_back(p.string());
    for (const TopicInfo& t : file->storage->Topics()) file->topic_map.push_back(MergeTopic(t));
    files_.push_back(std::move(file));
  }
}

void BagReader::OpenBareFile(const std::string& path) {
  CheckInputFile(path, "bag");  // a FIFO would block the open
  const std::string kind = DetectStorage(path);
  if (kind.empty()) {
    throw InputError(path +
                     ": unknown storage: neither a sqlite3 (.db3) nor an MCAP file "
                     "(bad magic)");
  }
  auto file = std::make_unique<File>();
  file->storage = kind == "mcap" ? OpenMcapStorage(path, options_) : OpenSqliteStorage(path);
  const StorageStats stats = file->storage->Stats();
  info_.storage_identifier = kind;
  info_.message_count = stats.message_count;
  info_.start_ns = stats.start_ns;
  info_.end_ns = stats.end_ns;
  info_.files.push_back(path);
  for (const TopicInfo& t : file->storage->Topics()) file->topic_map.push_back(MergeTopic(t));
  files_.push_back(std::move(file));
}

bool BagReader::Advance(std::size_t i) {
  File& f = *files_[i];
  if (!f.storage->Next(&f.current)) return false;
  return true;
}

bool BagReader::Next(BagMessage* msg) {
  const auto later = [this](std::size_t a, std::size_t b) {
    const auto ta = files_[a]->current.log_time_ns, tb = files_[b]->current.log_time_ns;
    return ta != tb ? ta > tb : a > b;
  };
  // The previous message's file moves on only now, so its bytes stayed valid.
  if (last_ >= 0) {
    const auto i = static_cast<std::size_t>(last_);
    last_ = -1;
    if (Advance(i)) {
      heap_.push_back(i);
      std::push_heap(heap_.begin(), heap_.end(), later);
    }
  }
  if (heap_.empty()) return false;
  std::pop_heap(heap_.begin(), heap_.end(), later);
  const std::size_t i = heap_.back();
  heap_.pop_back();
  last_ = static_cast<long>(i);
  const File& f = *files_[i];
  const StorageMessage& m = f.current;
  if (m.topic < 0 || static_cast<std::size_t>(m.topic) >= f.topic_map.size()) {
    throw InputError(f.storage->Path() + ": message refers to an unknown topic");
  }
  msg->topic = f.topic_map[static_cast<std::size_t>(m.topic)];
  msg->file = static_cast<int>(i);
  msg->log_time_ns = m.log_time_ns;
  msg->data = m.data;
  msg->size = m.size;
  if (message_compression_) {
    const unsigned long long n = ZSTD_getFrameContentSize(m.data, m.size);
    if (n == ZSTD_CONTENTSIZE_ERROR || n == ZSTD_CONTENTSIZE_UNKNOWN || n > (1ull << 30)) {
      throw InputError(f.storage->Path() + ": message at " + std::to_string(m.log_time_ns) +
                       " ns on " + info_.topics[static_cast<std::size_t>(msg->topic)].name +
                       " is not a valid zstd frame (bag compression_mode MESSAGE)");
    }
    decompressed_.resize(static_cast<std::size_t>(n));
    const std::size_t got =
        ZSTD_decompress(decompressed_.data(), decompressed_.size(), m.data, m.size);
    if (ZSTD_isError(got) || got != n) {
      throw InputError(f.storage->Path() + ": corrupt zstd message at " +
                       std::to_string(m.log_time_ns) + " ns");
    }
    msg->data = decompressed_.data();
    msg->size = decompressed_.size();
  }
  return true;
}

}  // namespace uwbsar::rosbag
