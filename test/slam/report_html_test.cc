// slam/outputs/report_html.h: the trajectory plot has axes in metres, start and end markers and
// its loops above the paths; per-run sections and table notes are rendered.
#include "slam/outputs/report_html.h"

#include <gtest/gtest.h>

#include "slam/outputs/map_figure.h"

namespace uwbsar::slam {
namespace {

RunReport TwoPaths() {
  RunReport r;
  r.title = "t";
  r.trajectories.push_back({"ground truth", FigurePalette::kGroundTruth.css, {{0, 0}, {4, 1}}});
  r.trajectories.push_back({"SLAM", FigurePalette::kSlam.css, {{0, 0.1}, {4, 1.1}}});
  r.loop_segments.push_back({{0, 0}, {4, 1}});
  return r;
}

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(ReportHtmlTest, TrajectoryPlotHasAxesMarkersAndLoopsAbovePaths) {
  const std::string html = RenderReportHtml(TwoPaths());
  EXPECT_NE(html.find(">x (m)<"), std::string::npos);
  EXPECT_NE(html.find(">y (m)<"), std::string::npos);
  EXPECT_GE(Count(html, "class=\"tick\""), 6u);
  EXPECT_EQ(Count(html, "class=\"start\""), 2u);
  EXPECT_EQ(Count(html, "class=\"end\""), 2u);
  // SVG paints in document order: the loop comes after the last path.
  ASSERT_NE(html.find("class=\"loop\""), std::string::npos);
  EXPECT_GT(html.find("class=\"loop\""), html.rfind("<polyline"));
  // The legend names every path, the loops and the markers, in the paths' colours.
  for (const char* label : {">ground truth<", ">SLAM<", ">accepted loop<", ">start<", ">end<"}) {
    EXPECT_NE(html.find(label), std::string::npos) << label;
  }
  EXPECT_NE(html.find(std::string("stroke=\"") + FigurePalette::kGroundTruth.css),
            std::string::npos);
}

TEST(ReportHtmlTest, SectionsAndTableNotesAreRendered) {
  RunReport r = TwoPaths();
  r.tables.push_back({"Time per stage", {"stage", "seconds"}, {{"imaging", "1.0"}}, "overlap"});
  RunReport run = TwoPaths();
  run.title = "Run 0: a.db3";
  run.summary.push_back({"keyframes", "3"});
  r.sections.push_back(run);
  run.title = "Run 1: b.db3";
  r.sections.push_back(run);
  const std::string html = RenderReportHtml(r);
  EXPECT_NE(html.find("<p class=\"note\">overlap</p>"), std::string::npos);
  EXPECT_NE(html.find("<h2>Run 0: a.db3</h2>"), std::string::npos);
  EXPECT_NE(html.find("<h2>Run 1: b.db3</h2>"), std::string::npos);
  EXPECT_EQ(Count(html, "<h3>Trajectory</h3>"), 2u);
  EXPECT_EQ(Count(html, "<svg"), 3u);
  EXPECT_LT(html.find("Time per stage"), html.find("Run 0: a.db3"));
}

}  // namespace
}  // namespace uwbsar::slam
