#include "drivers/dds/publication_monitor.h"

#include <utility>

#include "drivers/dds/dds_check.h"
#include "drivers/dds/ros2_qos.h"

namespace uwbsar::dds {

PublicationMonitor::PublicationMonitor(dds_entity_t participant,
                                       std::map<std::string, std::string> expected_types)
    : expected_types_(std::move(expected_types)) {
  reader_ =
      Check(dds_create_reader(participant, DDS_BUILTIN_TOPIC_DCPSPUBLICATION, nullptr, nullptr),
            "dds_create_reader(DCPSPublication)");
}

std::vector<DdsEvent> PublicationMonitor::Poll() {
  std::vector<DdsEvent> events;
  constexpr int kBatch = 16;
  void* samples[kBatch];
  dds_sample_info_t infos[kBatch];
  for (;;) {
    samples[0] = nullptr;
    const dds_return_t n =
        Check(dds_take(reader_, samples, infos, kBatch, kBatch), "dds_take(DCPSPublication)");
    for (dds_return_t i = 0; i < n; ++i) {
      if (!infos[i].valid_data) continue;
      const auto* endpoint = static_cast<const dds_builtintopic_endpoint_t*>(samples[i]);
      if (endpoint->topic_name == nullptr || endpoint->type_name == nullptr) continue;
      const auto expected = expected_types_.find(endpoint->topic_name);
      if (expected == expected_types_.end() || expected->second == endpoint->type_name) continue;
      const std::string guid(reinterpret_cast<const char*>(endpoint->key.v),
                             sizeof(endpoint->key.v));
      if (!reported_writers_.insert(guid).second) continue;
      DdsEvent event;
      event.kind = DdsEventKind::kWrongType;
      event.topic = DdsTopicToRos(endpoint->topic_name);
      event.detail = "topic " + event.topic + " published with type " + endpoint->type_name +
                     ", expected " + expected->second;
      events.push_back(std::move(event));
    }
    if (n > 0) dds_return_loan(reader_, samples, n);
    if (n < kBatch) break;
  }
  return events;
}

}  // namespace uwbsar::dds
