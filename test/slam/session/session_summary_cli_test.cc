// One shape for every folder (issue 49, items 3 and 4): the summary.json of `map --resume`,
// `merge` and `localize` holds every key a single `map` run's has, of the same type, and a
// joined folder holds the files of a single run's; the loop and keyframe counts that
// `map --resume` prints, writes into summary.json and shows in report.html agree.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

#include "test/cli_runner.h"
#include "test/slam/session/session_cli_fixture.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;
using testing::CliRun;
using testing::Json;
using testing::SessionCliTest;
using testing::Uwbsar;

/// Every key path of `single` (objects followed, the first element of arrays) that `other`
/// lacks or holds with another JSON type ("runs[].ate: missing"); null counts as present.
void MissingKeys(const nlohmann::json& single, const nlohmann::json& other, const std::string& at,
                 std::vector<std::string>* missing) {
  for (auto it = single.begin(); it != single.end(); ++it) {
    const std::string path = at + it.key();
    if (!other.contains(it.key())) {
      missing->push_back(path + ": missing");
      continue;
    }
    const nlohmann::json& o = other[it.key()];
    const bool both_numbers = it->is_number() && o.is_number();
    if (o.is_null()) continue;  // present, and not applicable (docs/formats.md says where)
    if (it->type() != o.type() && !both_numbers) {
      missing->push_back(path + ": " + o.type_name() + " instead of " + it->type_name());
    } else if (it->is_object()) {
      MissingKeys(*it, o, path + ".", missing);
    } else if (it->is_array() && !it->empty() && !o.empty() && it->front().is_object()) {
      for (const nlohmann::json& element : o)
        MissingKeys(it->front(), element, path + "[].", missing);
    }
  }
}

std::string Text(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

int Number(const std::string& text, const std::string& pattern) {
  std::smatch m;
  if (!std::regex_search(text, m, std::regex(pattern))) return -1;
  return std::stoi(m[1]);
}

TEST_F(SessionCliTest, EveryFolderHasTheSummaryKeysAndFilesOfASingleRun) {
  const nlohmann::json single = Json(Map("a") + "/summary.json");
  ASSERT_TRUE(single.contains("ate")) << "the fixture's bags have ground truth";
  const std::string resumed = *dir_ + "/shape_resumed", merged = *dir_ + "/shape_merged",
                    localized = *dir_ + "/shape_localized";
  for (const std::string& args :
       {"map " + Bag("b") + " --resume " + Map("a") + " --out " + resumed,
        "merge " + Map("a") + " " + Map("b") + " --out " + merged,
        "localize " + Bag("b") + " --map " + Map("a") + " --out " + localized}) {
    const CliRun r = Uwbsar("-q " + args);
    ASSERT_EQ(r.exit_code, 0) << args << "\n" << r.output;
  }
  for (const std::string& dir : {resumed, merged, localized}) {
    std::vector<std::string> missing;
    MissingKeys(single, Json(dir + "/summary.json"), "", &missing);
    EXPECT_TRUE(missing.empty()) << dir << ": " << ::testing::PrintToString(missing);
  }
  // Every run with ground truth keeps its ATE, the saved map's run 0 too.
  for (const std::string& dir : {resumed, merged}) {
    const nlohmann::json s = Json(dir + "/summary.json");
    for (const nlohmann::json& run : s["runs"]) {
      EXPECT_TRUE(run.contains("ate")) << dir << ": " << run.dump();
    }
    // The files the README's output table lists for a map folder, beside the per-run ones.
    for (const char* f : {"trajectory.tum", "odometry.tum", "ground_truth.tum", "loops.csv",
                          "graph.g2o", "trajectory_0.tum", "trajectory_1.tum"}) {
      EXPECT_TRUE(fs::exists(dir + "/" + f)) << dir << "/" << f;
    }
    // trajectory.tum holds every run, one after another.
    std::size_t per_run = 0;
    for (const nlohmann::json& run : s["runs"]) {
      per_run += Text(dir + "/" + run["tum"].get<std::string>()).size();
    }
    EXPECT_EQ(Text(dir + "/trajectory.tum").size(), per_run) << dir;
  }
}

TEST_F(SessionCliTest, ResumePrintsTheLoopAndKeyframeCountsOfItsSummaryAndReport) {
  const std::string out = *dir_ + "/counts_resumed";
  const CliRun r = Uwbsar("map " + Bag("b") + " --resume " + Map("a") + " --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json s = Json(out + "/summary.json");
  const std::string html = Text(out + "/report.html");
  // Found by the join, and accepted in the map (the loops of retired views go with them).
  const int found = Number(r.output, R"((\d+) loops between the runs found by the join)");
  const int accepted = Number(r.output, R"((\d+) loops accepted in the map)");
  const int between = Number(r.output, R"(accepted in the map \((\d+) between runs\))");
  EXPECT_EQ(found, s["merge"]["loop_edges"].get<int>()) << r.output;
  EXPECT_EQ(accepted, s["loops"]["accepted"].get<int>()) << r.output;
  EXPECT_EQ(between, s["loops"]["between_runs"].get<int>()) << r.output;
  EXPECT_EQ(Number(html, R"(<th>loops accepted</th><td>(\d+)</td>)"), accepted);
  EXPECT_EQ(Number(html, R"(<th>loops accepted between runs</th><td>(\d+)</td>)"), between);
  EXPECT_EQ(Number(html, R"(<th>loops between the runs found by the join</th><td>(\d+)</td>)"),
            found);
  int between_rows = 0;  // the loop table's rows of loops between the runs
  for (auto at = html.find("<td>between sessions</td>"); at != std::string::npos;
       at = html.find("<td>between sessions</td>", at + 1)) {
    ++between_rows;
  }
  EXPECT_GE(between_rows, between);
  // Run 0 made the saved map's keyframes, whether the new run retired them or not.
  const nlohmann::json single = Json(Map("a") + "/summary.json");
  EXPECT_EQ(s["runs"][0]["keyframes"], single["runs"][0]["keyframes"]) << s["runs"].dump();
  const int kept_0 = s["runs"][0]["keyframes_kept"].get<int>();
  EXPECT_EQ(kept_0 + s["runs"][1]["keyframes_kept"].get<int>(), s["keyframes"].get<int>());
  EXPECT_NE(html.find("<th>keyframes</th><td>" + single["runs"][0]["keyframes"].dump() + " (" +
                      std::to_string(kept_0) + " kept in the map)</td>"),
            std::string::npos);
}

}  // namespace
}  // namespace uwbsar
