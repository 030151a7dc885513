// The dense refinement of near agreements (frontend/place_recognition/dense_refinement.h) on the
// paper's real corridor images (../shared/data/real/seed_corridor). Region D_d maps onto R_r by
// (d - r) m along x, 0 along y, 0 rotation (up to a few cm of odometry drift), so a refinement
// seeded near that truth must find it with a distinct peak, and one seeded where no loop is
// (regions 2 m or more apart, or a neighbour seeded 1 m off) must be refused. The second split
// cuts D and R from the stitched strips at the regions' boundaries (the stitched strips are
// normalised over the whole strip, so their pixels differ from the regions' by up to 78 gray
// levels): the pairs the rule rejects there by a small margin go through the refinement.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "eval/image_loop_study.h"
#include "frontend/place_recognition/dense_refinement.h"
#include "slam/app_config.h"
#include "test/shared_data.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;

const char kRegions[] = "real/seed_corridor/regions/D1.png";

ImageFeatures Region(const std::string& name) {
  const Config config;
  const SarImageFile file =
      ReadSarImageFile(testing::SharedDataPath("real/seed_corridor/regions/" + name + ".png"),
                       0.005, config.limits.max_map_image_pixels);
  return ExtractImageFeatures(file, {}, config,
                              ImageFeatureResolution(0.005, 0.005, PlaceRecognizerConfig(config)));
}

const std::vector<ImageFeatures>& Regions(char side) {
  static std::vector<ImageFeatures> d, r;
  std::vector<ImageFeatures>& v = side == 'D' ? d : r;
  if (v.empty()) {
    for (int i = 1; i <= 6; ++i) v.push_back(Region(std::string(1, side) + std::to_string(i)));
  }
  return v;
}

/// The truth of D_d onto R_r as the refinement's pixel transform (R is a, D is b).
PixelRigid Truth(int d, int r, double resolution_m) { return {(d - r) / resolution_m, 0.0, 0.0}; }

TEST(RealCorridorRefinementTest, TruePairsSeededOffTheTruthFindItWithADistinctPeak) {
  UWBSAR_NEED_SHARED_DATA(kRegions);
  const DenseRefinementConfig config = Config{}.place_recognition.validation.refinement;
  for (int i = 1; i <= 6; ++i) {
    const ImageFeatures& d = Regions('D')[i - 1];
    const ImageFeatures& r = Regions('R')[i - 1];
    const double res = d.grid.resolution_m;
    // Seeded 3 cm and 0.5 deg off, as two detectors 6 px apart would fuse.
    PixelRigid seed = Truth(i, i, res);
    seed.tx_px += 0.03 / res;
    seed.ty_px -= 0.02 / res;
    seed.rotation_deg += 0.5;
    const DenseRefinement f = RefineByCorrelation(r.image, d.image, seed, res, config);
    std::printf(
        "D%d -> R%d: peak %.3f, second %.3f, ratio %.2f, at (%+.3f m, %+.3f m, %+.2f deg)\n", i, i,
        f.peak_ncc, f.second_ncc, f.peak_ratio, f.transform.tx_px * res, f.transform.ty_px * res,
        f.transform.rotation_deg);
    ASSERT_TRUE(f.found) << "D" << i << ": " << f.reason;
    EXPECT_GE(f.peak_ratio, config.min_peak_ratio) << "D" << i;
    EXPECT_GE(f.peak_ncc, config.min_peak_ncc) << "D" << i;
    // Within the odometry drift between the passes (the accepted loops: <= 2.7 cm, 0.75 deg).
    EXPECT_LT(std::hypot(f.transform.tx_px, f.transform.ty_px) * res, 0.04) << "D" << i;
    EXPECT_LT(std::abs(f.transform.rotation_deg), 1.0) << "D" << i;
  }
}

