#include "drivers/sim/route.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/bounded_file.h"

namespace uwbsar::sim {

std::vector<std::string> BuiltInRouteNames() { return {"depart-return", "loop"}; }

Route BuiltInRoute(const std::string& name, const SimRouteConfig& c) {
  const Pose2 start{c.start_x_m, c.start_y_m, c.start_yaw_deg * M_PI / 180.0};
  Route route;
  route.name = name;
  if (name == "depart-return") {
    route.waypoints = {start * Point2{0, 0}, start * Point2{c.depart_distance_m, 0},
                       start * Point2{0, 0}};
  } else if (name == "loop") {
    const double l = c.loop_length_m, w = c.loop_width_m;
    route.waypoints = {start * Point2{0, 0}, start * Point2{l, 0}, start * Point2{l, w},
                       start * Point2{0, w}, start * Point2{0, 0}};
  } else {
    throw InputError("unknown built-in route '" + name + "'");
  }
  return route;
}

Route ReadWaypointsFile(const std::string& path, double max_mb) {
  std::ifstream in = OpenTextInput(path, "waypoints", max_mb);
  Route route;
  route.name = std::filesystem::path(path).stem().string();
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    const std::string where = path + ":" + std::to_string(line_no);
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    for (char& ch : line) {
      if (ch == ',') ch = ' ';
    }
    std::istringstream fields(line);
    std::string tokens[3];
    int n = 0;
    while (n < 3 && fields >> tokens[n]) ++n;
    if (n == 0) continue;
    if (n != 2) throw InputError(where + ": expected 'x_m y_m'");
    double xy[2];
    for (int k = 0; k < 2; ++k) {
      char* end = nullptr;
      xy[k] = std::strtod(tokens[k].c_str(), &end);
      if (end == tokens[k].c_str() || *end != '\0' || !std::isfinite(xy[k])) {
        throw InputError(where + ": field '" + (k == 0 ? "x_m" : "y_m") + "' is not a number: '" +
                         tokens[k] + "'");
      }
    }
    const Point2 p{xy[0], xy[1]};
    if (!route.waypoints.empty() &&
        std::hypot(p.x_m - route.waypoints.back().x_m, p.y_m - route.waypoints.back().y_m) < 1e-6) {
      continue;  // a repeated waypoint adds nothing
    }
    route.waypoints.push_back(p);
  }
  if (route.waypoints.size() < 2) {
    throw InputError(path + ": a route needs at least two distinct waypoints");
  }
  return route;
}

Route ResolveRoute(const std::string& spec, const SimRouteConfig& config, double max_mb) {
  for (const std::string& name : BuiltInRouteNames()) {
    if (spec == name) return BuiltInRoute(name, config);
  }
  std::error_code ec;
  if (!std::filesystem::exists(spec, ec)) {
    std::string names;
    for (const std::string& name : BuiltInRouteNames()) names += (names.empty() ? "" : ", ") + name;
    throw InputError("route '" + spec + "' is neither a built-in route (" + names +
                     ") nor a waypoints file");
  }
  return ReadWaypointsFile(spec, max_mb);  // a FIFO or a device is named as such
}

}  // namespace uwbsar::sim
