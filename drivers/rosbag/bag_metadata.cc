#include "drivers/rosbag/bag_metadata.h"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "core/bounded_file.h"
#include "core/errors.h"

namespace uwbsar::rosbag {
namespace {

class Parser {
 public:
  explicit Parser(const std::string& name) : name_(name) {}

  [[noreturn]] void Fail(const YAML::Node& node, const std::string& field,
                         const std::string& what) const {
    std::string where = name_;
    if (node.IsDefined() && node.Mark().line >= 0) {
      where += ":" + std::to_string(node.Mark().line + 1);
    }
    throw InputError(where + ": field '" + field + "': " + what);
  }

  YAML::Node Required(const YAML::Node& parent, const std::string& key,
                      const std::string& path) const {
    // A scalar or list where a mapping belongs: name the mapping (yaml-cpp would throw a
    // bare BadSubscript naming no file).
    if (!parent.IsMap()) {
      const std::size_t dot = path.rfind('.');
      Fail(parent, dot == std::string::npos ? path : path.substr(0, dot),
           dot == std::string::npos ? "its parent is not a map" : "is not a map");
    }
    const YAML::Node n = parent[key];
    if (!n.IsDefined() || n.IsNull()) Fail(parent, path, "missing");
    return n;
  }

  template <class T>
  T As(const YAML::Node& n, const std::string& path) const {
    try {
      return n.as<T>();
    } catch (const YAML::Exception&) {
      Fail(n, path, "has the wrong type or value");
    }
  }

  template <class T>
  T Get(const YAML::Node& parent, const std::string& key, const std::string& path) const {
    return As<T>(Required(parent, key, path), path);
  }

  template <class T>
  T Optional(const YAML::Node& parent, const std::string& key, const std::string& path,
             T fallback) const {
    if (!parent.IsMap()) Fail(parent, path, "its parent is not a map");
    const YAML::Node n = parent[key];
    if (!n.IsDefined() || n.IsNull()) return fallback;
    return As<T>(n, path);
  }

  // Time fields are maps: duration: {nanoseconds: N}, starting_time:
  // {nanoseconds_since_epoch: N}.
  std::int64_t Nested(const YAML::Node& parent, const std::string& key, const std::string& inner,
                      const std::string& path) const {
    const YAML::Node n = Required(parent, key, path);
    return Get<std::int64_t>(n, inner, path + "." + inner);
  }