TEST(RealCorridorRefinementTest, PairsSeededWhereNoLoopIsAreRefused) {
  UWBSAR_NEED_SHARED_DATA(kRegions);
  const DenseRefinementConfig config = Config{}.place_recognition.validation.refinement;
  int refused = 0, tried = 0;
  double max_ratio = 0.0, max_ncc = 0.0;
  for (int d = 1; d <= 6; ++d) {
    for (int r = 1; r <= 6; ++r) {
      if (d == r) continue;
      const ImageFeatures& a = Regions('R')[r - 1];
      const ImageFeatures& b = Regions('D')[d - 1];
      // Seeded as if D_d were R_r (identity): no overlap at all for regions 2 m or more apart,
      // 1 m off for neighbours.
      const DenseRefinement f =
          RefineByCorrelation(a.image, b.image, {}, a.grid.resolution_m, config);
      ++tried;
      const bool accepted =
          f.found && f.peak_ratio >= config.min_peak_ratio && f.peak_ncc >= config.min_peak_ncc;
      refused += !accepted;
      if (f.found) max_ratio = std::max(max_ratio, f.peak_ratio);
      max_ncc = std::max(max_ncc, f.peak_ncc);
      std::printf("D%d -> R%d seeded at identity: %s, peak %.3f, second %.3f, ratio %.2f\n", d, r,
                  f.found ? "found" : f.reason.c_str(), f.peak_ncc, f.second_ncc, f.peak_ratio);
      EXPECT_FALSE(accepted) << "D" << d << " -> R" << r;
    }
  }
  std::printf(
      "%d of %d wrong seeds refused; highest ratio of a found peak %.2f, highest peak %.3f\n",
      refused, tried, max_ratio, max_ncc);
}

/// D and R cut from the stitched strips at the regions' boundaries, in a fresh folder.
std::string SecondSplit() {
  const fs::path dir = fs::temp_directory_path() / "uwbsar_real_second_split";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const cv::Mat dep =
      cv::imread(testing::SharedDataPath("real/seed_corridor/departing.png"), cv::IMREAD_GRAYSCALE);
  const cv::Mat ret =
      cv::imread(testing::SharedDataPath("real/seed_corridor/returning.png"), cv::IMREAD_GRAYSCALE);
  for (int i = 1; i <= 6; ++i) {
    const cv::Rect region((i - 1) * 200, 0, 400, dep.rows);
    cv::imwrite((dir / ("D" + std::to_string(i) + ".png")).string(), dep(region));
    cv::imwrite((dir / ("R" + std::to_string(i) + ".png")).string(), ret(region));
  }
  return dir.string();
}

TEST(RealCorridorRefinementTest, SecondSplitKeepsEveryAcceptedLoopTrueAndNoFalseLoop) {
  UWBSAR_NEED_SHARED_DATA("real/seed_corridor/returning.png");
  for (bool refine : {false, true}) {
    Config config;
    config.place_recognition.validation.refinement.enabled = refine;
    const ImageLoopStudy study = RunImageLoopStudy(SecondSplit(), 0.005, PaperDetectorPair(),
                                                   config, config.limits.max_map_image_pixels);
    int loops = 0, wrong = 0, refined = 0;
    for (const ImagePairResult& p : study.pairs) {
      const ImageMatch& m = p.match;
      if (m.validation.refinement_tried) {
        const DenseRefinement& f = m.validation.refinement;
        std::printf("  D%d -> R%d refined: %s (peak %.3f, second %.3f, ratio %.2f)\n", p.d, p.r,
                    m.accepted() ? "accepted" : m.validation.reason.c_str(), f.peak_ncc,
                    f.second_ncc, f.peak_ratio);
      }
      if (!m.accepted()) continue;
      refined += m.validation.refined;
      const bool right = std::hypot(m.transform.x_m - (p.d - p.r), m.transform.y_m) < 0.05 &&
                         std::abs(m.transform.yaw_deg) < 1.0;
      if (p.d == p.r && right) ++loops;
      if (!right || std::abs(p.d - p.r) > 1) ++wrong;
    }
    std::printf("second split, refinement %s: %d of 6 loops, %d false (%d accepted by it)\n",
                refine ? "on" : "off", loops, wrong, refined);
    EXPECT_EQ(wrong, 0);
    EXPECT_GE(loops, 5);
  }
}

}  // namespace
}  // namespace uwbsar
