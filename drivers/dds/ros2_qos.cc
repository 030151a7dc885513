#include "drivers/dds/ros2_qos.h"

#include <cctype>

#include "core/errors.h"

namespace uwbsar::dds {

std::string RosTopicToDds(const std::string& ros_topic) {
  if (ros_topic.empty() || ros_topic == "/") {
    throw InputError("ROS topic name is empty");
  }
  for (const char c : ros_topic) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '/')) {
      throw InputError("ROS topic name '" + ros_topic + "': character '" + std::string(1, c) +
                       "' is not allowed (letters, digits, '_' and '/' only)");
    }
  }
  return ros_topic.front() == '/' ? "rt" + ros_topic : "rt/" + ros_topic;
}

std::string DdsTopicToRos(const std::string& dds_topic) {
  if (dds_topic.size() < 4 || dds_topic.compare(0, 3, "rt/") != 0) return "";
  return dds_topic.substr(2);
}

void SetRos2Qos(dds_qos_t* qos, const std::string& reliability, int depth, Durability durability) {
  if (reliability == "reliable") {
    dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  } else if (reliability == "best_effort") {
    dds_qset_reliability(qos, DDS_RELIABILITY_BEST_EFFORT, 0);
  } else {
    throw InputError("dds.reliability: '" + reliability + "' is not one of reliable, best_effort");
  }
  if (depth < 1) {
    throw InputError("dds.history_depth: " + std::to_string(depth) + " is below 1");
  }
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, depth);
  dds_qset_durability(qos, durability == Durability::kTransientLocal
                               ? DDS_DURABILITY_TRANSIENT_LOCAL
                               : DDS_DURABILITY_VOLATILE);
  // rmw_cyclonedds restricts every endpoint to XCDR1 so that XCDR2-capable peers
  // still send classic CDR, the only representation ROS 2 type support decodes.
  const dds_data_representation_id_t xcdr1 = DDS_DATA_REPRESENTATION_XCDR1;
  dds_qset_data_representation(qos, 1, &xcdr1);
}

}  // namespace uwbsar::dds
