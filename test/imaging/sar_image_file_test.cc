// Reading SAR images from disk for `match`, `loops --images` and `compare`: pixel types, the
// grid YAML beside an image or naming it, and the one-line errors.
#include "imaging/sar_image_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <utility>

#include "core/errors.h"
#include "imaging/image_io.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;

class SarImageFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("uwbsar_sar_image_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    image_ = cv::Mat(40, 60, CV_8UC1, cv::Scalar(0));
    image_(cv::Rect(10, 5, 30, 20)).setTo(200);
    image_.at<std::uint8_t>(7, 12) = 90;
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string ErrorOf(const std::string& path) const {
    try {
      ReadSarImageFile(path, 0.005);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
  cv::Mat image_;
};

TEST_F(SarImageFileTest, EightAndSixteenBitImagesAreEnhancedInputAtTheGivenResolution) {
  cv::imwrite(Path("a.png"), image_);
  cv::Mat wide;
  image_.convertTo(wide, CV_16U, 257.0);
  cv::imwrite(Path("b.png"), wide);
  // A 16-bit PNG has no declared range: its own maximum (200 x 257) becomes 255.
  for (const auto& [name, bright] : {std::pair<const char*, int>{"a.png", 200}, {"b.png", 255}}) {
    const SarImageFile f = ReadSarImageFile(Path(name), 0.01);
    EXPECT_TRUE(f.enhanced);
    EXPECT_EQ(f.image.type(), CV_8UC1);
    EXPECT_EQ(f.image.at<std::uint8_t>(10, 20), bright) << name;
    EXPECT_DOUBLE_EQ(f.grid.resolution_m, 0.01);
    EXPECT_EQ(f.grid.cols, 60);
    EXPECT_EQ(cv::countNonZero(f.observed), 30 * 20);
    EXPECT_TRUE(f.grid_yaml.empty());
  }
}

TEST_F(SarImageFileTest, GridYamlBesideTheImageOrNamingItWins) {
  cv::imwrite(Path("strip.png"), image_);
  std::ofstream(Path("strip_grid.yaml")) << "x0_m: 1.5\ny0_m: 3.0\nresolution_m: 0.02\n";
  const SarImageFile beside = ReadSarImageFile(Path("strip.png"), 0.005);
  EXPECT_EQ(beside.grid_yaml, Path("strip_grid.yaml"));
  EXPECT_DOUBLE_EQ(beside.grid.resolution_m, 0.02);
  EXPECT_DOUBLE_EQ(beside.grid.x0_m, 1.5);
  EXPECT_DOUBLE_EQ(beside.grid.y0_m, 3.0);
  // A grid YAML naming its image relative to itself.
  fs::create_directories(dir_ / "meta");
  std::ofstream(Path("meta/g.yaml"))
      << "image: ../strip.png\nx0_m: 0\ny0_m: 0\nresolution_m: 0.005\nrows: 40\ncols: 60\n";
  const SarImageFile named = ReadSarImageFile(Path("meta/g.yaml"), 1.0);
  EXPECT_EQ(fs::canonical(named.path), fs::canonical(Path("strip.png")));
  EXPECT_DOUBLE_EQ(named.grid.resolution_m, 0.005);
}

TEST_F(SarImageFileTest, FloatTiffIsReadAsImagedWithItsGrid) {
  cv::Mat sar(40, 60, CV_32FC1, cv::Scalar(0.0f));
  sar(cv::Rect(5, 5, 10, 10)).setTo(-2.0f);
  sar.at<float>(20, 30) = 7.5f;
  WriteFloatTiff(Path("run_float.tif"), sar);
  std::ofstream(Path("run_grid.yaml"))
      << "x0_m: 0\ny0_m: 0\nresolution_m: 0.01\nrows: 40\ncols: 60\n";
  const SarImageFile f = ReadSarImageFile(Path("run_float.tif"), 0.005);
  EXPECT_FALSE(f.enhanced);
  EXPECT_EQ(f.image.type(), CV_32FC1);
  EXPECT_FLOAT_EQ(f.image.at<float>(20, 30), 7.5f);
  EXPECT_EQ(f.grid_yaml, Path("run_grid.yaml"));
  EXPECT_EQ(cv::countNonZero(f.observed), 101);
}

TEST_F(SarImageFileTest, BadInputIsOneLineNamingTheFile) {
  cv::imwrite(Path("uniform.png"), cv::Mat(10, 10, CV_8UC1, cv::Scalar(9)));
  cv::imwrite(Path("black.png"), cv::Mat(10, 10, CV_8UC1, cv::Scalar(0)));
  cv::imwrite(Path("colour.png"), cv::Mat(10, 10, CV_8UC3, cv::Scalar(1, 2, 3)));
  std::ofstream(Path("junk.png")) << "not an image";
  cv::imwrite(Path("sized.png"), image_);
  std::ofstream(Path("sized_grid.yaml"))
      << "x0_m: 0\ny0_m: 0\nresolution_m: 0.005\nrows: 41\ncols: 60\n";
  std::ofstream(Path("noimage.yaml")) << "x0_m: 0\ny0_m: 0\nresolution_m: 0.005\n";
  const std::pair<const char*, const char*> cases[] = {
      {"missing.png", "does not exist"}, {"uniform.png", "uniform"},
      {"black.png", "no measurement"},   {"colour.png", "unsupported SAR image"},
      {"junk.png", "junk.png"},          {"sized.png", "41"},
      {"noimage.yaml", "no 'image' key"}};
  for (const auto& [name, words] : cases) {
    const std::string error = ErrorOf(Path(name));
    EXPECT_NE(error.find(name), std::string::npos) << name << ": " << error;
    EXPECT_NE(error.find(words), std::string::npos) << name << ": " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
}

// A 10-bit sensor's PGM (maxval 1023) was scaled by 255/65535 into 0..4, a maxval-300 one was
// "uniform": a PGM's maxval is its full scale.
TEST_F(SarImageFileTest, SixteenBitPgmIsScaledByItsMaxval) {
  for (const int maxval : {1023, 300, 65535}) {
    const std::string path = Path("m" + std::to_string(maxval) + ".pgm");
    {
      std::ofstream out(path, std::ios::binary);
      out << "P5\n" << image_.cols << " " << image_.rows << "\n" << maxval << "\n";
      for (int r = 0; r < image_.rows; ++r) {
        for (int c = 0; c < image_.cols; ++c) {
          const int v = image_.at<std::uint8_t>(r, c) * maxval / 255;
          out.put(static_cast<char>(v >> 8));
          out.put(static_cast<char>(v & 0xff));
        }
      }
    }
    const SarImageFile f = ReadSarImageFile(path, 0.01);
    EXPECT_EQ(f.image.type(), CV_8UC1);
    EXPECT_NEAR(f.image.at<std::uint8_t>(10, 20), 200, 1) << maxval;
    EXPECT_NEAR(f.image.at<std::uint8_t>(7, 12), 90, 1) << maxval;
  }
}

// NaN pixels of a float image gave no keypoints without a word: they are not measured (0).
TEST_F(SarImageFileTest, NonFinitePixelsOfAFloatImageAreNotMeasured) {
  cv::Mat sar;
  image_.convertTo(sar, CV_32F);
  sar.at<float>(10, 20) = std::numeric_limits<float>::quiet_NaN();
  sar.at<float>(11, 20) = std::numeric_limits<float>::infinity();
  WriteFloatTiff(Path("nan.tif"), sar);
  const SarImageFile f = ReadSarImageFile(Path("nan.tif"), 0.01);
  EXPECT_EQ(f.image.at<float>(10, 20), 0.0f);
  EXPECT_EQ(f.image.at<float>(11, 20), 0.0f);
  EXPECT_EQ(f.image.at<float>(12, 20), 200.0f);
  EXPECT_EQ(cv::countNonZero(f.observed), 30 * 20 - 2);
  sar.setTo(std::numeric_limits<float>::quiet_NaN());
  WriteFloatTiff(Path("all_nan.tif"), sar);
  EXPECT_EQ(ErrorOf(Path("all_nan.tif")),
            Path("all_nan.tif") +
                ": SAR image holds no finite pixel (every value is NaN or "
                "infinite)");
}

}  // namespace
}  // namespace uwbsar
