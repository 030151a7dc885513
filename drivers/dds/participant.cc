#include "drivers/dds/participant.h"

#include <cerrno>
#include <cstdlib>
#include <map>
#include <mutex>

#include "core/errors.h"
#include "drivers/dds/dds_check.h"

namespace uwbsar::dds {
namespace {

// Domains created with an explicit configuration, shared by the participants of this
// process: Cyclone refuses a second dds_create_domain for a live domain id, and
// deleting a domain deletes every participant in it, so it lives while any uses it.
struct DomainRef {
  dds_entity_t domain = 0;
  int users = 0;
};
std::mutex g_domains_mutex;
std::map<int, DomainRef>& Domains() {
  static std::map<int, DomainRef> domains;
  return domains;
}

void AcquireDomain(int domain_id, const std::string& xml) {
  std::lock_guard<std::mutex> lock(g_domains_mutex);
  DomainRef& ref = Domains()[domain_id];
  if (ref.users == 0) {
    const dds_entity_t domain =
        dds_create_domain(static_cast<dds_domainid_t>(domain_id), xml.c_str());
    if (domain < 0) {
      Domains().erase(domain_id);
      throw DdsError("dds_create_domain(" + std::to_string(domain_id) + ")", domain);
    }
    ref.domain = domain;
  }
  ++ref.users;
}

void ReleaseDomain(int domain_id) {
  std::lock_guard<std::mutex> lock(g_domains_mutex);
  auto it = Domains().find(domain_id);
  if (it == Domains().end()) return;
  if (--it->second.users == 0) {
    dds_delete(it->second.domain);
    Domains().erase(it);
  }
}

}  // namespace

int ResolveDomainId(int configured, const char* ros_domain_id_env) {
  if (configured >= 0) {
    if (configured > kMaxDomainId) {
      throw InputError("dds.domain_id: " + std::to_string(configured) + " is above " +
                       std::to_string(kMaxDomainId));
    }
    return configured;
  }
  if (ros_domain_id_env == nullptr || *ros_domain_id_env == '\0') return 0;
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(ros_domain_id_env, &end, 10);
  if (errno != 0 || *end != '\0' || value < 0 || value > kMaxDomainId) {
    throw InputError(std::string("ROS_DOMAIN_ID: '") + ros_domain_id_env +
                     "' is not a domain id (an integer 0.." + std::to_string(kMaxDomainId) + ")");
  }
  return static_cast<int>(value);
}

std::string CycloneXmlConfig(const std::string& network_interface, int max_participants) {
  const bool loopback = network_interface == "lo" || network_interface == "127.0.0.1";
  std::string xml =
      "<General><Interfaces><NetworkInterface name=\"" + network_interface + "\"/></Interfaces>";
  if (loopback) xml += "<AllowMulticast>false</AllowMulticast>";
  xml += "</General>";
  if (loopback) {
    xml +=
        "<Discovery><Peers><Peer address=\"127.0.0.1\"/></Peers>"
        "<ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>" +
        std::to_string(max_participants) + "</MaxAutoParticipantIndex></Discovery>";
  }
  return xml;
}

Participant::Participant(const DdsConfig& config)
    : domain_id_(ResolveDomainId(config.domain_id, std::getenv("ROS_DOMAIN_ID"))) {
  if (!config.network_interface.empty()) {
    AcquireDomain(domain_id_, CycloneXmlConfig(config.network_interface));
    owns_domain_ref_ = true;
  }
  participant_ = dds_create_participant(static_cast<dds_domainid_t>(domain_id_), nullptr, nullptr);
  if (participant_ < 0) {
    const dds_return_t rc = participant_;
    if (owns_domain_ref_) ReleaseDomain(domain_id_);
    throw DdsError("dds_create_participant(" + std::to_string(domain_id_) + ")", rc);
  }
}

Participant::~Participant() {
  dds_delete(participant_);
  if (owns_domain_ref_) ReleaseDomain(domain_id_);
}

}  // namespace uwbsar::dds
