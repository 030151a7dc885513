// Real radar data in the loop: the paper's own SAR images of its corridor (departing and
// returning strips, regions D1..D6 / R1..R6, recovered from the reference implementation's
// published figures; ../shared/data/real/seed_corridor) through uwbsar's place recognition
// (`uwbsar loops --images`, `uwbsar match`) and map comparison (`uwbsar compare`), with the
// default configuration. The truth: D_i -> R_j is (i - j) m along x, 0 along y, 0 rotation,
// up to a few cm of odometry drift; the paper's pipeline re-run on these files finds 5 of 6.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "eval/image_loop_study.h"
#include "slam/app_config.h"
#include "test/cli_runner.h"
#include "test/shared_data.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;
using testing::CliRun;
using testing::Uwbsar;

const char kRegions[] = "real/seed_corridor/regions/D1.png";

std::string RegionsDir() { return testing::SharedDataPath("real/seed_corridor/regions"); }

std::string FreshDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("uwbsar_real_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

const ImageLoopStudy& Study() {
  static const ImageLoopStudy study =
      RunImageLoopStudy(RegionsDir(), 0.005, {DetectorKind::kAkaze, DetectorKind::kOrb}, Config{},
                        Config{}.limits.max_map_image_pixels);
  return study;
}

TEST(RealCorridorTest, AllSixLoopsAreAcceptedWithTheDefaultConfiguration) {
  UWBSAR_NEED_SHARED_DATA(kRegions);
  int accepted = 0;
  for (const ImagePairResult& p : Study().pairs) {
    if (p.d != p.r) continue;
    const ImageMatch& m = p.match;
    const auto& a = m.matches.at(DetectorKind::kAkaze);
    const auto& o = m.matches.at(DetectorKind::kOrb);
    std::printf("D%d -> R%d: %s, AKAZE %d good, ORB %d good, x %+.3f m, y %+.3f m, yaw %+.2f deg\n",
                p.d, p.r, m.accepted() ? "accepted" : m.validation.reason.c_str(), a.good_matches,
                o.good_matches, m.transform.x_m, m.transform.y_m, m.transform.yaw_deg);
    EXPECT_TRUE(m.accepted()) << "D" << p.d << " -> R" << p.r << ": " << m.validation.reason;
    if (!m.accepted()) continue;
    ++accepted;
    // Within the odometry drift between the passes (the reference's own: <= 4 cm, 0.6 deg).
    EXPECT_LT(std::hypot(m.transform.x_m, m.transform.y_m), 0.05) << "D" << p.d;
    EXPECT_LT(std::abs(m.transform.yaw_deg), 1.0) << "D" << p.d;
  }
  EXPECT_EQ(accepted, 6);  // the paper's pipeline on these files: 5 (D2 missed)
}

TEST(RealCorridorTest, NoFalseLoopAmongTheThirtyNonLoopPairs) {
  UWBSAR_NEED_SHARED_DATA(kRegions);
  int accepted_off_diagonal = 0;
  for (const ImagePairResult& p : Study().pairs) {
    if (p.d == p.r || !p.match.accepted()) continue;
    ++accepted_off_diagonal;
    const CentredTransform& t = p.match.transform;
    const double expected_x_m = p.d - p.r;
    std::printf("D%d -> R%d accepted: x %+.3f m (expected %+.1f), y %+.3f m, yaw %+.2f deg\n", p.d,
                p.r, t.x_m, expected_x_m, t.y_m, t.yaw_deg);
    // Regions 1 m apart share half their area: allowed only with the right offset.
    EXPECT_LE(std::abs(p.d - p.r), 1) << "D" << p.d << " -> R" << p.r << " is a false loop";
    EXPECT_LT(std::hypot(t.x_m - expected_x_m, t.y_m), 0.25) << "D" << p.d << " -> R" << p.r;
    EXPECT_LT(std::abs(t.yaw_deg), 3.0) << "D" << p.d << " -> R" << p.r;
  }
  std::printf("%d of 30 non-loop pairs accepted\n", accepted_off_diagonal);
}

TEST(RealCorridorTest, LoopsCommandWritesTheMatrixTablesAndPicture) {
  UWBSAR_NEED_SHARED_DATA(kRegions);
  const std::string out = FreshDir("loops");
  const CliRun r = Uwbsar("loops --images " + RegionsDir() + " --json --out " + out, false);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output);
  ASSERT_EQ(j["loops"].size(), 6u);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(j["loops"][i][i], 1) << "D" << i + 1;
  EXPECT_EQ(j["pairs"].size(), 36u);
  for (const char* f : {"pairs.csv", "pairs.md", "loops.json", "matrix.png"}) {
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  }
  std::ifstream csv(out + "/pairs.csv");
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, 37);  // header + 36 pairs
  EXPECT_FALSE(cv::imread(out + "/matrix.png").empty());
}

