// Errors from the Cyclone DDS C API as exceptions: every call that can fail goes
// through Check(), so a failure names the call and Cyclone's return code text.
#pragma once

#include <dds/dds.h>

#include <stdexcept>
#include <string>

namespace uwbsar::dds {

/// A Cyclone DDS call failed: what() is "DDS <call> failed: <dds_strretcode>".
class DdsError : public std::runtime_error {
 public:
  DdsError(const std::string& call, dds_return_t rc);
  dds_return_t code() const { return code_; }

 private:
  dds_return_t code_;
};

/// Returns `rc` (an entity handle or count) when >= 0, else throws DdsError naming `call`.
dds_return_t Check(dds_return_t rc, const char* call);

}  // namespace uwbsar::dds
