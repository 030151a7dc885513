// Which keyframe a revisit retires (slam/session/place_views.h).
#include "slam/session/place_views.h"

#include <gtest/gtest.h>

#include <cmath>

namespace uwbsar {
namespace {

PlaceView View(int id, double x, double y, double heading_deg, double path_mid_m,
               int trajectory = 0) {
  PlaceView v;
  v.id = id;
  v.trajectory = trajectory;
  v.anchor_world = {x, y};
  v.robot_heading_rad = heading_deg * M_PI / 180.0;
  v.path_mid_m = path_mid_m;
  v.stamp = id;  // ids in time order
  return v;
}

TEST(PlaceViewsTest, ARevisitRetiresTheOldestViewBeyondTheLimit) {
  PlaceViewsConfig config;
  config.max_per_place = 2;
  // Lap 1 and lap 2 passed here heading east; lap 3 comes.
  const std::vector<PlaceView> kept = {View(1, 0.0, 0.0, 0.0, 1.0), View(40, 0.3, 0.1, 5.0, 35.0),
                                       View(80, 0.1, -0.2, -3.0, 69.0)};
  EXPECT_EQ(KeyframeToRetire(kept, kept[2], config), 1);
  config.max_per_place = 3;
  EXPECT_EQ(KeyframeToRetire(kept, kept[2], config), std::nullopt);
  config.max_per_place = 1;
  EXPECT_EQ(ViewsOfPlace(kept, kept[2], config).size(), 2u);
  EXPECT_EQ(KeyframeToRetire(kept, kept[2], config), 1);  // one at a time, oldest first
  config.max_per_place = 0;                               // keep everything
  EXPECT_EQ(KeyframeToRetire(kept, kept[2], config), std::nullopt);
}

TEST(PlaceViewsTest, OnlyRevisitsOfTheSamePlaceAndHeadingCount) {
  PlaceViewsConfig config;
  config.max_per_place = 1;
  const PlaceView query = View(100, 0.0, 0.0, 0.0, 200.0);
  EXPECT_EQ(KeyframeToRetire({View(1, 1.5, 0.0, 0.0, 1.0), query}, query, config),
            std::nullopt);  // too far
  EXPECT_EQ(KeyframeToRetire({View(1, 0.5, 0.0, 180.0, 1.0), query}, query, config),
            std::nullopt);  // the other way along the corridor
  EXPECT_EQ(KeyframeToRetire({View(99, 0.5, 0.0, 0.0, 199.0), query}, query, config),
            std::nullopt);  // the same pass
  EXPECT_EQ(KeyframeToRetire({View(99, 0.5, 0.0, 0.0, 199.0, 1), query}, query, config),
            99);  // another run passing here is a revisit whatever its path
  EXPECT_EQ(KeyframeToRetire({View(1, 0.5, 0.0, 40.0, 1.0), query}, query, config), 1);
}

TEST(PlaceViewsTest, TheGaugeAndNewerViewsAreNeverRetired) {
  PlaceViewsConfig config;
  config.max_per_place = 1;
  PlaceView gauge = View(0, 0.0, 0.0, 0.0, 0.5);
  gauge.retirable = false;
  const PlaceView query = View(50, 0.2, 0.0, 0.0, 40.0);
  EXPECT_EQ(KeyframeToRetire({gauge, query}, query, config), std::nullopt);
  const PlaceView later = View(60, 0.2, 0.0, 0.0, 80.0);
  EXPECT_EQ(KeyframeToRetire({later, query}, query, config), std::nullopt);
}

}  // namespace
}  // namespace uwbsar
