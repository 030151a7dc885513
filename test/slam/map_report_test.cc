// slam/map_report.h StageTimingTable: the stages' seconds, their sum and the wall time, the
// shares of the wall time, and a note that the stages overlap on two threads.
#include "slam/map_report.h"

#include <gtest/gtest.h>

namespace uwbsar::slam {
namespace {

TEST(MapReportTest, TimingTableSharesAreOfTheWallTimeAndSayTheStagesOverlap) {
  StageTimes t;
  t.imaging_s = 3.0;
  t.features_s = 2.0;
  t.matching_s = 1.0;
  t.optimization_s = 0.5;
  const ReportTable table = StageTimingTable(t, 4.0, true);
  ASSERT_EQ(table.rows.size(), 6u);
  EXPECT_EQ(table.rows[0], (std::vector<std::string>{"imaging", "feeding", "3.000", "75.0 %"}));
  EXPECT_EQ(table.rows[1][1], "keyframe");
  // The stages add up to more than the wall time: the table says both, and why.
  EXPECT_EQ(table.rows[4][0], "sum of the stages");
  EXPECT_EQ(table.rows[4][3], "162.5 %");
  EXPECT_EQ(table.rows[5][0], "wall time (the whole run)");
  EXPECT_EQ(table.rows[5][2], "4.000");
  EXPECT_NE(table.note.find("overlap"), std::string::npos) << table.note;
}

TEST(MapReportTest, TimingTableOnOneThreadSaysSo) {
  StageTimes t;
  t.imaging_s = 1.0;
  const ReportTable table = StageTimingTable(t, 2.0, false);
  EXPECT_EQ(table.rows[1][1], "feeding");
  EXPECT_EQ(table.note.find("overlap"), std::string::npos) << table.note;
  EXPECT_NE(table.note.find("one after"), std::string::npos) << table.note;
}

}  // namespace
}  // namespace uwbsar::slam