TEST(RealCorridorTest, MatchPrintsTheDocumentedJsonShape) {
  UWBSAR_NEED_SHARED_DATA(kRegions);
  const std::string out = FreshDir("match");
  const CliRun r = Uwbsar(
      "match " + RegionsDir() + "/D3.png " + RegionsDir() + "/R2.png --json --out " + out, false);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output);
  for (const char* key : {"accepted", "reason", "transform", "detectors"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  for (const char* det : {"akaze", "orb"}) {
    const nlohmann::json& d = j["detectors"][det];
    for (const char* key : {"keypoints", "ratio_matches", "good", "scale", "x_m", "y_m", "yaw_deg"})
      EXPECT_TRUE(d.contains(key)) << det << "." << key;
    EXPECT_EQ(d["keypoints"].size(), 2u);
  }
  if (j["accepted"].get<bool>()) {  // D3 -> R2: 1 m apart, allowed only with the right offset
    EXPECT_NEAR(j["transform"]["x_m"].get<double>(), 1.0, 0.25);
    EXPECT_EQ(j["reason"], "");
  } else {
    EXPECT_TRUE(j["transform"].is_null());
    EXPECT_NE(j["reason"], "");
  }
  EXPECT_FALSE(cv::imread(out + "/match.png").empty());
}

TEST(RealCorridorTest, DepartingStripAgainstTheLidarGridBeatsThePapersFigure) {
  UWBSAR_NEED_SHARED_DATA("real/seed_corridor/departing.png");
  UWBSAR_NEED_SEED_LAB_MAP();
  // The grid YAML shipped with the test data names the image relative to itself; point it
  // at wherever the shared data is.
  const std::string dir = FreshDir("compare");
  std::ifstream shipped(std::string(UWBSAR_SOURCE_DIR) +
                        "/test/data/real/seed_corridor/departing_grid.yaml");
  ASSERT_TRUE(shipped.good());
  std::ofstream grid(dir + "/departing_grid.yaml");
  for (std::string line; std::getline(shipped, line);) {
    grid << (line.rfind("image:", 0) == 0
                 ? "image: " + testing::SharedDataPath("real/seed_corridor/departing.png")
                 : line)
         << "\n";
  }
  grid.close();
  const CliRun r = Uwbsar("compare " + dir + "/departing_grid.yaml " + testing::SeedLabLidarMap() +
                              " --json --out " + dir + "/out",
                          false);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(r.output);
  const nlohmann::json& m = j["metrics"];
  const nlohmann::json& c = j["cells"];
  std::printf(
      "real departing strip vs LiDAR: paper counting %d / %d = %.2f %% (paper 1397 / 16800 = "
      "8.3 %%), observed cells %d / %d = %.2f %%, precision %.3f, recall %.3f, F1 %.3f, "
      "SAR->LiDAR mean %.3f m p95 %.3f m, LiDAR->SAR mean %.3f m; ICP %s, T = (%.3f m, %.3f m, "
      "%.2f deg)\n",
      c["sar_rectangle_differing"].get<int>(), c["sar_rectangle"].get<int>(),
      100.0 * m["paper_difference_ratio"].get<double>(), c["differing"].get<int>(),
      c["evaluated"].get<int>(), 100.0 * m["difference_ratio"].get<double>(),
      m["precision"].get<double>(), m["recall"].get<double>(), m["f1"].get<double>(),
      m["sar_to_lidar"]["mean_m"].get<double>(), m["sar_to_lidar"]["p95_m"].get<double>(),
      m["lidar_to_sar"]["mean_m"].get<double>(),
      j["alignment"]["accepted"].get<bool>() ? "converged" : "failed",
      j["alignment"]["T_lidar_sar"]["x_m"].get<double>(),
      j["alignment"]["T_lidar_sar"]["y_m"].get<double>(),
      j["alignment"]["T_lidar_sar"]["yaw_deg"].get<double>());
  EXPECT_TRUE(j["alignment"]["accepted"].get<bool>()) << j["alignment"]["reason"];
  EXPECT_EQ(c["sar_rectangle"].get<int>(), 140 * 120);  // 7 m x 6 m at 5 cm, as the paper
  EXPECT_LE(m["paper_difference_ratio"].get<double>(), 0.083);
  EXPECT_TRUE(fs::exists(dir + "/out/overlay.png"));
}

TEST(MatchCliTest, BadInputExitsThreeWithOneLine) {
  const std::string dir = FreshDir("match_bad");
  cv::Mat texture(200, 200, CV_8UC1);
  cv::randu(texture, 0, 255);
  cv::imwrite(dir + "/a.png", texture);
  cv::imwrite(dir + "/uniform.png", cv::Mat(200, 200, CV_8UC1, cv::Scalar(128)));
  cv::imwrite(dir + "/black.png", cv::Mat(200, 200, CV_8UC1, cv::Scalar(0)));
  cv::Mat big(2000, 2000, CV_8UC1);
  cv::randu(big, 0, 255);
  cv::imwrite(dir + "/big.png", big);
  std::ofstream(dir + "/not_an_image.png") << "hello";
  const std::string a = dir + "/a.png";
  for (const std::string& b : {dir + "/missing.png", dir + "/uniform.png", dir + "/black.png",
                               dir + "/big.png", dir + "/not_an_image.png"}) {
    const CliRun r = Uwbsar("match " + a + " " + b);
    EXPECT_EQ(r.exit_code, 3) << b << ": " << r.output;
    EXPECT_NE(r.output.find(b.substr(dir.size() + 1)), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
  // A pair with nothing in common is an outcome, not an error.
  cv::Mat other(200, 200, CV_8UC1);
  cv::randu(other, 0, 255);
  cv::imwrite(dir + "/b.png", other);
  const CliRun r = Uwbsar("match " + a + " " + dir + "/b.png --json", false);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(nlohmann::json::parse(r.output)["accepted"].get<bool>());
}

}  // namespace
}  // namespace uwbsar