 private:
  const std::string& name_;
};

}  // namespace

namespace {

/// One entry of topics_with_message_count.
TopicInfo ParseTopic(const Parser& p, const YAML::Node& entry) {
  const std::string field = "topics_with_message_count.topic_metadata";
  const YAML::Node tm = p.Required(entry, "topic_metadata", field);
  TopicInfo t;
  t.name = p.Get<std::string>(tm, "name", field + ".name");
  t.type = p.Get<std::string>(tm, "type", field + ".type");
  t.serialization_format =
      p.Optional<std::string>(tm, "serialization_format", field + ".serialization_format", "cdr");
  const YAML::Node qos = tm["offered_qos_profiles"];
  if (qos.IsDefined() && !qos.IsNull()) {
    if (qos.IsScalar()) {
      t.offered_qos_profiles = qos.Scalar();
    } else {  // version 9: a YAML list
      YAML::Emitter e;
      e << qos;
      t.offered_qos_profiles = e.c_str();
    }
  }
  t.type_description_hash =
      p.Optional<std::string>(tm, "type_description_hash", field + ".type_description_hash", "");
  t.message_count =
      p.Get<std::uint64_t>(entry, "message_count", "topics_with_message_count.message_count");
  return t;
}

/// One entry of files.
BagFileInfo ParseFileInfo(const Parser& p, const YAML::Node& f) {
  BagFileInfo info;
  info.path = p.Get<std::string>(f, "path", "files.path");
  info.starting_time_ns =
      p.Nested(f, "starting_time", "nanoseconds_since_epoch", "files.starting_time");
  info.duration_ns = p.Nested(f, "duration", "nanoseconds", "files.duration");
  info.message_count = p.Get<std::uint64_t>(f, "message_count", "files.message_count");
  return info;
}

BagMetadata Parse(const std::string& text, const std::string& name);

}  // namespace

BagMetadata ParseBagMetadata(const std::string& text, const std::string& name) {
  try {
    return Parse(text, name);
  } catch (const YAML::Exception& e) {
    // Anything the field checks did not foresee is still bad input naming the file and line.
    throw InputError(name + (e.mark.line >= 0 ? ":" + std::to_string(e.mark.line + 1) : "") +
                     ": unexpected YAML shape: " + e.msg);
  }
}

namespace {

BagMetadata Parse(const std::string& text, const std::string& name) {
  YAML::Node doc;
  try {
    doc = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(name + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  }
  const Parser p(name);
  const YAML::Node root =
      p.Required(doc, "rosbag2_bagfile_information", "rosbag2_bagfile_information");
  if (!root.IsMap()) p.Fail(root, "rosbag2_bagfile_information", "is not a map");
  BagMetadata m;
  m.version = p.Get<int>(root, "version", "version");
  if (m.version < 1) p.Fail(root["version"], "version", "must be >= 1");
  m.storage_identifier = p.Get<std::string>(root, "storage_identifier", "storage_identifier");
  const YAML::Node files = p.Required(root, "relative_file_paths", "relative_file_paths");
  if (!files.IsSequence()) p.Fail(files, "relative_file_paths", "is not a list");
  for (const auto& f : files)
    m.relative_file_paths.push_back(p.As<std::string>(f, "relative_file_paths"));
  m.duration_ns = p.Nested(root, "duration", "nanoseconds", "duration");
  m.starting_time_ns = p.Nested(root, "starting_time", "nanoseconds_since_epoch", "starting_time");
  m.message_count = p.Get<std::uint64_t>(root, "message_count", "message_count");
  const YAML::Node topics = root["topics_with_message_count"];
  if (topics.IsDefined() && !topics.IsNull()) {
    if (!topics.IsSequence()) p.Fail(topics, "topics_with_message_count", "is not a list");
    for (const auto& entry : topics) m.topics.push_back(ParseTopic(p, entry));
  }
  m.compression_format =
      p.Optional<std::string>(root, "compression_format", "compression_format", "");
  m.compression_mode = p.Optional<std::string>(root, "compression_mode", "compression_mode", "");
  const YAML::Node file_list = root["files"];
  if (file_list.IsDefined() && file_list.IsSequence()) {
    for (const auto& f : file_list) m.files.push_back(ParseFileInfo(p, f));
  }
  m.ros_distro = p.Optional<std::string>(root, "ros_distro", "ros_distro", "");
  // Times must add up without overflow: the bag ends at starting_time + duration.
  if (m.duration_ns < 0) p.Fail(root["duration"], "duration", "is negative");
  if (m.starting_time_ns < 0) p.Fail(root["starting_time"], "starting_time", "is negative");
  if (m.duration_ns > std::numeric_limits<std::int64_t>::max() - m.starting_time_ns) {
    p.Fail(root["duration"], "duration",
           "starting_time + duration is past the last representable time (year 2262)");
  }
  return m;
}

}  // namespace

BagMetadata ReadBagMetadata(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    throw InputError(path + ": missing or unreadable (no bag metadata)");
  }
  return ParseBagMetadata(ReadBoundedFile(path, "bag metadata"), path);
}

std::string BagMetadataToYaml(const BagMetadata& m) {
  YAML::Emitter e;
  e << YAML::BeginMap << YAML::Key << "rosbag2_bagfile_information" << YAML::Value
    << YAML::BeginMap;
  e << YAML::Key << "version" << YAML::Value << m.version;
  e << YAML::Key << "storage_identifier" << YAML::Value << m.storage_identifier;
  e << YAML::Key << "duration" << YAML::Value << YAML::BeginMap << YAML::Key << "nanoseconds"
    << YAML::Value << m.duration_ns << YAML::EndMap;
  e << YAML::Key << "starting_time" << YAML::Value << YAML::BeginMap << YAML::Key
    << "nanoseconds_since_epoch" << YAML::Value << m.starting_time_ns << YAML::EndMap;
  e << YAML::Key << "message_count" << YAML::Value << m.message_count;
  e << YAML::Key << "topics_with_message_count" << YAML::Value << YAML::BeginSeq;
  for (const auto& t : m.topics) {
    e << YAML::BeginMap << YAML::Key << "topic_metadata" << YAML::Value << YAML::BeginMap;
    e << YAML::Key << "name" << YAML::Value << t.name;
    e << YAML::Key << "type" << YAML::Value << t.type;
    e << YAML::Key << "serialization_format" << YAML::Value << t.serialization_format;
    e << YAML::Key << "offered_qos_profiles" << YAML::Value << YAML::DoubleQuoted
      << t.offered_qos_profiles;
    if (m.version >= 7) {
      e << YAML::Key << "type_description_hash" << YAML::Value << t.type_description_hash;
    }
    e << YAML::EndMap << YAML::Key << "message_count" << YAML::Value << t.message_count
      << YAML::EndMap;
  }
  e << YAML::EndSeq;
  e << YAML::Key << "compression_format" << YAML::Value << YAML::DoubleQuoted
    << m.compression_format;
  e << YAML::Key << "compression_mode" << YAML::Value << YAML::DoubleQuoted << m.compression_mode;
  e << YAML::Key << "relative_file_paths" << YAML::Value << YAML::BeginSeq;
  for (const auto& f : m.relative_file_paths) e << f;
  e << YAML::EndSeq;
  if (m.version >= 5) {
    e << YAML::Key << "files" << YAML::Value << YAML::BeginSeq;
    for (const auto& f : m.files) {
      e << YAML::BeginMap << YAML::Key << "path" << YAML::Value << f.path;
      e << YAML::Key << "starting_time" << YAML::Value << YAML::BeginMap << YAML::Key
        << "nanoseconds_since_epoch" << YAML::Value << f.starting_time_ns << YAML::EndMap;
      e << YAML::Key << "duration" << YAML::Value << YAML::BeginMap << YAML::Key << "nanoseconds"
        << YAML::Value << f.duration_ns << YAML::EndMap;
      e << YAML::Key << "message_count" << YAML::Value << f.message_count << YAML::EndMap;
    }
    e << YAML::EndSeq;
  }
  if (m.version >= 8) e << YAML::Key << "ros_distro" << YAML::Value << m.ros_distro;
  e << YAML::EndMap << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

}  // namespace uwbsar::rosbag
