#include "backend/g2o_io.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <unordered_map>
#include <utility>

#include "backend/se2_edge_cost.h"
#include "core/bounded_file.h"
#include "core/errors.h"
#include "imaging/image_io.h"

namespace uwbsar {
namespace {

/// The comment that marks the next EDGE_SE2 as a wall edge (see g2o_io.h).
constexpr const char* kWallMarker = "uwbsar:wall";
constexpr const char* kMarginalMarker = "uwbsar:marginal";

/// A rejected line; caught per line so that skip_bad_lines can go on.
struct LineError {
  std::string message;
};

std::vector<std::string> Tokens(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  std::string token;
  while (in >> token) out.push_back(token);
  return out;
}

int ParseInt(const std::string& token, const char* field) {
  int value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size()) {
    throw LineError{std::string("field '") + field + "' is not an integer: '" + token + "'"};
  }
  return value;
}

double ParseFinite(const std::string& token, const char* field) {
  double value = 0.0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size()) {
    throw LineError{std::string("field '") + field + "' is not a number: '" + token + "'"};
  }
  if (!std::isfinite(value)) {
    throw LineError{std::string("field '") + field + "' is not finite: '" + token + "'"};
  }
  return value;
}

void ExpectCount(const std::vector<std::string>& t, std::size_t n, const char* what) {
  if (t.size() != n) {
    throw LineError{std::string(what) + " needs " + std::to_string(n - 1) + " values, found " +
                    std::to_string(t.size() - 1)};
  }
}

G2oVertex ParseVertex(const std::vector<std::string>& t) {
  ExpectCount(t, 5, "VERTEX_SE2");
  G2oVertex v;
  v.id = ParseInt(t[1], "id");
  v.T_world_node = {ParseFinite(t[2], "x"), ParseFinite(t[3], "y"), ParseFinite(t[4], "theta")};
  return v;
}

G2oEdge ParseEdge(const std::vector<std::string>& t) {
  ExpectCount(t, 12, "EDGE_SE2");
  static const char* kInfo[6] = {"I11", "I12", "I13", "I22", "I23", "I33"};
  G2oEdge e;
  e.from_id = ParseInt(t[1], "from id");
  e.to_id = ParseInt(t[2], "to id");
  e.T_from_to = {ParseFinite(t[3], "dx"), ParseFinite(t[4], "dy"), ParseFinite(t[5], "dtheta")};
  double u[6];
  for (int k = 0; k < 6; ++k) u[k] = ParseFinite(t[static_cast<std::size_t>(6 + k)], kInfo[k]);
  e.information << u[0], u[1], u[2],  //
      u[1], u[3], u[4],               //
      u[2], u[4], u[5];
  if (e.from_id == e.to_id) throw LineError{"edge joins vertex " + t[1] + " to itself"};
  if (!SqrtInformation(e.information)) {
    throw LineError{"information matrix is not positive definite"};
  }
  return e;
}

std::string Fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.15g", v);
  return buf;
}

}  // namespace

G2oGraph ParseG2o(std::istream& in, const std::string& source, const G2oReadOptions& options) {
  G2oGraph g;
  std::unordered_map<int, int> vertex_line;
  std::unordered_map<int, int> fixed_line;
  std::string line;
  int line_no = 0;
  auto fail = [&](int at, const std::string& message) {
    const std::string full = source + ":" + std::to_string(at) + ": " + message;
    if (!options.skip_bad_lines) throw InputError(full);
    g.skipped.push_back(full);
  };
  bool wall_next = false;      // the previous line was `# uwbsar:wall`
  bool marginal_next = false;  // ... `# uwbsar:marginal`
  while (std::getline(in, line)) {
    ++line_no;
    const std::vector<std::string> t = Tokens(line);
    if (t.empty()) continue;
    if (t[0][0] == '#') {
      wall_next = t.size() == 2 && t[0] == "#" && t[1] == kWallMarker;
      marginal_next = t.size() == 2 && t[0] == "#" && t[1] == kMarginalMarker;
      continue;
    }
    const bool wall = std::exchange(wall_next, false);
    const bool marginal = std::exchange(marginal_next, false);
    try {
      if (t[0] == "VERTEX_SE2") {
        G2oVertex v = ParseVertex(t);
        if (vertex_line.count(v.id)) {
          throw LineError{"vertex " + std::to_string(v.id) + " already defined on line " +
                          std::to_string(vertex_line[v.id])};
        }
        v.line = line_no;
        vertex_line[v.id] = line_no;
        g.vertices.push_back(v);
      } else if (t[0] == "EDGE_SE2") {
        G2oEdge e = ParseEdge(t);
        e.line = line_no;
        e.wall = wall;
        e.marginal = marginal;
        g.edges.push_back(e);
      } else if (t[0] == "FIX") {
        if (t.size() < 2) throw LineError{"FIX needs at least one vertex id"};
        for (std::size_t k = 1; k < t.size(); ++k) {
          const int id = ParseInt(t[k], "id");
          if (fixed_line.emplace(id, line_no).second) g.fixed_ids.push_back(id);
        }
      } else {
        throw LineError{"unsupported record '" + t[0] + "' (expected VERTEX_SE2, EDGE_SE2 or FIX)"};
      }
    } catch (const LineError& e) {
      fail(line_no, e.message);
    }
  }
  // References are checked once the whole file is read (vertices may follow edges).
  std::vector<G2oEdge> edges;
  edges.reserve(g.edges.size());
  for (const G2oEdge& e : g.edges) {
    if (!vertex_line.count(e.from_id) || !vertex_line.count(e.to_id)) {
      const int missing = vertex_line.count(e.from_id) ? e.to_id : e.from_id;
      fail(e.line, "edge refers to unknown vertex " + std::to_string(missing));
    } else {
      edges.push_back(e);
    }
  }
  g.edges = std::move(edges);
  std::vector<int> fixed_ids;
  for (const int id : g.fixed_ids) {
    if (!vertex_line.count(id)) {
      fail(fixed_line[id], "FIX refers to unknown vertex " + std::to_string(id));
    } else {
      fixed_ids.push_back(id);
    }
  }
  g.fixed_ids = std::move(fixed_ids);
  return g;
}

