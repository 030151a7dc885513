#include "frontend/place_recognition/candidate_search.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace uwbsar {
namespace {

TEST(CandidateSearchTest, RadiusGrowsWithTravelSinceTheLastLoopUpToTheCap) {
  CandidateSearchConfig c;
  c.base_radius_m = 1.0;
  c.radius_growth_per_m = 0.1;
  c.max_radius_m = 4.0;
  EXPECT_DOUBLE_EQ(SearchRadius(c, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(SearchRadius(c, 10.0), 2.0);
  EXPECT_DOUBLE_EQ(SearchRadius(c, 1000.0), 4.0);
  EXPECT_DOUBLE_EQ(SearchRadius(c, -5.0), 1.0);
}

// A gyro base's heading error grows with time: a slow stretch since the last loop widens the
// search more than a fast one over the same path (3 sigmas of rate * d * t / 2 sideways).
TEST(CandidateSearchTest, RadiusWidensWithTheTimeSinceTheLastLoopForAGyroBase) {
  CandidateSearchConfig c;
  c.base_radius_m = 1.0;
  c.radius_growth_per_m = 0.1;
  c.max_radius_m = 10.0;
  EXPECT_DOUBLE_EQ(SearchRadius(c, 20.0, 250.0), 3.0);  // a wheel base: the path alone
  c.heading_rate_sigma_radps = 0.03 * M_PI / 180.0;     // the Kobuki's turn-on bias spread
  const double fast = SearchRadius(c, 20.0, 100.0);     // 0.2 m/s
  const double slow = SearchRadius(c, 20.0, 250.0);     // 0.08 m/s
  EXPECT_NEAR(fast, 3.0 + 3.0 * 0.03 * M_PI / 180.0 * 20.0 * 100.0 / 2.0, 1e-12);
  EXPECT_GT(slow - 3.0, 2.4 * (fast - 3.0));
  EXPECT_DOUBLE_EQ(SearchRadius(c, 20.0, NAN), 3.0);  // time unknown
  EXPECT_DOUBLE_EQ(SearchRadius(c, 200.0, 5000.0), 10.0);
}

TEST(CandidateSearchTest, WithinMatchesBruteForceOnRandomKeyframes) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-30.0, 30.0);
  KeyframeIndex index(2.0);
  std::vector<Point2> points;
  for (int id = 0; id < 500; ++id) {
    points.push_back({u(rng), u(rng)});
    index.Upsert(id, points.back(), id);
  }
  for (int q = 0; q < 50; ++q) {
    const Point2 p{u(rng), u(rng)};
    const double r = 0.5 + std::abs(u(rng)) / 5;
    std::vector<int> expected, got;
    for (int id = 0; id < 500; ++id) {
      if (std::hypot(points[id].x_m - p.x_m, points[id].y_m - p.y_m) <= r) expected.push_back(id);
    }
    for (const auto& h : index.Within(p, r)) got.push_back(h.id);
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, expected);
  }
}

TEST(CandidateSearchTest, UpsertMovesAKeyframe) {
  KeyframeIndex index(1.0);
  index.Upsert(7, {0.0, 0.0}, 0.0);
  index.Upsert(7, {10.0, 10.0}, 0.0);
  EXPECT_EQ(index.size(), 1u);
  EXPECT_TRUE(index.Within({0.0, 0.0}, 1.0).empty());
  ASSERT_EQ(index.Within({10.0, 10.0}, 0.5).size(), 1u);
}

KeyframeIndex Corridor() {
  // A keyframe every metre along x, out and back: ids 0..9 outbound, 10..19 inbound.
  KeyframeIndex index(2.0);
  for (int k = 0; k < 10; ++k) index.Upsert(k, {k + 0.5, 0.0}, k);
  for (int k = 0; k < 10; ++k) index.Upsert(10 + k, {9.5 - k, 0.05}, 10.0 + k);
  return index;
}

TEST(CandidateSearchTest, NearestFirstWithinRadiusExcludingRecentAndCapped) {
  const KeyframeIndex index = Corridor();
  CandidateSearchConfig c;
  c.base_radius_m = 1.6;
  c.radius_growth_per_m = 0.0;
  c.exclude_recent_path_m = 3.0;
  c.max_candidates = 2;
  CandidateQuery q;
  q.position_world = {3.5, 0.0};
  q.path_begin_m = 16.0;  // keyframe 16 is at x = 3.5
  const CandidateSet set = FindCandidates(index, q, c);
  ASSERT_EQ(set.ids.size(), 2u);
  EXPECT_EQ(set.ids[0], 3);  // nearest
  EXPECT_TRUE(set.ids[1] == 2 || set.ids[1] == 4);
  EXPECT_TRUE(set.used_prior);
  EXPECT_DOUBLE_EQ(set.radius_m, 1.6);
  for (int id : set.ids) EXPECT_LT(id, 14);  // ids 14.. began less than 3 m before 16
}

TEST(CandidateSearchTest, NoPriorModeChecksEveryOlderKeyframe) {
  const KeyframeIndex index = Corridor();
  CandidateSearchConfig c;
  c.use_pose_prior = false;
  c.exclude_recent_path_m = 3.0;
  c.max_candidates = 2;  // ignored without a prior
  CandidateQuery q;
  q.position_world = {100.0, 100.0};  // the estimate is far off: drift
  q.path_begin_m = 20.0;
  const CandidateSet set = FindCandidates(index, q, c);
  EXPECT_FALSE(set.used_prior);
  EXPECT_EQ(set.ids.size(), 18u);  // 0..17
  const CandidateSet with_prior = FindCandidates(index, q, CandidateSearchConfig{});
  EXPECT_TRUE(with_prior.ids.empty());
}

TEST(CandidateSearchTest, NonFiniteQueryFindsNothing) {
  const KeyframeIndex index = Corridor();
  CandidateQuery q;
  q.position_world = {std::nan(""), 0.0};
  q.path_begin_m = 30.0;
  EXPECT_TRUE(FindCandidates(index, q, CandidateSearchConfig{}).ids.empty());
}

}  // namespace
}  // namespace uwbsar
