// Detected tiles out of core (slam/session/tile_store.h).
#include "slam/session/tile_store.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <thread>
#include <vector>

namespace uwbsar {
namespace {

cv::Mat RandomTile(int rows, int cols, int seed) {
  cv::Mat tile(rows, cols, CV_32FC1);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  rng.fill(tile, cv::RNG::UNIFORM, 0.0f, 1.0f);
  tile.rowRange(0, rows / 4).setTo(0.0f);  // unobserved pixels
  return tile;
}

double MaxDifference(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() ? cv::norm(a, b, cv::NORM_INF) : 1e9;
}

TEST(TileStoreTest, TilesReadBackExactlyWhenTheCacheHoldsNone) {
  TileStore store(/*cache_bytes=*/0);  // every Load reads the file
  std::vector<cv::Mat> tiles;
  std::vector<TileRef> refs;
  for (int i = 0; i < 5; ++i) {
    tiles.push_back(RandomTile(120 + i, 80, i));
    refs.push_back(store.Put(tiles.back()));
  }
  for (int i = 4; i >= 0; --i) {
    EXPECT_TRUE(refs[i].stored());
    EXPECT_EQ(MaxDifference(refs[i].Load(), tiles[i]), 0.0) << i;
  }
  EXPECT_GT(store.file_bytes(), 0u);
  EXPECT_EQ(store.live_bytes(), store.file_bytes());
  EXPECT_TRUE(store.Put(cv::Mat()).empty());
}

TEST(TileStoreTest, TheFileFollowsTheTilesKeptNotTheTilesEverStored) {
  TileStore store(1 << 20);
  std::vector<TileRef> kept;
  for (int i = 0; i < 10; ++i) kept.push_back(store.Put(RandomTile(100, 100, i)));
  const std::size_t ten = store.file_bytes();
  // A hundred more tiles, each retired (its last reference dropped) before the next.
  for (int i = 0; i < 100; ++i) {
    TileRef r = store.Put(RandomTile(100, 100, 100 + i));
    EXPECT_EQ(MaxDifference(r.Load(), RandomTile(100, 100, 100 + i)), 0.0);
  }
  EXPECT_LT(store.file_bytes(), ten + ten / 5);  // freed extents were reused
  for (int i = 0; i < 10; ++i)
    EXPECT_EQ(MaxDifference(kept[i].Load(), RandomTile(100, 100, i)), 0.0);
}

TEST(TileStoreTest, ReferencesOutliveTheStoreAndThreadsShareIt) {
  TileRef survivor;
  {
    TileStore store(4 * 100 * 100 * 4);  // four tiles decoded at most
    std::vector<TileRef> refs;
    for (int i = 0; i < 16; ++i) refs.push_back(store.Put(RandomTile(100, 100, i)));
    std::vector<std::thread> readers;
    std::vector<int> wrong(4, 0);
    for (int t = 0; t < 4; ++t) {
      readers.emplace_back([&, t] {
        for (int round = 0; round < 20; ++round) {
          for (int i = 0; i < 16; ++i) {
            const int k = (i * 5 + t + round) % 16;
            wrong[t] += MaxDifference(refs[k].Load(), RandomTile(100, 100, k)) != 0.0;
          }
        }
      });
    }
    for (std::thread& r : readers) r.join();
    for (int t = 0; t < 4; ++t) EXPECT_EQ(wrong[t], 0);
    survivor = refs[3];
  }
  EXPECT_EQ(MaxDifference(survivor.Load(), RandomTile(100, 100, 3)), 0.0);
  const TileRef in_memory(RandomTile(10, 10, 1));
  EXPECT_FALSE(in_memory.stored());
  EXPECT_EQ(MaxDifference(in_memory.Load(), RandomTile(10, 10, 1)), 0.0);
}

}  // namespace
}  // namespace uwbsar
