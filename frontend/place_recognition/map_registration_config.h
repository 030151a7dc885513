// Configuration of the registration of a keyframe against a saved map's tiles at a predicted pose
// (frontend/place_recognition/map_registration.h): place_recognition.registration.*.
#pragma once

#include <string>

namespace uwbsar {

/// A keyframe registered against the map tiles near where the robot is predicted to be: the two
/// detected tiles, at resolution_m, correlated over the pixels both observed (masked NCC of the
/// high-passed images) around the prediction. A registration is a constraint only when its peak
/// is distinct. Used by localisation once the robot is placed (slam/localization/localizer.h).
struct MapRegistrationConfig {
  bool enabled = true;
  double resolution_m = 0.03;      ///< pixel size the tiles are compared at
  double white_percentile = 95.0;  ///< of each image's observed pixels, mapped to white: brighter
                                   ///< ones saturate, so a reflector that is new since the map
                                   ///< weighs no more than the scene's bright ones (robustness)
  int max_map_tiles = 1;           ///< the map tiles nearest the prediction registered with
  double max_centre_distance_m = 2.0;  ///< ... whose centres lie within this of the keyframe's
  double search_m = 0.15;              ///< shifts searched, +- this around the prediction (the
                                       ///< search recentres once on a peak in its outer half)
  double search_deg = 1.0;             ///< rotations searched, +- this ...
  double step_deg = 0.5;               ///< ... in steps of this
  double min_peak_ncc = 0.12;          ///< the correlation at the peak at least this
  double min_peak_ratio = 1.5;     ///< the peak over the second peak (outside its lobe, or on the
                                   ///< window's edge: a lone wall's ridge) at least this
  double highpass_sigma_m = 0.05;  ///< local mean (Gaussian of this sigma) taken off first
  double min_overlap_fraction = 0.3;  ///< of the smaller observed area, at the prediction
  double sigma_xy_m = 0.02;           ///< standard deviation of a registration's translation ...
  double sigma_yaw_deg = 0.3;         ///< ... and of its rotation (its information)

  template <class V>
  void Visit(V& v) {
    v("enabled", enabled);
    v("resolution_m", resolution_m);
    v("white_percentile", white_percentile);
    v("max_map_tiles", max_map_tiles);
    v("max_centre_distance_m", max_centre_distance_m);
    v("search_m", search_m);
    v("search_deg", search_deg);
    v("step_deg", step_deg);
    v("min_peak_ncc", min_peak_ncc);
    v("min_peak_ratio", min_peak_ratio);
    v("highpass_sigma_m", highpass_sigma_m);
    v("min_overlap_fraction", min_overlap_fraction);
    v("sigma_xy_m", sigma_xy_m);
    v("sigma_yaw_deg", sigma_yaw_deg);
  }
};

/// Semantic checks; throws ConfigError naming `key` + the field
/// ("place_recognition.registration.").
void Validate(const MapRegistrationConfig& config, const std::string& source_name,
              const std::string& key);

}  // namespace uwbsar
