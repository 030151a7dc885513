// What the ROS 2 link reports besides data: publishers coming and going, topics
// falling silent, samples out of order, a wrong type on one of our topics. The
// caller counts and records them (they are not errors: the run goes on).
#pragma once

#include <string>

namespace uwbsar::dds {

enum class DdsEventKind {
  kPublisherMatched,  ///< first publisher of a topic found
  kPublisherGone,     ///< the last publisher of a topic left (or its lease expired)
  kPublisherBack,     ///< a topic has a publisher again after kPublisherGone
  kTopicSilent,       ///< a matched topic sent nothing for dds.silence_timeout_s
  kTopicResumed,      ///< samples again after kTopicSilent
  kDuplicate,         ///< a sample with the same stamp as the previous one
  kOutOfOrder,        ///< a sample stamped before the previous one
  kInvalidSample,     ///< decoded but unusable (non-finite, zero quaternion, empty scan)
  kWrongType,         ///< a remote writer on one of our topics with another type
  kIncompatibleQos,   ///< a publisher exists but its QoS cannot match ours
  kSamplesLost,       ///< DDS reports samples lost in transport
};
inline constexpr int kNumDdsEventKinds = 11;

/// A stable lower-case name ("publisher_gone", ...) for logs and counters.
const char* DdsEventKindName(DdsEventKind kind);

struct DdsEvent {
  DdsEventKind kind = DdsEventKind::kPublisherMatched;
  std::string topic;   ///< ROS 2 topic name, e.g. "/odom"
  std::string detail;  ///< one human-readable line, e.g. "publisher of /odom gone"
};

}  // namespace uwbsar::dds
