// Settings of imaging.*, declared beside the code that owns them (imaging/back_projection.h); the
// application configuration (slam/config/system_config.h, slam/app_config.h) assembles the
// sections, and core/config_io.h reads and writes any struct with a Visit(). config/default.yaml
// documents every field; a test keeps the two in sync.
#pragma once

#include <string>

#include "core/named_enum.h"

namespace uwbsar {

/// imaging.mode: "paper": real samples, linear interpolation (as the paper); "coherent":
/// analytic signal with exp(j 4 pi fc R / c) phase.
enum class ImagingMode { kPaper, kCoherent };
template <>
struct EnumNames<ImagingMode> {
  static constexpr std::pair<ImagingMode, const char*> kNames[] = {
      {ImagingMode::kPaper, "paper"}, {ImagingMode::kCoherent, "coherent"}};
};

/// Back-projection (paper section "Back-projection Algorithm").
struct ImagingConfig {
  ImagingMode mode = ImagingMode::kPaper;  ///< paper or coherent (see ImagingMode)
  double pixel_size_m = 0.005;             ///< 5 mm per pixel, as the paper
  int coherent_oversampling = 4;  ///< analytic-signal upsampling before interpolation (coherent)
  int num_threads = 2;            ///< threads for back-projection (0 = OpenCV default)

  bool coherent() const { return mode == ImagingMode::kCoherent; }

  template <class V>
  void Visit(V& v) {
    v("mode", mode);
    v("pixel_size_m", pixel_size_m);
    v("coherent_oversampling", coherent_oversampling);
    v("num_threads", num_threads);
  }
};
/// Semantic checks of imaging.*; throws ConfigError naming the dotted key.
void Validate(const ImagingConfig& config, const std::string& source_name);

}  // namespace uwbsar
