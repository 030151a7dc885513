// SURF (Bay, Ess, Tuytelaars, Van Gool 2008) implemented in the project, because
// Debian's OpenCV ships no xfeatures2d: a fast-Hessian detector on an integral
// image (box-filter approximations of the second derivatives, 3x3x3 non-maximum
// suppression and quadratic sub-pixel/scale interpolation), orientation from
// Haar-wavelet responses in a sliding 60-degree window, and the 64-dimensional
// descriptor (sums of dx, |dx|, dy, |dy| over 4x4 sub-regions of a 20-sigma window).
// Conventions follow OpenCV's former SURF so that the paper's parameters mean the
// same: the Hessian determinant is in squared 8-bit intensity units, keypoint size
// is the filter side (9 px = scale 1.2), angles in degrees, class_id = Laplacian sign.
// Built only with -DUWBSAR_WITH_SURF=ON (the default).
#pragma once

#include <opencv2/features2d.hpp>

namespace uwbsar {

struct SurfParams {
  double hessian_threshold = 200.0;  ///< minimum Hessian determinant (paper: 200)
  int octaves = 4;                   ///< filter sizes double per octave
  int octave_layers = 4;             ///< scales searched per octave (paper: 4)
  bool upright = false;              ///< U-SURF: orientation fixed at 0
  int max_keypoints = 0;             ///< keep the strongest this many (0 = all), before the
                                     ///< orientation and descriptor are computed
};

/// A cv::Feature2D so that SURF plugs into the same pipeline as OpenCV's detectors.
/// Descriptors are CV_32F, 64 columns, unit L2 norm; match them with NORM_L2.
class Surf : public cv::Feature2D {
 public:
  static cv::Ptr<Surf> Create(const SurfParams& params) { return cv::makePtr<Surf>(params); }
  explicit Surf(const SurfParams& params) : params_(params) {}

  /// Detects on an 8-bit single-channel image (optional 8-bit mask); with
  /// use_provided_keypoints, only orientations (unless upright) and descriptors are computed.
  void detectAndCompute(cv::InputArray image, cv::InputArray mask,
                        std::vector<cv::KeyPoint>& keypoints, cv::OutputArray descriptors,
                        bool use_provided_keypoints = false) override;

  int descriptorSize() const override { return 64; }
  int descriptorType() const override { return CV_32F; }
  int defaultNorm() const override { return cv::NORM_L2; }
  cv::String getDefaultName() const override { return "uwbsar.SURF"; }

 private:
  SurfParams params_;
};

}  // namespace uwbsar
