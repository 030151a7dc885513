// One sub-aperture of a radar's scans imaged on a local polar grid: the building block of fast
// factorised back-projection (Ulander, Hellsten and Stenstroem, IEEE TAES 2003; see
// imaging/factorized_back_projection.h for the tree that uses it).
//
// The grid is centred on the mean antenna position C, with b the mean boresight and a = b turned
// by -90 deg. A sample (r, psi) is the point C + r (psi a + sqrt(1 - psi^2) b): r is the range
// from C and psi the sine of the angle from b. Along psi the image of an aperture of extent H is
// band-limited to H / lambda fringes (delay = r - u . dir), so a sub-aperture twice as long needs
// twice the psi samples and the same r samples: that is what makes merging cheap. Samples hold
// what direct back-projection gives at that point: the sum over the scans whose sector holds it
// of the scan's profile at the point's range. They are stored complex and at baseband (times
// exp(-j kc r), kc = 4 pi fc / c), so that they are smooth along r and a coarse range grid
// holds them: coherent mode from the analytic profiles, paper mode from the real profiles and
// their quadrature (RangeProfile::quadrature), keeping the real part when projecting.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <utility>
#include <vector>

#include "core/pose2.h"
#include "imaging/image_grid.h"
#include "imaging/range_profile.h"
#include "imaging/sector_spans.h"
#include "imaging/sensor_geometry.h"

namespace uwbsar {

/// What the polar grids are sampled for; the same for every sub-aperture of one imager.
struct PolarSampling {
  bool coherent = false;
  double carrier_wavenumber_rad_per_m = 0.0;  ///< kc = 4 pi fc / c (coherent baseband)
  double min_wavelength_m = 0.0;              ///< c / (fc + bandwidth): the finest fringe
  double range_step_m = 0.0;                  ///< polar range sample spacing (of the baseband)
  double angular_oversampling = 4.0;          ///< psi samples per two-way fringe
};

/// One scan of the sub-aperture: its profile (shared with the keyframe) and antenna pose.
struct SubaperturePulse {
  std::shared_ptr<const RangeProfile> profile;
  Pose2 T_grid_sensor;
};

class PolarSubaperture {
 public:
  /// Images `pulses` (one radar with `geometry`, in scan order) on a polar grid. nullopt when
  /// their sectors, seen from the centre, reach beyond 80 deg of the mean boresight (a tight
  /// turn): the polar grid cannot hold them, and the caller images those scans directly.
  static std::optional<PolarSubaperture> FromPulses(std::vector<SubaperturePulse> pulses,
                                                    const SensorGeometry& geometry,
                                                    const PolarSampling& sampling, int threads);
  /// One image of consecutive sub-apertures of one radar: each is interpolated onto the finer
  /// grid of the whole (coherent: with the phase of the range difference). nullopt as above.
  static std::optional<PolarSubaperture> Merge(const std::vector<const PolarSubaperture*>& parts,
                                               const SensorGeometry& geometry,
                                               const PolarSampling& sampling, int threads);

  /// Adds the image, interpolated, onto `spans` of `grid` (the pixels the scans' sectors cover;
  /// `image` grid-sized, CV_32FC1 or CV_32FC2 by mode). Returns the pixels written.
  long long ProjectInto(const ImageGrid& grid, const std::vector<RowSpan>& spans, cv::Mat* image,
                        int threads) const;

  const std::vector<SubaperturePulse>& pulses() const { return pulses_; }
  int range_samples() const { return range_samples_; }
  int angle_samples() const { return angle_samples_; }

 private:
  PolarSubaperture() = default;
  /// Centre, axes and sample lattice for `pulses`; false when the sectors do not fit.
  /// `boresights` (if given) receives each scan's (cos, sin) of yaw.
  bool PlanGrid(const SensorGeometry& geometry, const PolarSampling& sampling,
                std::vector<std::pair<double, double>>* boresights = nullptr);
  /// The unit direction of psi row `j` in the grid frame.
  void RowDirection(int j, double* dx, double* dy) const;

  std::vector<SubaperturePulse> pulses_;
  bool coherent_ = false;
  double kc_ = 0.0;
  double cx_m_ = 0.0, cy_m_ = 0.0;  ///< centre C, grid frame (double: grids may be far out)
  double ax_ = 0.0, ay_ = 0.0;      ///< unit axis a (psi = sin of the angle from b, towards a)
  double bx_ = 0.0, by_ = 0.0;      ///< unit mean boresight b
  double range0_m_ = 0.0, range_step_m_ = 0.0;
  double psi0_ = 0.0, psi_step_ = 0.0;
  int range_samples_ = 0, angle_samples_ = 0;
  /// Row-major [angle][range]: the baseband image's real and imaginary parts.
  std::vector<float> re_;
  std::vector<float> im_;
};

}  // namespace uwbsar
