// Over all candidate keyframe pairs of simulated runs (no pose
// prior: every pair that does not share scans), precision and recall of accepted loops
// for each detector alone (more than N good matches and a plausible scale) and for the
// paper's AKAZE+ORB rule; and for the recognizer's matching (AKAZE+ORB at the feature
// resolution, "PR") without and with the per-radar pass (radar_match.h, "PR+radar"), which
// matches radar by radar the pairs whose combined tiles fail. An accepted loop is correct when its
// metric transform is within 5 cm and 2 deg of the ground truth; a pair is a true loop when the
// tiles' true centres are within 1 m (their paths overlap by at least half).
#include <gtest/gtest.h>

#include <cstdio>
#include <map>

#include "frontend/place_recognition/place_recognizer.h"
#include "frontend/place_recognition/radar_match.h"
#include "slam/app_config.h"
#include "test/frontend/place_recognition/sim_run.h"
#include "test/shared_data.h"

namespace uwbsar::testing {
namespace {

struct Tally {
  int accepted = 0, correct = 0, positives = 0, found = 0;
  double Precision() const { return accepted ? static_cast<double>(correct) / accepted : 1.0; }
  double Recall() const { return positives ? static_cast<double>(found) / positives : 1.0; }
  void Add(const Tally& o) {
    accepted += o.accepted;
    correct += o.correct;
    positives += o.positives;
    found += o.found;
  }
};

using Scores = std::map<std::string, Tally>;

Scores Evaluate(const Config& config, const std::vector<Keyframe>& keyframes,
                const std::vector<Pose2>& T_world_anchor_true) {
  const auto& pr = config.place_recognition;
  std::vector<std::map<DetectorKind, FeatureSet>> features(keyframes.size());
  std::vector<Point2> centre(keyframes.size());
  std::vector<KeyframeFeatures> cached(keyframes.size());  // as the recognizer keeps them
  std::vector<FeatureImage> images(keyframes.size());      // at the tile resolution
  const PlaceRecognitionConfig at_features = AtFeatureResolution(pr, FeatureDownsampling(config));
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    const FeatureImage image =
        MakeFeatureImage(keyframes[k].image, config.enhance, pr.detectors.mask_erode_px);
    images[k] = image;
    for (DetectorKind kind : AvailableDetectors()) {
      features[k][kind] = ComputeFeatures(image, kind, pr.detectors);
    }
    cached[k] = ExtractKeyframeFeatures(keyframes[k], config);
    centre[k] = T_world_anchor_true[k] * cached[k].centre_anchor;
  }
  std::vector<FeatureImage> refinement_images(keyframes.size());  // unpacked, as the recognizer
  double packed_bytes = 0.0, raw_bytes = 0.0;                     // would for a refined pair
  for (std::size_t k = 0; k < keyframes.size(); ++k) {
    refinement_images[k] = UnpackForRefinement(*cached[k].refinement_image);
    packed_bytes += static_cast<double>(cached[k].refinement_image->size());
    raw_bytes += static_cast<double>(refinement_images[k].gray.total());
  }
  std::printf("[B] refinement image per keyframe: %.0f kB packed, %.0f kB raw\n",
              packed_bytes / 1024.0 / static_cast<double>(keyframes.size()),
              raw_bytes / 1024.0 / static_cast<double>(keyframes.size()));
  Scores scores;
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    for (std::size_t j = i + 1; j < keyframes.size(); ++j) {
      if (keyframes[j].path_begin_m - keyframes[i].path_begin_m <
          pr.candidates.exclude_recent_path_m) {
        continue;  // shares scans: never a candidate
      }
      const Pose2 truth = Between(T_world_anchor_true[i], T_world_anchor_true[j]);
      const bool positive =
          std::hypot(centre[i].x_m - centre[j].x_m, centre[i].y_m - centre[j].y_m) <= 1.0;
      auto score = [&](const std::string& name, const LoopValidation& v) {
        Tally& t = scores[name];
        t.positives += positive;
        if (!v.accepted) return;
        const Pose2 e = Between(truth, v.constraint.T_ij);
        const bool correct =
            std::hypot(e.x_m, e.y_m) < 0.05 && std::abs(e.yaw_rad) < 2 * M_PI / 180;
        ++t.accepted;
        t.correct += correct;
        t.found += correct && positive;
      };
      const Keyframe& a = keyframes[i];
      const Keyframe& b = keyframes[j];
      std::map<DetectorKind, MatchResult> m;
      for (DetectorKind kind : AvailableDetectors()) {
        m[kind] = MatchFeatures(features[i][kind], features[j][kind], pr.matching);
        // One detector alone: the rule with the detector standing in for both.
        score(DetectorName(kind),
              ValidateLoop(a.id, a.grid, b.id, b.grid, m[kind], m[kind], pr.validation));
      }
      const LoopValidation paper = ValidateLoop(a.id, a.grid, b.id, b.grid, m[DetectorKind::kAkaze],
                                                m[DetectorKind::kOrb], pr.validation);
      score("AKAZE+ORB", paper);
      LoopValidationConfig refined = pr.validation;
      refined.refinement.enabled = true;
      const LoopValidation dense =
          ValidateLoop(a.id, a.grid, b.id, b.grid, m[DetectorKind::kAkaze], m[DetectorKind::kOrb],
                       refined, {&images[i], &images[j]});
      score("AKAZE+ORB+dense", dense);
      if (dense.refinement_tried) {
        const Pose2 e = Between(truth, dense.refined ? dense.constraint.T_ij : truth);
        std::printf(
            "[B] tile-resolution refinement %d -> %d (%s): %s, peak %.3f, second %.3f, "
            "ratio %.2f%s\n",
            a.id, b.id, positive ? "true loop" : "no loop",
            dense.refined ? "accepted" : dense.reason.c_str(), dense.refinement.peak_ncc,
            dense.refinement.second_ncc, dense.refinement.peak_ratio,
            dense.refined ? (std::hypot(e.x_m, e.y_m) < 0.05 ? ", correct" : ", WRONG") : "");
      }
      const KeyframeFeatures& fa = cached[i];
      const KeyframeFeatures& fb = cached[j];
      LoopValidation v =
          ValidateLoop(fa.id, fa.grid, fb.id, fb.grid,
                       MatchFeatures(fa.Features(DetectorKind::kAkaze),
                                     fb.Features(DetectorKind::kAkaze), at_features.matching),
                       MatchFeatures(fa.Features(DetectorKind::kOrb),
                                     fb.Features(DetectorKind::kOrb), at_features.matching),
                       at_features.validation, {&refinement_images[i], &refinement_images[j]});
      score("PR", v);
      if (v.refinement_tried) {
        const Pose2 e = Between(truth, v.refined ? v.constraint.T_ij : truth);
        std::printf("[B] refinement %d -> %d (%s): %s, peak %.3f, second %.3f, ratio %.2f%s\n",
                    fa.id, fb.id, positive ? "true loop" : "no loop",
                    v.refined ? "accepted" : v.reason.c_str(), v.refinement.peak_ncc,
                    v.refinement.second_ncc, v.refinement.peak_ratio,
                    v.refined ? (std::hypot(e.x_m, e.y_m) < 0.05 ? ", correct" : ", WRONG") : "");
      }
      if (!v.accepted && HasRadarFeatures(fa, at_features) && HasRadarFeatures(fb, at_features)) {
        v = MatchByRadar(fa, fb, at_features).validation;
      }
      score("PR+radar", v);
    }
  }
  return scores;
}

