// A DDS domain participant for talking to ROS 2 nodes: domain id resolution with
// ROS 2's rule, an optional Cyclone configuration that pins DDS to one network
// interface, and RAII ownership of the participant (deleting it deletes every
// reader, writer and topic created under it).
#pragma once

#include <dds/dds.h>

#include <string>

#include "drivers/dds/dds_config.h"

namespace uwbsar::dds {

/// Largest domain id whose RTPS ports (7400 + 250 * id + offsets) fit in 16 bits.
inline constexpr int kMaxDomainId = 232;

/// The domain to join: `configured` when >= 0, else `ros_domain_id_env` (the value of
/// $ROS_DOMAIN_ID, nullptr or "" when unset -> 0). Throws InputError naming
/// ROS_DOMAIN_ID (or dds.domain_id) for a non-numeric or out-of-range value.
int ResolveDomainId(int configured, const char* ros_domain_id_env);

/// Cyclone XML configuration restricting DDS to `network_interface`. For the loopback
/// interface ("lo"), which has no multicast, discovery goes unicast to 127.0.0.1 with
/// automatic participant indices (up to `max_participants` per domain on the host).
std::string CycloneXmlConfig(const std::string& network_interface, int max_participants = 30);

class Participant {
 public:
  /// Joins the domain of `config` (see ResolveDomainId; reads $ROS_DOMAIN_ID). With a
  /// network_interface, the domain is created from CycloneXmlConfig (replacing
  /// $CYCLONEDDS_URI); participants of one process share one domain, configured by
  /// the first one. Throws DdsError or InputError.
  explicit Participant(const DdsConfig& config);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  dds_entity_t handle() const { return participant_; }
  int domain_id() const { return domain_id_; }

 private:
  int domain_id_ = 0;
  bool owns_domain_ref_ = false;
  dds_entity_t participant_ = 0;
};

}  // namespace uwbsar::dds
