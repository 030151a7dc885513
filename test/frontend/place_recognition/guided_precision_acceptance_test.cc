// The guided pass (frontend/place_recognition/guided_match.h) matches with a prediction and a
// lower good-match threshold, so its precision is tested on its own: on a simulated run of
// our own seed_hall floor (its loop and depart-return routes), every keyframe pair is given to
// GuidedAttempt
//   - with the true transform when the tiles overlap (the control: guided pairs are found),
//   - with a wrong prediction (0.3-2 m or 8 deg off the truth) when they overlap, and
//   - as a false pair: tiles 3 m or more apart claimed to lie on each other,
// and no accepted attempt may be off the truth by more than 5 cm or 2 deg. Measured: true
// 15/23 accepted (19/23 before the distinctiveness check in NearPrediction), wrong
// predictions 0/115 (1/115 before: 8 deg off predicted, accepted 5 deg off the truth),
// false pairs 0/63. About 35 s in Release.
#include <gtest/gtest.h>

#include <cstdio>

#include "frontend/place_recognition/guided_match.h"
#include "test/frontend/place_recognition/sim_run.h"

namespace uwbsar::testing {
namespace {

struct GuidedTally {
  int tried = 0, accepted = 0, wrong = 0;
};

TEST(GuidedPrecisionAcceptanceTest, WrongPredictionsAndFalsePairsAreNotAccepted) {
  Config config;
  const std::string map = std::string(UWBSAR_SOURCE_DIR) + "/config/maps/seed_hall/seed_hall.yaml";
  const PlaceRecognitionConfig pr =
      AtFeatureResolution(config.place_recognition, FeatureDownsampling(config));
  GuidedTally control, shifted, false_pairs;
  for (const auto& [route, seed] : {std::pair<const char*, int>{"loop", 5}, {"depart-return", 4}}) {
    const SimulatedRun run = SimulateAndImage(config, map, route, static_cast<std::uint64_t>(seed));
    std::vector<KeyframeFeatures> features;
    std::vector<Pose2> truth;
    for (const Keyframe& k : run.keyframes) {
      features.push_back(ExtractKeyframeFeatures(k, config));
      truth.push_back(TruePoseAt(run.ground_truth, k.stamp_ns) *
                      Between(k.T_world_robot, k.T_world_anchor));
    }
    auto attempt = [&](std::size_t o, std::size_t q, const Pose2& predicted, GuidedTally* tally) {
      GuidedPair pair;
      pair.old_keyframe = &features[o];
      pair.query = &features[q];
      pair.T_oq_predicted = predicted;
      const LoopAttempt a = GuidedAttempt(pair, pr);
      ++tally->tried;
      if (!a.validation.accepted) return;
      ++tally->accepted;
      const Pose2 e = Between(Between(truth[o], truth[q]), a.validation.constraint.T_ij);
      tally->wrong += std::hypot(e.x_m, e.y_m) > 0.05 || std::abs(e.yaw_rad) > 2 * M_PI / 180;
    };
    const Pose2 offsets[] = {{0.3, 0.0, 0.0},
                             {0.0, 0.5, 0.0},
                             {-1.0, 0.0, 0.0},
                             {2.0, 0.0, 0.0},
                             {0.0, 0.0, 8 * M_PI / 180}};
    for (std::size_t o = 0; o < features.size(); ++o) {
      for (std::size_t q = o + 1; q < features.size(); ++q) {
        if (features[q].path_begin_m - features[o].path_begin_m <
            pr.candidates.exclude_recent_path_m) {
          continue;  // shares scans
        }
        const Pose2 T_oq = Between(truth[o], truth[q]);
        const Point2 centre_o = truth[o] * features[o].centre_anchor;
        const Point2 centre_q = truth[q] * features[q].centre_anchor;
        const double apart_m = std::hypot(centre_o.x_m - centre_q.x_m, centre_o.y_m - centre_q.y_m);
        if (apart_m <= 1.0) {
          attempt(o, q, T_oq, &control);
          for (const Pose2& offset : offsets) attempt(o, q, T_oq * offset, &shifted);
        } else if (apart_m >= 3.0) {
          // Claimed on top of each other, with the true heading difference (as an aliased
          // corridor would be): q's tile centre predicted on o's.
          const Pose2 rotation{0.0, 0.0, T_oq.yaw_rad};
          const Point2 moved = rotation * features[q].centre_anchor;
          attempt(o, q,
                  {features[o].centre_anchor.x_m - moved.x_m,
                   features[o].centre_anchor.y_m - moved.y_m, T_oq.yaw_rad},
                  &false_pairs);
        }
      }
    }
  }
  for (const auto& [name, t] : {std::pair<const char*, const GuidedTally&>{"true", control},
                                {"wrong prediction", shifted},
                                {"false pair", false_pairs}}) {
    std::printf("[B] guided %-16s tried %4d accepted %4d wrong %d\n", name, t.tried, t.accepted,
                t.wrong);
  }
  EXPECT_GT(control.accepted, 0);  // the pass finds the true pairs: the test can fail below
  EXPECT_EQ(control.wrong, 0);
  // A prediction 0.3 m or more off the truth leaves nothing right to accept within the
  // guided pass's 0.15 m, and a false pair has no right transform: all accepted are wrong.
  EXPECT_EQ(shifted.accepted, 0);
  EXPECT_EQ(false_pairs.accepted, 0);
}

}  // namespace
}  // namespace uwbsar::testing
