// Acceptance of place_recognition.validation.detectors (issue 27): the validation rule's
// detector pair is chosen by the configuration alone. With `detectors: [brisk, orb]` read from
// YAML, the recognizer computes, matches and validates BRISK and ORB on a simulated revisit of
// a cluttered corridor (sar_scene.h): it finds correct loops, and every attempt and stored
// keyframe carries BRISK and ORB, never AKAZE.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "app/app_config_io.h"
#include "frontend/place_recognition/place_recognizer.h"
#include "slam/app_config.h"
#include "test/frontend/place_recognition/sar_scene.h"

namespace uwbsar::testing {
namespace {

TEST(PlaceRecognitionDetectorPairTest, BriskAndOrbFromYamlValidateASimulatedRevisit) {
  const Config config = LoadConfigFromString(
      "place_recognition:\n  validation:\n    detectors: [brisk, orb]\n", "brisk_orb.yaml");
  // Out along a cluttered corridor and back the same way, with a drifting second pass.
  CorridorRevisit revisit = ImageClutteredCorridorRevisit(config);
  ImagedPass& d = revisit.out;
  ImagedPass& r = revisit.back;

  PlaceRecognizer recognizer(config);
  std::vector<Pose2> truth;  // by keyframe id
  int attempts = 0, loops = 0;
  auto process = [&](Keyframe k, const Pose2& T_true) {
    truth.resize(static_cast<std::size_t>(k.id) + 1);
    truth[static_cast<std::size_t>(k.id)] = T_true;
    const PlaceRecognitionResult result = recognizer.Process(k);
    for (const LoopAttempt& a : result.attempts) {
      ++attempts;
      EXPECT_EQ(a.matches.size(), 2u);
      EXPECT_EQ(a.matches.count(DetectorKind::kBrisk), 1u);
      EXPECT_EQ(a.matches.count(DetectorKind::kOrb), 1u);
      EXPECT_EQ(a.matches.count(DetectorKind::kAkaze), 0u);
      EXPECT_EQ(a.validation.reason.find("AKAZE"), std::string::npos) << a.validation.reason;
    }
    for (const LoopConstraint& l : result.loops) {
      ++loops;
      EXPECT_GT(l.good_matches.at(DetectorKind::kBrisk), 0);
      EXPECT_GT(l.good_matches.at(DetectorKind::kOrb), 0);
      const Pose2 expected =
          Between(truth[static_cast<std::size_t>(l.i)], truth[static_cast<std::size_t>(l.j)]);
      EXPECT_NEAR(l.T_ij.x_m, expected.x_m, 0.05) << l.i << " -> " << l.j;
      EXPECT_NEAR(l.T_ij.y_m, expected.y_m, 0.05) << l.i << " -> " << l.j;
      EXPECT_NEAR(NormalizeAngle(l.T_ij.yaw_rad - expected.yaw_rad), 0.0, 2.0 * M_PI / 180.0);
    }
    const KeyframeFeatures* stored = recognizer.Find(k.id);
    ASSERT_NE(stored, nullptr);
    EXPECT_EQ(stored->by_detector.count(DetectorKind::kAkaze), 0u);
    EXPECT_GT(stored->Features(DetectorKind::kBrisk).size(), 0);
  };
  const int first_return_id = static_cast<int>(d.keyframes.size());
  for (std::size_t k = 0; k < d.keyframes.size(); ++k) {
    process(std::move(d.keyframes[k]), d.T_world_anchor_true[k]);
  }
  for (std::size_t k = 0; k < r.keyframes.size(); ++k) {
    Keyframe kf = std::move(r.keyframes[k]);
    kf.id += first_return_id;
    kf.path_begin_m += 100.0;
    kf.path_end_m += 100.0;
    process(std::move(kf), r.T_world_anchor_true[k]);
  }
  std::printf("BRISK+ORB: %d attempts, %d loops validated\n", attempts, loops);
  EXPECT_GT(attempts, 0);
  EXPECT_GE(loops, 1);
}

}  // namespace
}  // namespace uwbsar::testing
