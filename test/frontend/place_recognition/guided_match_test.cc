#include "frontend/place_recognition/guided_match.h"

#include <gtest/gtest.h>

namespace uwbsar {
namespace {

KeyframeFeatures At(int id, const Pose2& T_world_anchor) {
  KeyframeFeatures k;
  k.id = id;
  k.T_world_anchor = T_world_anchor;
  k.centre_anchor = {1.0, 0.0};
  return k;
}

// Outbound keyframes 0..9 along +x (1 m apart); the return drifted: its estimates are 2 m
// off in y and 10 deg off in heading, but the loop (i = 5, j = 25) says j is on i. The
// neighbour q = 23 two metres before j is predicted on old keyframe 3, with the transform
// of the truth, whatever the drift.
TEST(GuidedMatchTest, LoopPredictsTheNeighbourOnTheOldKeyframeItOverlaps) {
  std::vector<KeyframeFeatures> olds;
  for (int k = 0; k < 10; ++k) olds.push_back(At(k, {static_cast<double>(k), 0.0, 0.0}));
  std::vector<const KeyframeFeatures*> old_ptrs;
  for (const KeyframeFeatures& o : olds) old_ptrs.push_back(&o);
  const Pose2 drift{0.0, 2.0, 0.17};
  const KeyframeFeatures j = At(25, drift * Pose2{5.0, 0.0, 0.0});
  const KeyframeFeatures q = At(23, drift * Pose2{3.0, 0.0, 0.0});
  const Pose2 T_ij{0.0, 0.0, 0.0};
  GuidedMatchConfig config;
  GuidedPair pair;
  ASSERT_TRUE(PredictGuidedPair(olds[5], j, T_ij, q, old_ptrs, config, &pair));
  EXPECT_EQ(pair.old_keyframe->id, 3);
  EXPECT_EQ(pair.query->id, 23);
  EXPECT_NEAR(pair.T_oq_predicted.x_m, 0.0, 1e-9);
  EXPECT_NEAR(pair.T_oq_predicted.y_m, 0.0, 1e-9);
  EXPECT_NEAR(pair.T_oq_predicted.yaw_rad, 0.0, 1e-9);

  // A loop that claims j lies 5 m beyond the outbound keyframes predicts q off every tile.
  EXPECT_FALSE(PredictGuidedPair(olds[5], j, Pose2{9.0, 0.0, 0.0}, q, old_ptrs, config, &pair));
}

}  // namespace
}  // namespace uwbsar