G2oGraph ReadG2o(const std::string& path, const G2oReadOptions& options) {
  std::ifstream in = OpenTextInput(path, "g2o", options.max_file_mb);
  return ParseG2o(in, path, options);
}

EdgeKind ClassifyG2oEdge(const G2oEdge& edge) {
  if (edge.wall) return EdgeKind::kWall;
  if (edge.marginal) return EdgeKind::kMarginal;
  return std::abs(static_cast<long>(edge.to_id) - edge.from_id) == 1 ? EdgeKind::kOdometry
                                                                     : EdgeKind::kLoop;
}

void LoadIntoPoseGraph(const G2oGraph& g2o, PoseGraph* graph) {
  for (const G2oVertex& v : g2o.vertices) graph->AddNode(v.id, v.T_world_node, false);
  for (const int id : g2o.fixed_ids) graph->FixNode(id);
  for (const G2oEdge& e : g2o.edges) {
    PoseGraphEdge edge;
    edge.from_id = e.from_id;
    edge.to_id = e.to_id;
    edge.T_from_to = e.T_from_to;
    edge.information = e.information;
    edge.kind = ClassifyG2oEdge(e);
    graph->AddEdge(edge);
  }
}

std::string G2oText(const std::map<int, Pose2>& poses, const std::vector<PoseGraphEdge>& edges,
                    const std::vector<int>& fixed_ids) {
  std::ostringstream out;
  for (const auto& [id, p] : poses) {
    out << "VERTEX_SE2 " << id << ' ' << Fmt(p.x_m) << ' ' << Fmt(p.y_m) << ' ' << Fmt(p.yaw_rad)
        << '\n';
  }
  for (const int id : fixed_ids) out << "FIX " << id << '\n';
  for (const PoseGraphEdge& e : edges) {
    const Eigen::Matrix3d& I = e.information;
    if (e.kind == EdgeKind::kWall) out << "# " << kWallMarker << '\n';
    if (e.kind == EdgeKind::kMarginal) out << "# " << kMarginalMarker << '\n';
    out << "EDGE_SE2 " << e.from_id << ' ' << e.to_id << ' ' << Fmt(e.T_from_to.x_m) << ' '
        << Fmt(e.T_from_to.y_m) << ' ' << Fmt(e.T_from_to.yaw_rad) << ' ' << Fmt(I(0, 0)) << ' '
        << Fmt(I(0, 1)) << ' ' << Fmt(I(0, 2)) << ' ' << Fmt(I(1, 1)) << ' ' << Fmt(I(1, 2)) << ' '
        << Fmt(I(2, 2)) << '\n';
  }
  return out.str();
}

void WriteG2o(const std::string& path, const PoseGraph& graph, bool drop_rejected_loops) {
  std::vector<PoseGraphEdge> edges = graph.Edges();
  if (drop_rejected_loops) {
    const std::vector<EdgeReport> reports = graph.EdgeReports();
    std::vector<PoseGraphEdge> kept;
    for (std::size_t i = 0; i < edges.size(); ++i) {
      if (!reports[i].rejected) kept.push_back(edges[i]);
    }
    edges = std::move(kept);
  }
  WriteTextAtomic(path, G2oText(graph.GetPoses(), edges, graph.FixedNodes()));
}

std::string TumText(const std::vector<std::pair<double, Pose2>>& trajectory) {
  std::ostringstream out;
  for (const auto& [t, p] : trajectory) {
    out << Fmt(t) << ' ' << Fmt(p.x_m) << ' ' << Fmt(p.y_m) << " 0 0 0 "
        << Fmt(std::sin(0.5 * p.yaw_rad)) << ' ' << Fmt(std::cos(0.5 * p.yaw_rad)) << '\n';
  }
  return out.str();
}

void WriteTum(const std::string& path, const std::vector<std::pair<double, Pose2>>& trajectory) {
  WriteTextAtomic(path, TumText(trajectory));
}

}  // namespace uwbsar
