// Dense refinement of a loop pair whose two detectors nearly agree: the two feature images are
// compared pixel by pixel (masked, zero-mean normalised cross-correlation, NCC) over a small
// window of shifts and rotations around the detectors' fused transform. The detectors place a
// pair from a few dozen keypoints each, and on real walls their matches slide along the wall,
// so two right answers can land a few pixels apart; the correlation of the whole overlap says
// where the images actually align, and whether that alignment is unique (the peak's ratio to
// the next local maximum: a wall seen alone gives a ridge, no distinct peak).
//
// Shifts come from one cv::matchTemplate (TM_CCORR, DFT) per term of the masked NCC, so the
// whole shift window costs a few correlations of the overlap per rotation. It runs only for
// pairs the rule rejects by a small margin (loop_validator.h), never for accepted ones.
#pragma once

#include <string>
#include <vector>

#include "frontend/place_recognition/features.h"
#include "frontend/place_recognition/place_recognition_config.h"

namespace uwbsar {

/// A rigid pixel transform of image b into image a, in the detectors' convention
/// (feature_matcher.h): p_a = R(rotation) p_b + (tx, ty), scale 1.
struct PixelRigid {
  double tx_px = 0.0;
  double ty_px = 0.0;
  double rotation_deg = 0.0;
};

struct DenseRefinement {
  bool found = false;             ///< a peak inside the search window (not yet judged distinct)
  std::string reason;             ///< why not found (empty when found)
  PixelRigid transform;           ///< at the peak, sub-pixel; valid when found
  double peak_ncc = 0.0;          ///< NCC at the best integer shift and rotation
  double second_ncc = 0.0;        ///< the second peak of the peak's shift surface (SecondPeak)
  double peak_ratio = 0.0;        ///< peak_ncc / second_ncc (1e9 when no other maximum > 0)
  double overlap_fraction = 0.0;  ///< measured overlap at the seed, of the smaller image
};

/// The feature image as a keyframe keeps it for the refinement: one 8-bit plane (measured
/// pixels at least 1, the rest 0), PNG-compressed at the fastest level (the feature images of
/// simulated and real tiles shrink to a third or less). Empty for an empty image.
std::vector<unsigned char> PackForRefinement(const FeatureImage& image);
/// The packed image back, with an empty mask (RefineByCorrelation takes it to mean gray > 0);
/// empty when `packed` is.
FeatureImage UnpackForRefinement(const std::vector<unsigned char>& packed);

/// Correlates `b` warped by `seed` (and by the searched shifts and rotations about the centre
/// of the overlap) with `a`, over the pixels both measured; when the peak lies in the window's
/// outer half, once more around it (so a peak up to twice search_m and search_deg from the
/// seed is found, and its lobe is seen whole). Both images share one pixel size,
/// `resolution_m`, which turns config.search_m into pixels.
DenseRefinement RefineByCorrelation(const FeatureImage& a, const FeatureImage& b,
                                    const PixelRigid& seed, double resolution_m,
                                    const DenseRefinementConfig& config);

/// Empty when `r` found a peak whose correlation is at least `min_peak_ncc` and at least
/// `min_peak_ratio` times its second peak; otherwise why not (loop validation's refinement and
/// map registration judge their peaks alike).
std::string JudgePeak(const DenseRefinement& r, double min_peak_ncc, double min_peak_ratio);

}  // namespace uwbsar
