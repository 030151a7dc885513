#include "drivers/dds/dds_events.h"

namespace uwbsar::dds {

const char* DdsEventKindName(DdsEventKind kind) {
  switch (kind) {
    case DdsEventKind::kPublisherMatched:
      return "publisher_matched";
    case DdsEventKind::kPublisherGone:
      return "publisher_gone";
    case DdsEventKind::kPublisherBack:
      return "publisher_back";
    case DdsEventKind::kTopicSilent:
      return "topic_silent";
    case DdsEventKind::kTopicResumed:
      return "topic_resumed";
    case DdsEventKind::kDuplicate:
      return "duplicate";
    case DdsEventKind::kOutOfOrder:
      return "out_of_order";
    case DdsEventKind::kInvalidSample:
      return "invalid_sample";
    case DdsEventKind::kWrongType:
      return "wrong_type";
    case DdsEventKind::kIncompatibleQos:
      return "incompatible_qos";
    case DdsEventKind::kSamplesLost:
      return "samples_lost";
  }
  return "unknown";
}

}  // namespace uwbsar::dds
