#include "eval/loop_stats.h"

#include <gtest/gtest.h>

#include "core/errors.h"

namespace uwbsar {
namespace {

const char* kHeader =
    "d,r,n_akaze,scale_akaze,tx_akaze_px,ty_akaze_px,rot_akaze_deg,n_orb,scale_orb,tx_orb_px,"
    "ty_orb_px,rot_orb_deg\n";

TEST(LoopStatsTest, PaperLikeStatsGiveTheDiagonalLoopMatrix) {
  // D1->R1 and D2->R2 are loops (paper Table III); D1->R2 is not (paper Table IV style).
  const std::string csv = std::string(kHeader) +
                          "1,1,40,1.00,5.0,-7.3,-0.63,30,1.00,5.5,-9.5,-0.66\n"
                          "2,2,25,1.00,3.1,-7.0,-0.28,20,0.99,10.7,-4.1,-1.51\n"
                          "1,2,5,1.16,-340,54,20.59,7,1.13,-334,78,21.21\n"
                          "2,1,3,-,-,-,-,8,0.05,28,826,7.11\n";
  const std::vector<PairStats> stats = ParsePairStats(csv, "s.csv");
  ASSERT_EQ(stats.size(), 4u);
  EXPECT_FALSE(stats[3].detectors.at(DetectorKind::kAkaze).has_transform);
  const LoopMatrix m = EvaluateLoopMatrix(stats, LoopValidationConfig{});
  EXPECT_EQ(m.d_ids, (std::vector<int>{1, 2}));
  EXPECT_EQ(m.r_ids, (std::vector<int>{1, 2}));
  EXPECT_EQ(m.loops, (std::vector<std::vector<int>>{{1, 0}, {0, 1}}));
  EXPECT_TRUE(m.reasons[0][0].empty());
  EXPECT_NE(m.reasons[0][1].find("AKAZE: 5 good matches"), std::string::npos);
}

TEST(LoopStatsTest, ThresholdsComeFromTheConfig) {
  const std::string csv = std::string(kHeader) + "1,1,8,1.0,0,0,0,9,1.0,0,0,0\n";
  LoopValidationConfig c;
  EXPECT_EQ(EvaluateLoopMatrix(ParsePairStats(csv, "s"), c).loops[0][0], 0);
  c.min_good_matches = 5;
  EXPECT_EQ(EvaluateLoopMatrix(ParsePairStats(csv, "s"), c).loops[0][0], 1);
}

TEST(LoopStatsTest, RowsRoundTripThroughTheWriter) {
  PairStats p;
  p.d = 3;
  p.r = 4;
  p.detectors[DetectorKind::kAkaze] = {12, true, 1.01, 2.5, -3.25, 0.5};
  p.detectors[DetectorKind::kOrb].good_matches = 2;  // no transform
  const std::vector<PairStats> back =
      ParsePairStats(std::string(kHeader) + PairStatsRow(p) + "\n", "s");
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].d, 3);
  EXPECT_DOUBLE_EQ(back[0].detectors.at(DetectorKind::kAkaze).ty_px, -3.25);
  EXPECT_FALSE(back[0].detectors.at(DetectorKind::kOrb).has_transform);
  EXPECT_EQ(back[0].detectors.at(DetectorKind::kOrb).good_matches, 2);
}

TEST(LoopStatsTest, ColumnsMayComeInAnyOrderWithExtras) {
  const std::string csv =
      "r,d,note,n_orb,scale_orb,tx_orb_px,ty_orb_px,rot_orb_deg,n_akaze,scale_akaze,tx_akaze_px,"
      "ty_akaze_px,rot_akaze_deg\n"
      "2,1,hello,30,1,0,0,0,40,1,0,0,0\n";
  const std::vector<PairStats> s = ParsePairStats(csv, "s");
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].d, 1);
  EXPECT_EQ(s[0].r, 2);
  EXPECT_EQ(s[0].detectors.at(DetectorKind::kAkaze).good_matches, 40);
}

void ExpectInputError(const std::string& csv, const std::string& fragment) {
  try {
    ParsePairStats(csv, "stats.csv");
    FAIL() << "expected InputError for: " << csv;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(LoopStatsTest, BadInputNamesFileLineAndColumn) {
  ExpectInputError("", "no header");
  ExpectInputError("d,r,n_akaze\n1,1,3\n", "lacks column 'scale_akaze'");
  ExpectInputError(std::string(kHeader) + "1,1,abc,1,0,0,0,3,1,0,0,0\n",
                   "stats.csv:2: column 'n_akaze'");
  ExpectInputError(std::string(kHeader) + "1,1,3,1,0,0,0,3,1,0,0,x\n", "column 'rot_orb_deg'");
  ExpectInputError(std::string(kHeader) + "1,1,3,1,0,0,0,3,1,0\n", "missing field");
  ExpectInputError(std::string(kHeader) + "1,1,3,1,-,0,0,3,1,0,0,0\n", "partly given");
  ExpectInputError(std::string(kHeader) + "-1,1,3,1,0,0,0,3,1,0,0,0\n", "column 'd'");
  ExpectInputError(std::string(kHeader) + "1,1,3,1,0,0,0,3,1,0,0,0\n1,1,3,1,0,0,0,3,1,0,0,0\n",
                   "listed twice");
}

}  // namespace
}  // namespace uwbsar
