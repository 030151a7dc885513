#include "drivers/rosbag/bag_writer.h"

#include <exception>
#include <filesystem>
#include <fstream>

#include "core/errors.h"
#include "core/log.h"
#include "drivers/rosbag/bag_metadata.h"
#include "drivers/rosbag/ros_codecs.h"

namespace uwbsar::rosbag {
namespace fs = std::filesystem;

std::string DefaultQosProfileYaml() {
  // What Humble records for a default publisher: reliable, volatile, infinite
  // deadline/lifespan/lease (9223372036.854775807 s), automatic liveliness.
  return "- history: 3\n  depth: 0\n  reliability: 1\n  durability: 2\n"
         "  deadline:\n    sec: 9223372036\n    nsec: 854775807\n"
         "  lifespan:\n    sec: 9223372036\n    nsec: 854775807\n"
         "  liveliness: 1\n"
         "  liveliness_lease_duration:\n    sec: 9223372036\n    nsec: 854775807\n"
         "  avoid_ros_namespace_conventions: false";
}

BagWriter::BagWriter(const std::string& dir, const BagWriterOptions& options)
    : dir_(fs::path(dir).lexically_normal().string()), options_(options) {
  if (!dir_.empty() && dir_.back() == '/') dir_.pop_back();
  partial_dir_ = dir_ + ".partial";
  if (options_.storage != "sqlite3" && options_.storage != "mcap") {
    throw InputError(dir_ + ": unknown storage id '" + options_.storage +
                     "' (supported: sqlite3, mcap)");
  }
  std::error_code ec;
  if (fs::exists(dir_, ec)) throw InputError(dir_ + ": exists already, not overwriting");
  if (fs::exists(partial_dir_, ec)) {
    throw InputError(partial_dir_ + ": exists (an interrupted recording?); remove it first");
  }
  fs::create_directories(partial_dir_, ec);
  if (ec) throw InputError(partial_dir_ + ": cannot create: " + ec.message());
  const std::string file = (fs::path(partial_dir_) / StorageFileName()).string();
  storage_ = options_.storage == "mcap" ? CreateMcapStorage(file, options_.mcap)
                                        : CreateSqliteStorage(file);
}

BagWriter::~BagWriter() {
  if (!storage_) return;
  // Unwinding from a failure (e.g. disk full): finishing the file would only fail again
  // and bury the real error under a second one; the .partial stays as a crash leaves it.
  if (std::uncaught_exceptions() > 0) {
    storage_.reset();
    return;
  }
  try {
    Close();
  } catch (const std::exception& e) {
    Log(LogLevel::kError, dir_ + ": bag not finished: " + e.what());
  }
}

std::string BagWriter::StorageFileName() const {
  return fs::path(dir_).filename().string() + "_0." + (options_.storage == "mcap" ? "mcap" : "db3");
}

int BagWriter::AddTopic(const std::string& name, const std::string& type,
                        const std::string& definition) {
  for (const TopicInfo& t : topics_) {
    if (t.name == name) throw std::invalid_argument("topic " + name + " added twice");
  }
  TopicInfo t;
  t.name = name;
  t.type = type;
  t.offered_qos_profiles = DefaultQosProfileYaml();
  t.message_definition = definition.empty() ? RosMessageDefinition(type) : definition;
  t.definition_encoding = "ros2msg";
  storage_->AddTopic(t);
  topics_.push_back(std::move(t));
  return static_cast<int>(topics_.size() - 1);
}

void BagWriter::Write(int topic, TimestampNs log_time_ns, const std::uint8_t* data,
                      std::size_t size) {
  if (!storage_) throw std::logic_error(dir_ + ": Write() after Close()");
  if (topic < 0 || static_cast<std::size_t>(topic) >= topics_.size()) {
    throw std::invalid_argument("unknown topic id " + std::to_string(topic));
  }
  storage_->Write(topic, log_time_ns, data, size);
  topics_[static_cast<std::size_t>(topic)].message_count++;
  if (message_count_ == 0) start_ns_ = end_ns_ = last_flush_ns_ = log_time_ns;
  start_ns_ = std::min(start_ns_, log_time_ns);
  end_ns_ = std::max(end_ns_, log_time_ns);
  ++message_count_;
  if (static_cast<double>(log_time_ns - last_flush_ns_) >= options_.flush_period_s * 1e9) {
    Flush();
    last_flush_ns_ = log_time_ns;
  }
}

void BagWriter::Flush() {
  if (storage_) storage_->Flush();
}

void BagWriter::Close() {
  if (!storage_) return;
  BagMetadata m;
  m.version = 5;
  m.storage_identifier = options_.storage;
  m.relative_file_paths = {StorageFileName()};
  m.starting_time_ns = start_ns_;
  m.duration_ns = end_ns_ - start_ns_;
  m.message_count = message_count_;
  m.topics = topics_;
  m.files = {BagFileInfo{StorageFileName(), start_ns_, end_ns_ - start_ns_, message_count_}};
  const std::string yaml = BagMetadataToYaml(m);
  auto storage = std::move(storage_);
  storage->Close(yaml);
  storage.reset();
  const fs::path meta = fs::path(partial_dir_) / "metadata.yaml";
  {
    std::ofstream out(meta, std::ios::binary | std::ios::trunc);
    out << yaml;
    if (!out) throw InputError(meta.string() + ": cannot write");
  }
  std::error_code ec;
  fs::rename(partial_dir_, dir_, ec);
  if (ec)
    throw InputError(dir_ + ": cannot rename " + partial_dir_ + " into place: " + ec.message());
}

void BagWriter::EncodeAndWrite(int topic, TimestampNs t, const Float32MultiArray& m) {
  EncodeCdr(m, &buffer_);
  Write(topic, t, buffer_);
}
void BagWriter::EncodeAndWrite(int topic, TimestampNs t, const Odometry& m) {
  EncodeCdr(m, &buffer_);
  Write(topic, t, buffer_);
}
void BagWriter::EncodeAndWrite(int topic, TimestampNs t, const LaserScan& m) {
  EncodeCdr(m, &buffer_);
  Write(topic, t, buffer_);
}
void BagWriter::EncodeAndWrite(int topic, TimestampNs t, const TfMessage& m) {
  EncodeCdr(m, &buffer_);
  Write(topic, t, buffer_);
}

}  // namespace uwbsar::rosbag
