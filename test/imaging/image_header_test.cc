// The declared size of an image is read from its header and checked
// against limits.max_map_image_pixels before anything decodes it.
#include "imaging/image_header.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "imaging/occupancy_grid.h"

namespace uwbsar {
namespace {

namespace fs = std::filesystem;

class ImageHeaderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("uwbsar_image_header_test_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  std::string Read(const std::string& path) const {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  void Write(const std::string& path, const std::string& bytes) const {
    std::ofstream(path, std::ios::binary) << bytes;
  }
  fs::path dir_;
};

TEST_F(ImageHeaderTest, SizeOfEveryMapFormatIsReadWithoutDecoding) {
  const cv::Mat image(37, 53, CV_8UC1, cv::Scalar(254));
  for (const char* ext : {".png", ".pgm", ".bmp", ".jpg", ".tif"}) {
    const std::string path = Path(std::string("m") + ext);
    ASSERT_TRUE(cv::imwrite(path, image)) << ext;
    const ImageHeader h = ReadImageHeader(path);
    EXPECT_EQ(h.width, 53) << ext << " " << h.format;
    EXPECT_EQ(h.height, 37) << ext << " " << h.format;
    EXPECT_DOUBLE_EQ(h.pixels, 53.0 * 37.0) << ext;
  }
  // Multi-page TIFF: every page counts.
  const std::vector<cv::Mat> pages = {cv::Mat(10, 20, CV_32FC1, 0.0f), cv::Mat(10, 20, CV_32FC1)};
  ASSERT_TRUE(cv::imwritemulti(Path("two.tif"), pages));
  EXPECT_DOUBLE_EQ(ReadImageHeader(Path("two.tif")).pixels, 400.0);
  // PNM with a comment in the header, as map_server writes.
  Write(Path("c.pgm"), "P5\n# CREATOR: map_saver\n640 480\n255\n");
  EXPECT_EQ(ReadImageHeader(Path("c.pgm")).width, 640);
}

TEST_F(ImageHeaderTest, UnknownFormatOrCutHeaderIsAnErrorNamingTheFile) {
  Write(Path("x.img"), "GIF89a......");
  Write(Path("cut.png"), "\x89PNG\r\n\x1a\n\0\0");
  for (const char* name : {"x.img", "cut.png"}) {
    try {
      ReadImageHeader(Path(name));
      ADD_FAILURE() << name;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

TEST_F(ImageHeaderTest, MapImageDeclaringMorePixelsThanTheBudgetIsRefusedBeforeDecoding) {
  // A small real PNG whose IHDR is patched to declare 20000 x 20000 pixels: decoding it
  // would allocate 400 MB (and OpenCV's buffers several GB more).
  ASSERT_TRUE(cv::imwrite(Path("small.png"), cv::Mat(8, 8, CV_8UC1, cv::Scalar(254))));
  std::string png = Read(Path("small.png"));
  const char size[8] = {0, 0, 0x4e, 0x20, 0, 0, 0x4e, 0x20};  // 20000, big-endian
  png.replace(16, 8, size, 8);
  Write(Path("bomb.png"), png);
  Write(Path("bomb.yaml"), "image: bomb.png\nresolution: 0.05\norigin: [0, 0, 0]\n");
  try {
    LoadOccupancyGrid(Path("bomb.yaml"));
    FAIL() << "the bomb was decoded";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("bomb.png"), std::string::npos) << msg;
    EXPECT_NE(msg.find("20000 x 20000"), std::string::npos) << msg;
    EXPECT_NE(msg.find("limits.max_map_image_pixels"), std::string::npos) << msg;
  }
  // The budget is the caller's: a small one refuses the real 8 x 8 image too.
  Write(Path("small.yaml"), "image: small.png\nresolution: 0.05\norigin: [0, 0, 0]\n");
  EXPECT_EQ(LoadOccupancyGrid(Path("small.yaml")).cols, 8);
  EXPECT_THROW(LoadOccupancyGrid(Path("small.yaml"), 63.0), InputError);
}

}  // namespace
}  // namespace uwbsar
