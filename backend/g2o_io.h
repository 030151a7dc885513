// g2o pose-graph files (SE(2) subset): `VERTEX_SE2 id x y theta`,
// `EDGE_SE2 i j dx dy dtheta I11 I12 I13 I22 I23 I33` (measurement = pose j in
// the frame of i, upper triangle of the information row by row) and `FIX id...`.
// Blank lines and lines starting with '#' are ignored, except the comments `# uwbsar:wall` and
// `# uwbsar:marginal`: uwbsar writes them right before the EDGE_SE2 of a wall-profile edge
// (EdgeKind::kWall) or a removed node's folded edge (EdgeKind::kMarginal), so that its own reader
// restores the kind while other g2o tools see a plain edge. Every other line is checked; a bad one
// throws an InputError naming the file and line, or is skipped and reported when skip_bad_lines is
// set (the rest is still loaded).
#pragma once

#include <Eigen/Core>
#include <istream>
#include <map>
#include <string>
#include <vector>

#include "backend/pose_graph.h"
#include "core/limits_config.h"
#include "core/pose2.h"

namespace uwbsar {

struct G2oVertex {
  int id = 0;
  Pose2 T_world_node;
  int line = 0;
};

struct G2oEdge {
  int from_id = 0;
  int to_id = 0;
  Pose2 T_from_to;
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  int line = 0;
  bool wall = false;      ///< preceded by the `# uwbsar:wall` comment
  bool marginal = false;  ///< preceded by the `# uwbsar:marginal` comment
};

struct G2oGraph {
  std::vector<G2oVertex> vertices;  ///< in file order
  std::vector<G2oEdge> edges;       ///< in file order; all refer to known vertices
  std::vector<int> fixed_ids;
  std::vector<std::string> skipped;  ///< one message per skipped line (skip_bad_lines)
};

struct G2oReadOptions {
  bool skip_bad_lines = false;  ///< skip and report bad lines instead of throwing
  double max_file_mb = LimitsConfig{}.max_input_file_mb;  ///< ReadG2o: the largest file read
};

G2oGraph ParseG2o(std::istream& in, const std::string& source_name,
                  const G2oReadOptions& options = {});
/// Throws InputError when the file cannot be opened, is not a regular file or is larger than
/// options.max_file_mb (and on bad lines, see above).
G2oGraph ReadG2o(const std::string& path, const G2oReadOptions& options = {});

/// Edges marked `# uwbsar:wall` are wall edges, `# uwbsar:marginal` marginal ones; of the others,
/// edges between consecutive ids are odometry and all others loops (the g2o datasets' convention).
EdgeKind ClassifyG2oEdge(const G2oEdge& edge);

/// Adds the vertices (with their file poses as initial estimates), FIX lines and edges to
/// `graph`, in file order: edge k of the file becomes edge index (first index + k).
void LoadIntoPoseGraph(const G2oGraph& g2o, PoseGraph* graph);

/// g2o text of a pose graph (vertices by id, FIX lines, edges in order).
std::string G2oText(const std::map<int, Pose2>& poses, const std::vector<PoseGraphEdge>& edges,
                    const std::vector<int>& fixed_ids);
/// Writes the graph's current estimate and edges atomically (optionally without rejected loops).
void WriteG2o(const std::string& path, const PoseGraph& graph, bool drop_rejected_loops);

/// TUM trajectory (`t x y z qx qy qz qw`), one line per (stamp_s, pose), z = 0.
std::string TumText(const std::vector<std::pair<double, Pose2>>& trajectory);
void WriteTum(const std::string& path, const std::vector<std::pair<double, Pose2>>& trajectory);

}  // namespace uwbsar
