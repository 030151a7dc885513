// Fast factorised back-projection (FFBP; Ulander, Hellsten and Stenstroem, IEEE TAES 2003) of
// one radar's scans into one image, formed as the scans arrive: every base_scans scans are
// imaged on a coarse polar grid (imaging/polar_subaperture.h), merge_factor consecutive polar
// images are merged into one with finer angular sampling, `levels` times, and each top image is
// interpolated onto the image's pixels. Direct back-projection costs scans x pixels; this costs
// about pixels x scans / top_scans plus polar work that grows with log(top_scans).
//
// The result approximates BackProjector's (the reference) to the interpolation error of the
// polar grids, which imaging.ffbp's oversampling settings bound (measured in the tests and in
// `uwbsar_bench --benchmark_filter=ImageTile`). Scans whose sectors do not fit one polar grid
// (a turn on the spot) are back-projected directly. The result does not depend on the number of
// threads.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "imaging/back_projection.h"
#include "imaging/imaging_config.h"
#include "imaging/polar_subaperture.h"
#include "imaging/pulse_config.h"

namespace uwbsar {

/// The polar sampling imaging.ffbp asks for, for profiles of `mode` (range bin c / (2 fs)).
PolarSampling PolarSamplingFor(const FfbpConfig& ffbp, const PulseConfig& pulse, bool coherent);

class FactorizedBackProjector {
 public:
  FactorizedBackProjector(const FfbpConfig& config, const PolarSampling& sampling, int threads);

  /// Hands over one scan of the radar `geometry` for `image` (grid-sized, CV_32FC1 or CV_32FC2
  /// to match the profile). Until Flush, every scan must be for the same radar, grid and image.
  /// Returns the pixels written by this call (when it completes a top sub-aperture).
  long long Add(std::shared_ptr<const RangeProfile> profile, const Pose2& T_grid_sensor,
                const SensorGeometry& geometry, const ImageGrid& grid, cv::Mat* image);
  /// Images everything handed over and not yet written into `image`; the next Add may start a
  /// new image. Returns the pixels written. `touched` (if given) receives the bounding box of
  /// the pixels written since the last Flush: those of every scan's sector, which then hold the
  /// scan's contribution.
  long long Flush(const ImageGrid& grid, cv::Mat* image, cv::Rect* touched = nullptr);

  /// Scans handed over and not yet written.
  int pending_scans() const;

 private:
  /// The pixels a sub-aperture's scans cover: per grid row, the hull of their sector spans
  /// (empty rows have lo >= hi). A base's is the hull of a few of its scans' sectors: the first,
  /// the last, and any that turned more than kFootprintTurnRad since the last of those. Between
  /// two of them, every scan's sector lies within their hull to within a tenth of a millimetre
  /// (the edges move linearly; the arcs bulge by d^2 / 8 r for a move d, r (1 - cos(a / 2)) for a
  /// turn a), so sector spans are computed twice per base on a straight path, not once per
  /// scan.
  struct Footprint {
    std::vector<int> lo, hi;
    void Add(const std::vector<RowSpan>& spans, int rows);
    void Add(const Footprint& other);
    std::vector<RowSpan> Spans() const;
  };
  struct Pending {
    PolarSubaperture image;
    Footprint footprint;
  };

  /// What Flush does, but for `touched`.
  long long FlushParts(const ImageGrid& grid, cv::Mat* image);
  /// Writes `part` into the image.
  long long Project(const Pending& part, const ImageGrid& grid, cv::Mat* image);
  /// One image of `parts` (nullopt when they do not fit one polar grid).
  std::optional<Pending> MergeParts(const std::vector<Pending>& parts);
  /// The base scans gathered so far as a polar image, emptying the base; nullopt when they do
  /// not fit one (then they are written into the image directly).
  std::optional<Pending> TakeBase(const ImageGrid& grid, cv::Mat* image, long long* pixels);
  /// The base as a level-0 image, carried upwards.
  void CloseBase(const ImageGrid& grid, cv::Mat* image, long long* pixels);
  /// Merges full levels upwards; a full top level is written into the image.
  void Carry(int level, const ImageGrid& grid, cv::Mat* image, long long* pixels);
  long long ProjectDirect(const std::vector<SubaperturePulse>& pulses, const ImageGrid& grid,
                          cv::Mat* image);
  /// Adds the sector of `pulse` to the base's footprint.
  void AddToFootprint(const SubaperturePulse& pulse, const ImageGrid& grid);

  FfbpConfig config_;
  PolarSampling sampling_;
  int threads_;
  SensorGeometry geometry_;             ///< of the scans pending
  std::vector<SubaperturePulse> base_;  ///< scans of the base being filled
  Footprint base_footprint_;            ///< their pixels
  std::size_t footprint_scans_ = 0;     ///< base_ scans up to the last in the footprint
  double footprint_yaw_rad_ = 0.0;      ///< yaw of the last scan in the footprint
  static constexpr double kFootprintTurnRad = M_PI / 180.0;
  std::vector<std::vector<Pending>> levels_;  ///< [l]: fewer than merge_factor images
  BackProjector direct_;
  std::vector<RowSpan> spans_;  ///< reused
  cv::Rect touched_;            ///< pixels written since the last Flush
};

}  // namespace uwbsar
