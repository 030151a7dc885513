// Watches DDS discovery (the DCPSPublication builtin topic) for writers on our topic
// names whose type is not the one we subscribe with. DDS never matches such a writer
// to our reader, so without this a robot publishing e.g. /odom as
// geometry_msgs/PoseStamped would look like a silent topic.
#pragma once

#include <dds/dds.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "drivers/dds/dds_events.h"

namespace uwbsar::dds {

class PublicationMonitor {
 public:
  /// `expected_types`: DDS topic name ("rt/odom") -> DDS type name. Creates a builtin
  /// reader in `participant` (deleted with it). Throws DdsError.
  PublicationMonitor(dds_entity_t participant, std::map<std::string, std::string> expected_types);

  /// The reader to attach to a waitset (triggers when discovery data is waiting).
  dds_entity_t reader() const { return reader_; }

  /// Takes the pending discovery data; one kWrongType event per offending writer.
  std::vector<DdsEvent> Poll();

 private:
  std::map<std::string, std::string> expected_types_;
  std::set<std::string> reported_writers_;  // GUID bytes of writers already reported
  dds_entity_t reader_ = 0;
};

}  // namespace uwbsar::dds
