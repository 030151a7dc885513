#include "eval/compare/map_loading.h"

#include <gtest/gtest.h>

#include <fstream>

#include "test/shared_data.h"
#include "test_maps.h"

namespace uwbsar {
namespace {

int CountUnknown(const OccupancyGrid& g) {
  int n = 0;
  for (std::int8_t v : g.cells) n += v == OccupancyGrid::kUnknown;
  return n;
}

TEST(MapLoadingTest, SeedLabGrey205IsUnknownDespiteNav2FreeThreshold) {
  UWBSAR_NEED_SEED_LAB_MAP();
  // my_map.pgm: 14308 free (254), 10656 unknown (205), 1276 occupied (0); free_thresh 0.25.
  const OccupancyGrid literal = LoadMapForComparison(testing::SeedLabYaml(), false);
  const OccupancyGrid compared = LoadMapForComparison(testing::SeedLabYaml(), true);
  EXPECT_EQ(CountUnknown(literal), 0);
  EXPECT_EQ(CountUnknown(compared), 10656);
  int occupied = 0;
  for (int r = 0; r < compared.rows; ++r) {
    for (int c = 0; c < compared.cols; ++c) occupied += compared.IsOccupied(r, c);
  }
  EXPECT_EQ(occupied, 1276);
}

TEST(MapLoadingTest, OnlyTrinaryUnnegatedMapsAreReinterpreted) {
  const std::string dir = testing::FreshDir("loading");
  std::ofstream(dir + "/m.pgm", std::ios::binary) << "P5\n3 1\n255\n"
                                                  << std::string("\xcd\xfe\x00", 3);
  std::ofstream(dir + "/scale.yaml")
      << "image: m.pgm\nmode: scale\nresolution: 0.1\norigin: [0, 0, 0]\n";
  std::ofstream(dir + "/negated.yaml")
      << "image: m.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 1\n";
  std::ofstream(dir + "/trinary.yaml") << "image: m.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n";
  EXPECT_EQ(LoadMapForComparison(dir + "/trinary.yaml", true).At(0, 0), OccupancyGrid::kUnknown);
  EXPECT_EQ(LoadMapForComparison(dir + "/trinary.yaml", true).At(0, 1), OccupancyGrid::kFree);
  EXPECT_NE(LoadMapForComparison(dir + "/scale.yaml", true).At(0, 0), OccupancyGrid::kUnknown);
  EXPECT_NE(LoadMapForComparison(dir + "/negated.yaml", true).At(0, 0), OccupancyGrid::kUnknown);
}

// The grey-205 rule applies to the normalised value: the same map written in 16 bits or
// with another maxval has the same unknown cells (it only applied to 8 bit before).
TEST(MapLoadingTest, Grey205RuleIsTheSameInEightAndSixteenBits) {
  const std::string dir = testing::FreshDir("loading16");
  std::ofstream(dir + "/m8.pgm", std::ios::binary) << "P5\n3 1\n255\n"
                                                   << std::string("\xcd\xfe\x00", 3);
  // 205 * 257 = 52685 (0xcdcd), 254 * 257 = 65278 (0xfefe), big-endian as Netpbm.
  std::ofstream(dir + "/m16.pgm", std::ios::binary) << "P5\n3 1\n65535\n"
                                                    << std::string("\xcd\xcd\xfe\xfe\x00\x00", 6);
  std::ofstream(dir + "/m1000.pgm") << "P2\n3 1\n1000\n804 996 0\n";
  for (const char* name : {"m8", "m16", "m1000"}) {
    std::ofstream(dir + "/" + name + ".yaml")
        << "image: " << name << ".pgm\nresolution: 0.1\norigin: [0, 0, 0]\n";
    const OccupancyGrid g = LoadMapForComparison(dir + "/" + name + ".yaml", true);
    EXPECT_EQ(g.At(0, 0), OccupancyGrid::kUnknown) << name;
    EXPECT_EQ(g.At(0, 1), OccupancyGrid::kFree) << name;
    EXPECT_EQ(g.At(0, 2), OccupancyGrid::kOccupied) << name;
  }
}

}  // namespace
}  // namespace uwbsar
