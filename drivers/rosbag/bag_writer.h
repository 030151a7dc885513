// Writing a ROS 2 bag directory that `ros2 bag info/play` (Humble and later),
// Foxglove and the Python `rosbags` open: one storage file, sqlite3 in the Humble
// layout (schema 3) or MCAP (ros2 profile, chunked, indexed), and a version-5
// metadata.yaml. Incremental, for live recording: open, AddTopic, Write message by
// message, Close. The bag is built under `<dir>.partial` and renamed to `<dir>` by
// Close(), so `<dir>` only ever names a complete bag; an interrupted recording leaves
// `<dir>.partial` whose storage file holds everything up to the last flush.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "drivers/rosbag/bag_storage.h"
#include "drivers/rosbag/ros_messages.h"

namespace uwbsar::rosbag {

struct BagWriterOptions {
  std::string storage = "sqlite3";  ///< "sqlite3" or "mcap"
  McapWriteOptions mcap;            ///< chunk compression and size (MCAP only)
  /// Flush when the receive time of written messages has advanced this much since the
  /// last flush. Message time, not wall-clock time, so the same input gives the same
  /// bytes; live recording (receive time = now) thereby flushes at least every period.
  double flush_period_s = 1.0;
};

class BagWriter {
 public:
  /// Throws InputError if `dir` or `<dir>.partial` exists or cannot be created, or the
  /// storage id is unknown.
  BagWriter(const std::string& dir, const BagWriterOptions& options = {});
  /// Closes the bag if Close() was not called (errors are logged, not thrown).
  ~BagWriter();
  BagWriter(const BagWriter&) = delete;
  BagWriter& operator=(const BagWriter&) = delete;

  /// Registers a topic and returns its id. Known types (ros_messages.h) get their
  /// ros2msg definition by default; pass `definition` for other types (MCAP readers
  /// such as Foxglove and rosbags decode with it), else an empty one is stored.
  int AddTopic(const std::string& name, const std::string& type,
               const std::string& definition = "");
  /// Writes one serialized (CDR) message received at `log_time_ns`.
  void Write(int topic, TimestampNs log_time_ns, const std::uint8_t* data, std::size_t size);
  void Write(int topic, TimestampNs log_time_ns, const std::vector<std::uint8_t>& cdr) {
    Write(topic, log_time_ns, cdr.data(), cdr.size());
  }
  /// Encodes and writes a message.
  template <class Message>
  void WriteMessage(int topic, TimestampNs log_time_ns, const Message& msg);
  /// Makes everything written so far durable in the storage file.
  void Flush();
  /// Finishes the storage file, writes metadata.yaml and renames the bag into place.
  void Close();

  const std::string& path() const { return dir_; }
  /// The storage file as it will be named after Close().
  std::string StorageFileName() const;

 private:
  void EncodeAndWrite(int topic, TimestampNs t, const Float32MultiArray& m);
  void EncodeAndWrite(int topic, TimestampNs t, const Odometry& m);
  void EncodeAndWrite(int topic, TimestampNs t, const LaserScan& m);
  void EncodeAndWrite(int topic, TimestampNs t, const TfMessage& m);

  std::string dir_, partial_dir_;
  BagWriterOptions options_;
  std::unique_ptr<StorageWriter> storage_;
  std::vector<TopicInfo> topics_;
  std::uint64_t message_count_ = 0;
  TimestampNs start_ns_ = 0, end_ns_ = 0;
  TimestampNs last_flush_ns_ = 0;
  std::vector<std::uint8_t> buffer_;
};

template <class Message>
void BagWriter::WriteMessage(int topic, TimestampNs log_time_ns, const Message& msg) {
  EncodeAndWrite(topic, log_time_ns, msg);
}

/// rosbag2's default offered QoS profile (reliable, volatile, keep last), as YAML text.
std::string DefaultQosProfileYaml();

}  // namespace uwbsar::rosbag
