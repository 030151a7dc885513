#include "imaging/imaging_config.h"

#include <cmath>
#include <string>

#include "core/config_require.h"

namespace uwbsar {

using config_validation::Require;

void Validate(const ImagingConfig& m, const std::string& src) {
  Require(m.pixel_size_m > 0, src, "imaging.pixel_size_m", "must be > 0");
  Require(m.coherent_oversampling >= 1 && m.coherent_oversampling <= 64, src,
          "imaging.coherent_oversampling", "must be in [1, 64]");
  Require(m.num_threads >= 0, src, "imaging.num_threads", "must be >= 0");
  const FfbpConfig& f = m.ffbp;
  Require(f.base_scans >= 1 && f.base_scans <= 1024, src, "imaging.ffbp.base_scans",
          "must be in [1, 1024]");
  Require(f.merge_factor >= 2 && f.merge_factor <= 16, src, "imaging.ffbp.merge_factor",
          "must be in [2, 16]");
  Require(f.levels >= 0 && f.levels <= 8, src, "imaging.ffbp.levels", "must be in [0, 8]");
  // Bounds the scans a sub-aperture keeps in memory (profiles are shared, poses copied).
  Require(static_cast<double>(f.base_scans) * std::pow(f.merge_factor, f.levels) <= 4096.0, src,
          "imaging.ffbp.levels",
          "base_scans * merge_factor^levels must be <= 4096 scans per sub-aperture");
  Require(f.angular_oversampling >= 1.0 && f.angular_oversampling <= 64.0, src,
          "imaging.ffbp.angular_oversampling", "must be in [1, 64]");
  Require(f.range_oversampling >= 0.25 && f.range_oversampling <= 64.0, src,
          "imaging.ffbp.range_oversampling", "must be in [0.25, 64]");
}

}  // namespace uwbsar
