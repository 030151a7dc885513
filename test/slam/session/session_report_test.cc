// The report.html of a joined session (slam/outputs/session_outputs.h,
// slam/outputs/session_report.h) is as full as a plain map's: the timings it is given, the loop
// table, the annotated figure of all runs and one section per run with that run's own figure.
#include "slam/outputs/session_report.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "slam/outputs/session_outputs.h"
#include "test/slam/session/tiny_session.h"

namespace uwbsar::slam {
namespace {

namespace fs = std::filesystem;

/// TinySession with a second run: its keyframes 3..5 a metre north of the first's, a loop
/// between the runs and one within the second.
SessionData TwoRuns() {
  SessionData s = testing::TinySession();
  s.trajectories.push_back({1, "second.db3", "storage:second"});
  const std::size_t n = s.keyframes.size();
  for (std::size_t i = 0; i < n; ++i) {
    SessionKeyframe k = s.keyframes[i];
    k.id = static_cast<int>(n + i);
    k.trajectory = 1;
    k.fixed = false;
    k.T_map_anchor.y_m += 1.0;
    s.keyframes.push_back(k);
  }
  for (int i = 0; i < 5; ++i) {
    s.odometry.push_back({1, 500000000LL * (i + 1), Pose2{0.5 * i, 0.25 * i, 0.05 * i}, 0.6 * i});
  }
  SessionLoop between = s.loops.front();
  between.query_id = 4, between.match_id = 1, between.accepted = false, between.reason = "chi2";
  s.loops.push_back(between);
  SessionLoop within = s.loops.front();
  within.query_id = 5, within.match_id = 3;
  s.loops.push_back(within);
  return s;
}

std::string Read(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::size_t Count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(SessionReportTest, LoopTableNamesEachLoopsRunsAndOutcome) {
  const ReportTable table = SessionLoopTable(TwoRuns());
  ASSERT_EQ(table.rows.size(), 3u);
  EXPECT_EQ(table.header[2], "query run");
  EXPECT_EQ(table.header[3], "match run");
  EXPECT_EQ(table.rows[1][0], "4");
  EXPECT_EQ(table.rows[1][2], "1");  // keyframe 4 is on the second run
  EXPECT_EQ(table.rows[1][3], "0");
  EXPECT_EQ(table.rows[1].back(), "chi2");
  // Accepted by the validator, rejected by the backend.
  const auto backend = std::find(table.header.begin(), table.header.end(), "backend");
  ASSERT_NE(backend, table.header.end());
  EXPECT_EQ(table.rows[1][static_cast<std::size_t>(backend - table.header.begin())], "rejected");
  EXPECT_EQ(table.rows[2][static_cast<std::size_t>(backend - table.header.begin())], "accepted");
}

TEST(SessionReportTest, LoopSegmentsOfARunKeepOnlyItsOwnLoops) {
  const SessionData s = TwoRuns();
  EXPECT_EQ(SessionLoopSegments(s).size(), 2u);  // the rejected one is not drawn
  EXPECT_EQ(SessionLoopSegments(s, 0).size(), 1u);
  ASSERT_EQ(SessionLoopSegments(s, 1).size(), 1u);
  EXPECT_DOUBLE_EQ(SessionLoopSegments(s, 1)[0].first.y_m, s.keyframes[3].T_map_anchor.y_m);
}

TEST(SessionReportTest, JoinedReportHasTimingsLoopTableAndEveryRunsSection) {
  const std::string dir =
      (fs::temp_directory_path() / ("uwbsar_session_report_" + std::to_string(::getpid())))
          .string();
  fs::remove_all(dir);
  const Config config;
  const std::vector<ReportTable> timing = {
      {"Time per stage of run 1", {"stage", "seconds"}, {{"imaging", "1.000"}}, ""}};
  WriteSessionOutputs(TwoRuns(), config, dir, {}, nlohmann::json::object(), "joined", timing);
  const std::string html = Read(dir + "/report.html");
  fs::remove_all(dir);
  EXPECT_NE(html.find("<h2>Time per stage of run 1</h2>"), std::string::npos);
  // Earlier runs' timings are not in the session: the report says where they are.
  EXPECT_NE(html.find("their own report.html"), std::string::npos);
  EXPECT_NE(html.find("<h2>Loop candidates</h2>"), std::string::npos);
  EXPECT_NE(html.find("<h2>Run 0: tiny.db3</h2>"), std::string::npos);
  EXPECT_NE(html.find("<h2>Run 1: second.db3</h2>"), std::string::npos);
  // The figure of all runs and one of each run's own map; a plot of all and of each.
  EXPECT_EQ(Count(html, "data:image/png;base64,"), 3u);
  EXPECT_EQ(Count(html, "<svg"), 3u);
  EXPECT_LT(html.find("Loop candidates"), html.find("Run 0: tiny.db3"));
}

}  // namespace
}  // namespace uwbsar::slam
