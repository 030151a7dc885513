#include "drivers/dds/dds_check.h"

namespace uwbsar::dds {

DdsError::DdsError(const std::string& call, dds_return_t rc)
    : std::runtime_error("DDS " + call + " failed: " + dds_strretcode(rc)), code_(rc) {}

dds_return_t Check(dds_return_t rc, const char* call) {
  if (rc < 0) throw DdsError(call, rc);
  return rc;
}

}  // namespace uwbsar::dds
