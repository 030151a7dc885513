#include "imaging/imaging_config.h"

#include <string>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const ImagingConfig& m, const std::string& src) {
  Require(m.pixel_size_m > 0, src, "imaging.pixel_size_m", "must be > 0");
  Require(m.coherent_oversampling >= 1 && m.coherent_oversampling <= 64, src,
          "imaging.coherent_oversampling", "must be in [1, 64]");
  Require(m.num_threads >= 0, src, "imaging.num_threads", "must be >= 0");
}

}  // namespace uwbsar
