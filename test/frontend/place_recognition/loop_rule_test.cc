#include "frontend/place_recognition/loop_rule.h"

#include <gtest/gtest.h>

#include <limits>

namespace uwbsar {
namespace {

DetectorStats Stats(int n, double scale, double tx, double ty, double rot) {
  DetectorStats s;
  s.good_matches = n;
  s.has_transform = true;
  s.scale = scale;
  s.tx_px = tx;
  s.ty_px = ty;
  s.rotation_deg = rot;
  return s;
}

// Paper Table III, D1 -> R1: AKAZE 1.00, 25.1 mm, -36.7 mm, -0.63 deg; ORB 1.00, 27.3 mm,
// -47.4 mm, -0.66 deg (5 mm pixels); good matches well above 10.
TEST(LoopRuleTest, AcceptsThePapersFirstLoopAndFusesByGoodMatches) {
  const DetectorStats akaze = Stats(56, 1.00, 25.1 / 5, -36.7 / 5, -0.63);
  const DetectorStats orb = Stats(37, 1.00, 27.3 / 5, -47.4 / 5, -0.66);
  const LoopDecision d = ApplyLoopRule(akaze, orb, LoopValidationConfig{});
  ASSERT_TRUE(d.accepted) << d.reason;
  EXPECT_TRUE(d.reason.empty());
  EXPECT_NEAR(d.tx_px, (56 * 25.1 / 5 + 37 * 27.3 / 5) / 93, 1e-9);
  EXPECT_NEAR(d.ty_px, (56 * -36.7 / 5 + 37 * -47.4 / 5) / 93, 1e-9);
  EXPECT_NEAR(d.rotation_deg, (56 * -0.63 + 37 * -0.66) / 93, 1e-9);
}

// Paper Table IV, D1 -> R3: AKAZE 5 good matches, scale 1.16, rot 20.59: rejected.
TEST(LoopRuleTest, RejectsThePapersNonLoopWithAReason) {
  const LoopDecision d = ApplyLoopRule(Stats(5, 1.16, -340, 54, 20.59),
                                       Stats(7, 1.13, -334, 78, 21.21), LoopValidationConfig{});
  EXPECT_FALSE(d.accepted);
  EXPECT_NE(d.reason.find("AKAZE: 5 good matches"), std::string::npos) << d.reason;
}

TEST(LoopRuleTest, GoodMatchThresholdIsStrict) {
  LoopValidationConfig c;
  const DetectorStats ok = Stats(30, 1.0, 0, 0, 0);
  EXPECT_FALSE(ApplyLoopRule(Stats(10, 1.0, 0, 0, 0), ok, c).accepted);
  EXPECT_TRUE(ApplyLoopRule(Stats(11, 1.0, 0, 0, 0), ok, c).accepted);
  const LoopDecision d = ApplyLoopRule(ok, Stats(10, 1.0, 0, 0, 0), c);
  EXPECT_NE(d.reason.find("ORB: 10 good matches"), std::string::npos) << d.reason;
  c.min_good_matches = 5;
  EXPECT_TRUE(ApplyLoopRule(Stats(6, 1.0, 0, 0, 0), ok, c).accepted);
}

TEST(LoopRuleTest, EachConsistencyLimitRejectsWithItsOwnReason) {
  const LoopValidationConfig c;
  const DetectorStats a = Stats(40, 1.0, 100, 50, 2);
  struct Case {
    DetectorStats orb;
    const char* expect;
  };
  const Case cases[] = {
      {Stats(40, 1.2, 100, 50, 2), "ORB: scale 1.200 outside"},
      {Stats(40, 0.8, 100, 50, 2), "ORB: scale 0.800 outside"},
      {Stats(40, 1.0, 111, 50, 2), "|dtx| 11.0 px"},
      {Stats(40, 1.0, 100, 39, 2), "|dty| 11.0 px"},
      {Stats(40, 1.0, 100, 50, 13), "|drot| 11.0 deg"},
  };
  for (const Case& k : cases) {
    const LoopDecision d = ApplyLoopRule(a, k.orb, c);
    EXPECT_FALSE(d.accepted);
    EXPECT_NE(d.reason.find(k.expect), std::string::npos) << d.reason;
  }
  EXPECT_TRUE(ApplyLoopRule(a, Stats(40, 1.0, 109, 41, 11), c).accepted);
}

TEST(LoopRuleTest, RotationsAgreeAndFuseAcrossTheWrap) {
  const LoopDecision d = ApplyLoopRule(Stats(30, 1.0, 0, 0, 179.0), Stats(15, 1.0, 0, 0, -179.0),
                                       LoopValidationConfig{});
  ASSERT_TRUE(d.accepted) << d.reason;
  EXPECT_NEAR(WrapDegrees(d.rotation_deg - (179.0 + 2.0 / 3.0)), 0.0, 1e-9);
}

TEST(LoopRuleTest, MissingOrNonFiniteTransformsAreRejected) {
  const DetectorStats ok = Stats(30, 1.0, 0, 0, 0);
  DetectorStats none = ok;
  none.has_transform = false;
  EXPECT_FALSE(ApplyLoopRule(none, ok, {}).accepted);
  DetectorStats nan = ok;
  nan.tx_px = std::numeric_limits<double>::quiet_NaN();
  const LoopDecision d = ApplyLoopRule(ok, nan, {});
  EXPECT_FALSE(d.accepted);
  EXPECT_NE(d.reason.find("non-finite"), std::string::npos) << d.reason;
}

}  // namespace
}  // namespace uwbsar