std::vector<Pose2> TrueAnchors(const SimulatedRun& run) {
  std::vector<Pose2> out;
  for (const Keyframe& k : run.keyframes) {
    out.push_back(TruePoseAt(run.ground_truth, k.stamp_ns) *
                  Between(k.T_world_robot, k.T_world_anchor));
  }
  return out;
}

void Print(const std::string& run, const Scores& s) {
  for (const auto& [name, t] : s) {
    std::printf(
        "[B] %-26s %-9s accepted %3d correct %3d | true loops %3d found %3d | precision "
        "%.3f recall %.3f\n",
        run.c_str(), name.c_str(), t.accepted, t.correct, t.positives, t.found, t.Precision(),
        t.Recall());
  }
}

TEST(PrecisionRecallAcceptanceTest, AkazeOrbRuleHasPrecisionOneOnSimulatedRuns) {
  UWBSAR_NEED_SEED_LAB_MAP();
  Config config;
  // The recognizer's path ("PR") with the refinement on (off by default): its packed images are
  // made only then, and the "AKAZE+ORB+dense" line measures it at the tile resolution.
  config.place_recognition.validation.refinement.enabled = true;
  Scores total;
  auto add = [&](const std::string& name, const Scores& s) {
    Print(name, s);
    for (const auto& [k, t] : s) total[k].Add(t);
  };
  {
    const SimulatedRun run = SimulateAndImage(config, SeedLabMap(), "depart-return", 4);
    add("seed_lab depart-return", Evaluate(config, run.keyframes, TrueAnchors(run)));
  }
  {
    const SimulatedRun run = SimulateAndImage(config, SeedLabMap(), "loop", 5);
    add("seed_lab loop", Evaluate(config, run.keyframes, TrueAnchors(run)));
  }
  {
    // Second environment: a cluttered corridor of point scatterers (walls, furniture).
    CorridorRevisit revisit = ImageClutteredCorridorRevisit(config);
    ImagedPass& d = revisit.out;
    ImagedPass& r = revisit.back;
    std::vector<Keyframe> keyframes = std::move(d.keyframes);
    std::vector<Pose2> truth = d.T_world_anchor_true;
    for (std::size_t k = 0; k < r.keyframes.size(); ++k) {
      Keyframe kf = std::move(r.keyframes[k]);
      kf.id += 1000;
      kf.path_begin_m += 100.0;
      keyframes.push_back(std::move(kf));
      truth.push_back(r.T_world_anchor_true[k]);
    }
    add("clutter corridor", Evaluate(config, keyframes, truth));
  }
  Print("all runs", total);
  EXPECT_EQ(total["AKAZE+ORB"].accepted, total["AKAZE+ORB"].correct);
  EXPECT_EQ(total["AKAZE+ORB+dense"].accepted, total["AKAZE+ORB+dense"].correct);
  EXPECT_GE(total["AKAZE+ORB+dense"].found, total["AKAZE+ORB"].found);
  EXPECT_GT(total["AKAZE+ORB"].Recall(), 0.5);
  EXPECT_EQ(total["PR+radar"].accepted, total["PR+radar"].correct);
  EXPECT_GE(total["PR+radar"].found, total["PR"].found);
}

}  // namespace
}  // namespace uwbsar::testing
