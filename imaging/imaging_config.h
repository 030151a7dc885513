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

/// imaging.method: "direct": every scan back-projected onto every pixel of its sector (the
/// reference); "ffbp": fast factorised back-projection (imaging/factorized_back_projection.h).
enum class ImagingMethod { kDirect, kFfbp };
template <>
struct EnumNames<ImagingMethod> {
  static constexpr std::pair<ImagingMethod, const char*> kNames[] = {
      {ImagingMethod::kDirect, "direct"}, {ImagingMethod::kFfbp, "ffbp"}};
};

/// imaging.ffbp.*: fast factorised back-projection (Ulander, Hellsten and Stenstroem 2003).
/// Scans are imaged in sub-apertures of base_scans on local polar grids, merged merge_factor at
/// a time for `levels` levels, and the top sub-apertures are interpolated onto the tile. The
/// defaults were chosen by measurement (docs/measurements.md, "Imaging").
struct FfbpConfig {
  int base_scans = 32;   ///< scans of one radar imaged directly on a polar grid
  int merge_factor = 2;  ///< sub-apertures merged into one per level
  int levels = 2;        ///< merge levels: a top sub-aperture holds base_scans * factor^levels
  double angular_oversampling = 8.0;  ///< polar angle samples per two-way fringe
  /// Polar range samples per two-way range fringe of the baseband image, c / (2 bandwidth).
  double range_oversampling = 12.0;

  int top_scans() const {
    int n = base_scans;
    for (int i = 0; i < levels; ++i) n *= merge_factor;
    return n;
  }

  template <class V>
  void Visit(V& v) {
    v("base_scans", base_scans);
    v("merge_factor", merge_factor);
    v("levels", levels);
    v("angular_oversampling", angular_oversampling);
    v("range_oversampling", range_oversampling);
  }
};

/// Back-projection (paper section "Back-projection Algorithm").
struct ImagingConfig {
  ImagingMethod method = ImagingMethod::kDirect;  ///< direct or ffbp (see ImagingMethod)
  FfbpConfig ffbp;                                ///< imaging.method ffbp only
  ImagingMode mode = ImagingMode::kPaper;         ///< paper or coherent (see ImagingMode)
  double pixel_size_m = 0.005;                    ///< 5 mm per pixel, as the paper
  int coherent_oversampling = 4;  ///< analytic-signal upsampling before interpolation (coherent)
  int num_threads = 2;            ///< threads for back-projection (0 = OpenCV default)

  bool coherent() const { return mode == ImagingMode::kCoherent; }

  template <class V>
  void Visit(V& v) {
    v("method", method);
    v("ffbp", ffbp);
    v("mode", mode);
    v("pixel_size_m", pixel_size_m);
    v("coherent_oversampling", coherent_oversampling);
    v("num_threads", num_threads);
  }
};
/// Semantic checks of imaging.*; throws ConfigError naming the dotted key.
void Validate(const ImagingConfig& config, const std::string& source_name);

}  // namespace uwbsar
