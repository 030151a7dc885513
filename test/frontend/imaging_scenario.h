// Test helper: simulate a run over point scatterers, image it with the real
// frontend and measure point-target quality. Shared by the imaging acceptance tests.
#pragma once

#include <stdexcept>
#include <vector>

#include "drivers/sim/synthetic_run.h"
#include "eval/psf_metrics.h"
#include "frontend/strip_renderer.h"
#include "imaging/enhance.h"
#include "slam/app_config.h"
#include "slam/jobs/imaging_job.h"

namespace uwbsar::testing {

/// The paper's detection (positive image Re + |Re|, Gaussian blur) of the real
/// part of an image. Applied to both modes it compares the imaging algorithms
/// under one detector: the real part of the coherent image is what the paper's
/// real-valued back-projection approximates.
inline cv::Mat PaperDetection(const Config& config, const cv::Mat& sar) {
  cv::Mat real = sar;
  if (sar.channels() == 2) cv::extractChannel(sar, real, 0);
  return EnhancedFloat(real, config.enhance);
}

/// The default configuration in `mode` ("paper" or "coherent"), imaged by direct
/// back-projection: the reference these tests measure (FfbpTest compares ffbp with it).
inline Config ConfigForMode(const char* mode) {
  Config config;
  config.imaging.method = ImagingMethod::kDirect;
  if (!EnumFromName(mode, &config.imaging.mode)) throw std::invalid_argument(mode);
  return config;
}

}  // namespace uwbsar::testing
