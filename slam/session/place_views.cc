#include "slam/session/place_views.h"

#include <algorithm>
#include <cmath>

namespace uwbsar {

std::vector<const PlaceView*> ViewsOfPlace(const std::vector<PlaceView>& kept,
                                           const PlaceView& query, const PlaceViewsConfig& config) {
  const double heading_rad = config.heading_deg * M_PI / 180.0;
  std::vector<const PlaceView*> out;
  for (const PlaceView& v : kept) {
    if (v.id == query.id) continue;
    if (std::hypot(v.anchor_world.x_m - query.anchor_world.x_m,
                   v.anchor_world.y_m - query.anchor_world.y_m) > config.radius_m)
      continue;
    if (std::abs(NormalizeAngle(v.robot_heading_rad - query.robot_heading_rad)) > heading_rad)
      continue;
    if (v.trajectory == query.trajectory &&
        std::abs(v.path_mid_m - query.path_mid_m) < config.min_separation_m)
      continue;
    out.push_back(&v);
  }
  std::sort(out.begin(), out.end(),
            [](const PlaceView* a, const PlaceView* b) { return a->stamp < b->stamp; });
  return out;
}

std::optional<int> KeyframeToRetire(const std::vector<PlaceView>& kept, const PlaceView& query,
                                    const PlaceViewsConfig& config) {
  if (config.max_per_place <= 0) return std::nullopt;
  const std::vector<const PlaceView*> views = ViewsOfPlace(kept, query, config);
  if (static_cast<int>(views.size()) + 1 <= config.max_per_place) return std::nullopt;
  for (const PlaceView* v : views) {
    if (v->retirable && v->stamp < query.stamp) return v->id;
  }
  return std::nullopt;
}

std::set<int> TiedByAcceptedLoops(const std::vector<EdgeReport>& reports) {
  std::set<int> tied;
  for (const EdgeReport& r : reports) {
    if (r.kind != EdgeKind::kLoop || r.rejected) continue;
    tied.insert(r.from_id);
    tied.insert(r.to_id);
  }
  return tied;
}

void RetireRevisitedViews(std::vector<PlaceView>* views, const std::vector<int>& queries,
                          const std::set<int>& tied, const PlaceViewsConfig& config,
                          const std::function<bool(int)>& retire) {
  const auto by_id = [views](int id) {
    return std::find_if(views->begin(), views->end(),
                        [id](const PlaceView& v) { return v.id == id; });
  };
  for (const int id : queries) {
    if (!tied.count(id)) continue;
    const auto query = by_id(id);
    if (query == views->end()) continue;  // retired by a newer keyframe already
    const std::optional<int> victim = KeyframeToRetire(*views, *query, config);
    if (victim && retire(*victim)) views->erase(by_id(*victim));
  }
}

}  // namespace uwbsar
