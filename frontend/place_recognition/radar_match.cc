#include "frontend/place_recognition/radar_match.h"

#include <cmath>
#include <utility>
#include <vector>

namespace uwbsar {
namespace {

/// Appends `part` to `all`, its keypoints moved from `from` pixels to `to` pixels and
/// labelled with the sensor id (class_id).
void Append(const FeatureSet& part, const ImageGrid& from, const ImageGrid& to, int sensor_id,
            FeatureSet* all) {
  all->detector = part.detector;
  all->norm_type = part.norm_type;
  all->detect_ms += part.detect_ms;
  for (cv::KeyPoint kp : part.keypoints) {
    const Point2 p = from.PixelToMetric(kp.pt.x, kp.pt.y);
    kp.pt = cv::Point2f(static_cast<float>(to.XToCol(p.x_m)), static_cast<float>(to.YToRow(p.y_m)));
    kp.class_id = sensor_id;
    all->keypoints.push_back(kp);
  }
  if (!part.descriptors.empty()) all->descriptors.push_back(part.descriptors);
}

/// Keypoints per sensor id of a per-radar feature set.
std::vector<int> CountPerSensor(const FeatureSet& f, std::size_t sensors) {
  std::vector<int> n(sensors, 0);
  for (const cv::KeyPoint& kp : f.keypoints) {
    if (kp.class_id >= 0 && static_cast<std::size_t>(kp.class_id) < sensors) ++n[kp.class_id];
  }
  return n;
}

/// allowed(r, c) for query keypoint r of b and train keypoint c of a: their radars are paired.
/// A radar with fewer than 2 keypoints takes no part (guided MatchFeatures would keep a single
/// allowed neighbour without the ratio test).
cv::Mat PairMask(const FeatureSet& a, const FeatureSet& b,
                 const std::vector<std::vector<char>>& paired) {
  const std::size_t sensors = paired.size();
  const std::vector<int> na = CountPerSensor(a, sensors), nb = CountPerSensor(b, sensors);
  cv::Mat allowed(b.size(), a.size(), CV_8U, cv::Scalar(0));
  for (int r = 0; r < b.size(); ++r) {
    const int sb = b.keypoints[r].class_id;
    if (sb < 0 || static_cast<std::size_t>(sb) >= sensors || nb[sb] < 2) continue;
    unsigned char* row = allowed.ptr<unsigned char>(r);
    for (int c = 0; c < a.size(); ++c) {
      const int sa = a.keypoints[c].class_id;
      if (sa >= 0 && static_cast<std::size_t>(sa) < sensors && na[sa] >= 2 && paired[sa][sb])
        row[c] = 1;
    }
  }
  return allowed;
}

}  // namespace

void ExtractRadarFeatures(const Keyframe& keyframe, const PlaceRecognizerConfig& config,
                          KeyframeFeatures* k) {
  const DetectorConfig& d = config.place_recognition.detectors;
  DetectorConfig per_radar = d;
  per_radar.max_keypoints = config.place_recognition.per_radar.max_keypoints;
  const std::vector<DetectorKind>& detectors = config.place_recognition.validation.detectors;
  k->radar_by_detector.clear();
  for (DetectorKind kind : detectors) k->radar_by_detector[kind] = FeatureSet();
  const std::vector<double>& boresight_deg = config.radar_boresight_yaw_deg;
  k->look_anchor_rad.assign(boresight_deg.size(), 0.0);
  // The robot's heading at the middle of the tile, in the anchor frame (which has the
  // world's orientation in odometry; a correction of the anchor turns it with the tile).
  const double heading_anchor_rad =
      keyframe.T_world_robot.yaw_rad - keyframe.T_world_anchor.yaw_rad;
  for (std::size_t s = 0; s < boresight_deg.size(); ++s) {
    k->look_anchor_rad[s] = NormalizeAngle(heading_anchor_rad + boresight_deg[s] * M_PI / 180.0);
  }
  for (const SensorTile& st : keyframe.sensor_tiles) {
    if (st.sensor_id < 0 || static_cast<std::size_t>(st.sensor_id) >= boresight_deg.size())
      continue;
    ImageGrid grid = st.grid;
    const FeatureImage image =
        DownsampleFeatureImage(MakeFeatureImage(st.image, config.enhance, d.mask_erode_px),
                               config.feature_downsampling, d.white_percentile, &grid);
    for (DetectorKind kind : detectors) {
      Append(ComputeFeatures(image, kind, per_radar), grid, k->grid, st.sensor_id,
             &k->radar_by_detector[kind]);
    }
  }
}

bool HasRadarFeatures(const KeyframeFeatures& k, const PlaceRecognitionConfig& pr) {
  const FeatureSet& counted = k.RadarFeatures(pr.validation.detectors.back());
  int radars = 0;
  for (int n : CountPerSensor(counted, k.look_anchor_rad.size())) radars += n >= 2;
  return radars >= 2;
}

LoopAttempt MatchByRadar(const KeyframeFeatures& i, const KeyframeFeatures& j,
                         const PlaceRecognitionConfig& pr) {
  LoopAttempt attempt;
  attempt.candidate_id = i.id;
  attempt.by_radar = true;
  const std::size_t sensors = std::min(i.look_anchor_rad.size(), j.look_anchor_rad.size());
  const double max_rad = pr.per_radar.max_look_difference_deg * M_PI / 180.0;
  std::vector<std::vector<char>> paired(sensors, std::vector<char>(sensors, 0));
  bool any = false;
  for (std::size_t a = 0; a < sensors; ++a) {
    for (std::size_t b = 0; b < sensors; ++b) {
      const double look_i = i.T_world_anchor.yaw_rad + i.look_anchor_rad[a];
      const double look_j = j.T_world_anchor.yaw_rad + j.look_anchor_rad[b];
      paired[a][b] = std::abs(NormalizeAngle(look_i - look_j)) <= max_rad;
      any = any || paired[a][b];
      attempt.cross_side = attempt.cross_side || (paired[a][b] && a != b);
    }
  }
  if (!any) {
    attempt.validation.reason = "per radar: no radars look the same way";
    return attempt;
  }
  for (DetectorKind kind : pr.validation.detectors) {
    const FeatureSet& fi = i.RadarFeatures(kind);
    const FeatureSet& fj = j.RadarFeatures(kind);
    attempt.matches[kind] = MatchFeatures(fi, fj, pr.matching, PairMask(fi, fj, paired));
  }
  attempt.validation = ValidateLoop(i.id, i.grid, j.id, j.grid, attempt.matches, pr.validation);
  if (!attempt.validation.accepted)
    attempt.validation.reason = "per radar: " + attempt.validation.reason;
  return attempt;
}

}  // namespace uwbsar
