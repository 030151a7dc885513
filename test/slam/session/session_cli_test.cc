// The session commands as a user meets them, on short simulated runs in the
// bundled seed_hall room: `map` writes session.uwbsar; `map --resume` joins a revisit and
// writes one map with a trajectory per run; `localize` places a revisit without changing
// the map; `merge` joins two sessions and refuses two of different buildings; a session
// of an incompatible configuration or a file that is not a session ends with one line and
// exit code 3.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "test/cli_runner.h"
#include "test/slam/session/session_cli_fixture.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;
using testing::CliRun;
using testing::Json;
using testing::Lines;
using testing::SessionCliTest;
using testing::Uwbsar;

std::string Text(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::size_t Occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST_F(SessionCliTest, MapWritesAnSqliteSession) {
  const std::string path = Map("a") + "/session.uwbsar";
  ASSERT_TRUE(fs::exists(path));
  std::ifstream in(path, std::ios::binary);
  std::string magic(15, '\0');
  in.read(magic.data(), 15);
  EXPECT_EQ(magic, "SQLite format 3");
}

TEST_F(SessionCliTest, ResumeJoinsTheRevisitAsASecondRun) {
  const std::string out = *dir_ + "/resumed";
  const CliRun r = Uwbsar("--config " + *dir_ + "/b.yaml map " + Bag("b") + " --resume " +
                          Map("a") + " --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json s = Json(out + "/summary.json");
  EXPECT_TRUE(s["merge"]["connected"].get<bool>()) << s.dump(2);
  EXPECT_LE(s["merge"]["connect_path_m"].get<double>(), 3.0);
  EXPECT_EQ(s["runs"].size(), 2u);
  for (const char* f : {"trajectory_0.tum", "trajectory_1.tum", "map.png", "report.html",
                        "session.uwbsar", "map_grid.yaml", "map.yaml", "graph.g2o"}) {
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  }
  // The report is as full as a plain map's: this run's stage times, the loop table, and a
  // section per run, the saved map's run 0 with its own figure too.
  const std::string html = Text(out + "/report.html");
  for (const char* part :
       {"<h2>Time per stage of run 1 (mapped by this command)</h2>", "The stages overlap",
        "<h2>Loop candidates</h2>", "<h2>Run 0: ", "<h2>Run 1: "}) {
    EXPECT_NE(html.find(part), std::string::npos) << part;
  }
  EXPECT_EQ(Occurrences(html, "data:image/png;base64,"), 3u);  // all runs, run 0, run 1
  // The joined session reads back: a revisit localises in it.
  const CliRun again =
      Uwbsar("localize " + Bag("b") + " --map " + out + " --out " + *dir_ + "/again");
  EXPECT_EQ(again.exit_code, 0) << again.output;
}

TEST_F(SessionCliTest, ResumeIntoAPlainMapsFolderReplacesItsOutputsAsOneSet) {
  // Resuming into the saved map's own folder: the joined set replaces the plain map's files
  // (trajectory.tum, odometry.tum, ground_truth.tum and loops.csv now over both runs; no other
  // file of the earlier run, such as trajectory_aligned.tum or a stale trajectory_9.tum, is left).
  const std::string out = *dir_ + "/resumed_in_place";
  fs::copy(Map("a"), out, fs::copy_options::recursive);
  std::ofstream(out + "/trajectory_9.tum") << "stale\n";
  const CliRun r = Uwbsar("-q --config " + *dir_ + "/b.yaml map " + Bag("b") + " --resume " + out +
                          " --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(out)) names.insert(e.path().filename().string());
  const std::set<std::string> expected = {
      ".uwbsar.lock",     "trajectory_0.tum",   "trajectory_1.tum",  "map.png",
      "map_float.tif",    "map_grid.yaml",      "map.yaml",          "map.pgm",
      "graph.g2o",        "session.uwbsar",     "report.html",       "summary.json",
      "results.mcap",     "trajectory.tum",     "odometry.tum",      "loops.csv",
      "ground_truth.tum", "ground_truth_0.tum", "ground_truth_1.tum"};
  EXPECT_EQ(names, expected);
  EXPECT_EQ(Json(out + "/summary.json")["runs"].size(), 2u);
}

TEST_F(SessionCliTest, LocalizePlacesTheRevisitWithoutChangingTheMap) {
  const std::string out = *dir_ + "/localized";
  const auto before = fs::last_write_time(Map("a") + "/session.uwbsar");
  const CliRun r = Uwbsar("localize " + Bag("b") + " --map " + Map("a") + " --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json s = Json(out + "/summary.json");
  ASSERT_FALSE(s["first_fix"].is_null()) << s.dump(2);
  EXPECT_LE(s["first_fix"]["path_m"].get<double>(), 3.0);
  EXPECT_TRUE(fs::exists(out + "/localize.csv"));
  EXPECT_TRUE(fs::exists(out + "/trajectory.tum"));
  EXPECT_EQ(fs::last_write_time(Map("a") + "/session.uwbsar"), before);
}

TEST_F(SessionCliTest, MergeReportHasTheMergeTimeTheLoopTableAndEachRun) {
  const std::string out = *dir_ + "/m_ab";
  const CliRun r = Uwbsar("-q merge " + Map("a") + " " + Map("b") + " --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string html = Text(out + "/report.html");
  for (const char* part : {"<h2>Time to merge</h2>", "their own report.html",
                           "<h2>Loop candidates</h2>", "<h2>Run 0: ", "<h2>Run 1: "}) {
    EXPECT_NE(html.find(part), std::string::npos) << part;
  }
  EXPECT_EQ(Occurrences(html, "data:image/png;base64,"), 3u);
}

TEST_F(SessionCliTest, MergeRefusesSessionsThatNoLoopConnects) {
  const CliRun r = Uwbsar("merge " + Map("a") + " " + Map("c") + " --out " + *dir_ + "/m_ac");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("cannot be merged"), std::string::npos) << r.output;
  EXPECT_EQ(Lines(r.output), 1) << r.output;
}

TEST_F(SessionCliTest, IncompatibleOrForeignSessionsEndWithOneLine) {
  std::ofstream(*dir_ + "/coarse.yaml") << "imaging:\n  pixel_size_m: 0.01\n";
  const CliRun r = Uwbsar("--config " + *dir_ + "/coarse.yaml map " + Bag("b") + " --resume " +
                          Map("a") + " --out " + *dir_ + "/r_bad");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("imaging.pixel_size_m"), std::string::npos) << r.output;
  EXPECT_EQ(Lines(r.output), 1) << r.output;
  std::ofstream(*dir_ + "/fake.uwbsar") << "not a session\n";
  const CliRun f =
      Uwbsar("localize " + Bag("b") + " --map " + *dir_ + "/fake.uwbsar --out " + *dir_ + "/l_bad");
  EXPECT_EQ(f.exit_code, 3) << f.output;
  EXPECT_NE(f.output.find("not a uwbsar session"), std::string::npos) << f.output;
  EXPECT_EQ(Lines(f.output), 1) << f.output;
}

}  // namespace
}  // namespace uwbsar
