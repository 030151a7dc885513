// slam.place_views.*: how many views of one place the map keeps (slam/session/place_views.h).
#pragma once

#include <string>

namespace uwbsar {

/// slam.place_views.*
struct PlaceViewsConfig {
  int max_per_place = 1;           ///< views kept of one place; 0 keeps every keyframe
  double radius_m = 1.0;           ///< anchors this close are one place ...
  double heading_deg = 45.0;       ///< ... seen with the robot's heading this close
  double min_separation_m = 10.0;  ///< views of one run at least this much path apart (a pass
                                   ///< revisits nothing of its own)

  template <class V>
  void Visit(V& v) {
    v("max_per_place", max_per_place);
    v("radius_m", radius_m);
    v("heading_deg", heading_deg);
    v("min_separation_m", min_separation_m);
  }
};

}  // namespace uwbsar
