#include "backend/g2o_io.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/errors.h"

namespace uwbsar {
namespace {

const char* kGood =
    "# a comment\n"
    "VERTEX_SE2 0 0 0 0\n"
    "VERTEX_SE2 1 1 0 0\n"
    "VERTEX_SE2 2 2 0.1 0.05\n"
    "\n"
    "EDGE_SE2 0 1 1 0 0 10 1 0 20 0 30\n"
    "EDGE_SE2 1 2 1 0 0 10 0 0 10 0 10\n"
    "EDGE_SE2 0 2 2 0 0 10 0 0 10 0 10\n"
    "FIX 0\n";

G2oGraph Parse(const std::string& text, bool skip = false) {
  std::istringstream in(text);
  G2oReadOptions options;
  options.skip_bad_lines = skip;
  return ParseG2o(in, "t.g2o", options);
}

/// The message of the InputError that parsing `text` throws ("" if none).
std::string ErrorOf(const std::string& text) {
  try {
    Parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(G2oIoTest, ParsesVerticesEdgesWithUpperTriangularInformationAndFix) {
  const G2oGraph g = Parse(kGood);
  ASSERT_EQ(g.vertices.size(), 3u);
  ASSERT_EQ(g.edges.size(), 3u);
  EXPECT_DOUBLE_EQ(g.vertices[2].T_world_node.yaw_rad, 0.05);
  const Eigen::Matrix3d& I = g.edges[0].information;
  EXPECT_DOUBLE_EQ(I(0, 0), 10);
  EXPECT_DOUBLE_EQ(I(0, 1), 1);
  EXPECT_DOUBLE_EQ(I(1, 0), 1);
  EXPECT_DOUBLE_EQ(I(1, 1), 20);
  EXPECT_DOUBLE_EQ(I(2, 2), 30);
  EXPECT_EQ(g.edges[0].line, 6);
  EXPECT_EQ(g.fixed_ids, std::vector<int>{0});
  EXPECT_EQ(ClassifyG2oEdge(g.edges[0]), EdgeKind::kOdometry);
  EXPECT_EQ(ClassifyG2oEdge(g.edges[2]), EdgeKind::kLoop);
}

TEST(G2oIoTest, MalformedLinesAreReportedWithTheirLineNumber) {
  EXPECT_NE(ErrorOf("VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 zero 0\n").find("t.g2o:2:"),
            std::string::npos);
  EXPECT_NE(ErrorOf("VERTEX_SE2 0 0 0\n").find("t.g2o:1: VERTEX_SE2 needs 4 values"),
            std::string::npos);
  EXPECT_NE(ErrorOf("VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 0 0 0\nEDGE_SE2 0 1 1 0 0 1 0 0 1 0\n")
                .find("t.g2o:3:"),
            std::string::npos);
  EXPECT_NE(ErrorOf("VERTEX_SE2 0 0 0 0\nVERTEX_XY 1 0 0\n").find("t.g2o:2: unsupported record"),
            std::string::npos);
  EXPECT_NE(ErrorOf("VERTEX_SE2 0 0 0 0\nVERTEX_SE2 0 1 0 0\n").find("already defined on line 1"),
            std::string::npos);
}

TEST(G2oIoTest, EdgesToUnknownVerticesAreErrors) {
  const std::string msg = ErrorOf("VERTEX_SE2 0 0 0 0\nEDGE_SE2 0 7 1 0 0 1 0 0 1 0 1\n");
  EXPECT_NE(msg.find("t.g2o:2: edge refers to unknown vertex 7"), std::string::npos) << msg;
  EXPECT_NE(ErrorOf("VERTEX_SE2 0 0 0 0\nFIX 3\n").find("t.g2o:2: FIX refers to unknown vertex 3"),
            std::string::npos);
}

TEST(G2oIoTest, NonPositiveDefiniteInformationIsAnError) {
  const std::string head = "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\n";
  EXPECT_NE(ErrorOf(head + "EDGE_SE2 0 1 1 0 0 1 0 0 -1 0 1\n").find("t.g2o:3: information"),
            std::string::npos);
  EXPECT_NE(ErrorOf(head + "EDGE_SE2 0 1 1 0 0 1 2 0 1 0 1\n").find("t.g2o:3: information"),
            std::string::npos);
  EXPECT_NE(ErrorOf(head + "EDGE_SE2 0 1 1 0 0 0 0 0 0 0 0\n").find("t.g2o:3: information"),
            std::string::npos);
}

TEST(G2oIoTest, NanAndInfinityAreErrors) {
  const std::string head = "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\n";
  EXPECT_NE(ErrorOf(head + "EDGE_SE2 0 1 nan 0 0 1 0 0 1 0 1\n")
                .find("t.g2o:3: field 'dx' is not finite"),
            std::string::npos);
  EXPECT_NE(ErrorOf("VERTEX_SE2 0 0 inf 0\n").find("t.g2o:1: field 'y' is not finite"),
            std::string::npos);
  EXPECT_NE(ErrorOf(head + "EDGE_SE2 0 1 1 0 0 1 0 0 1 0 NaN\n").find("'I33'"), std::string::npos);
}

TEST(G2oIoTest, SkipModeKeepsTheRestOfTheGraphAndReportsEachBadLine) {
  const std::string text = std::string(kGood) +
                           "EDGE_SE2 0 9 1 0 0 1 0 0 1 0 1\n"
                           "EDGE_SE2 1 2 nan 0 0 1 0 0 1 0 1\n"
                           "EDGE_SE2 1 2 1 0 0 1 0 0 -1 0 1\n"
                           "garbage line\n";
  const G2oGraph g = Parse(text, true);
  EXPECT_EQ(g.vertices.size(), 3u);
  EXPECT_EQ(g.edges.size(), 3u);
  ASSERT_EQ(g.skipped.size(), 4u);
  EXPECT_NE(g.skipped[0].find("t.g2o:11:"), std::string::npos) << g.skipped[0];
  EXPECT_NE(g.skipped[3].find("t.g2o:10: edge refers to unknown vertex 9"), std::string::npos)
      << g.skipped[3];
}

TEST(G2oIoTest, MissingFileIsAnInputError) {
  EXPECT_THROW(ReadG2o("/nonexistent/graph.g2o"), InputError);
}

TEST(G2oIoTest, WrittenGraphReadsBackTheSame) {
  const G2oGraph g = Parse(kGood);
  PoseGraph graph;
  LoadIntoPoseGraph(g, &graph);
  const std::string path =
      (std::filesystem::temp_directory_path() / "uwbsar_g2o_roundtrip.g2o").string();
  WriteG2o(path, graph, false);
  const G2oGraph back = ReadG2o(path);
  std::remove(path.c_str());
  ASSERT_EQ(back.vertices.size(), g.vertices.size());
  ASSERT_EQ(back.edges.size(), g.edges.size());
  EXPECT_EQ(back.fixed_ids, g.fixed_ids);
  for (std::size_t i = 0; i < g.edges.size(); ++i) {
    EXPECT_EQ(back.edges[i].from_id, g.edges[i].from_id);
    EXPECT_DOUBLE_EQ(back.edges[i].T_from_to.x_m, g.edges[i].T_from_to.x_m);
    EXPECT_TRUE(back.edges[i].information.isApprox(g.edges[i].information));
  }
  EXPECT_DOUBLE_EQ(back.vertices[2].T_world_node.y_m, 0.1);
}

TEST(G2oIoTest, WallEdgesReadBackAsWallEdges) {
  // uwbsar's graph.g2o marks a wall edge with a comment: other g2o tools see a plain edge,
  // uwbsar's reader (uwbsar optimize) keeps it a wall edge instead of taking it for a loop.
  PoseGraph graph;
  for (int id = 0; id < 3; ++id) graph.AddNode(id, Pose2{double(id), 0.0, 0.0}, false);
  graph.AddOdometryEdge(0, 1, Pose2{1.0, 0.0, 0.0});
  graph.AddOdometryEdge(1, 2, Pose2{1.0, 0.0, 0.0});
  PoseGraphEdge wall;
  wall.from_id = 0;
  wall.to_id = 2;
  wall.T_from_to = Pose2{2.0, 0.01, 0.0};
  wall.information = Eigen::Vector3d(0.025, 2500.0, 0.1).asDiagonal();
  wall.kind = EdgeKind::kWall;
  graph.AddEdge(wall);
  const std::string text = G2oText(graph.GetPoses(), graph.Edges(), {});
  EXPECT_NE(text.find("# uwbsar:wall\nEDGE_SE2 0 2 "), std::string::npos) << text;
  const G2oGraph back = Parse(text);
  ASSERT_EQ(back.edges.size(), 3u);
  EXPECT_EQ(ClassifyG2oEdge(back.edges[0]), EdgeKind::kOdometry);
  EXPECT_EQ(ClassifyG2oEdge(back.edges[1]), EdgeKind::kOdometry);
  EXPECT_EQ(ClassifyG2oEdge(back.edges[2]), EdgeKind::kWall);
  EXPECT_TRUE(back.edges[2].information.isApprox(wall.information));

  // The marker applies to the very next record only; a plain edge between other ids is a loop.
  const G2oGraph g = Parse(
      "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\nVERTEX_SE2 2 2 0 0\n"
      "# uwbsar:wall\nVERTEX_SE2 3 3 0 0\nEDGE_SE2 0 2 2 0 0 10 0 0 10 0 10\n"
      "# uwbsar:wall extra\nEDGE_SE2 1 3 2 0 0 10 0 0 10 0 10\n");
  ASSERT_EQ(g.edges.size(), 2u);
  EXPECT_EQ(ClassifyG2oEdge(g.edges[0]), EdgeKind::kLoop);
  EXPECT_EQ(ClassifyG2oEdge(g.edges[1]), EdgeKind::kLoop);
}

TEST(G2oIoTest, TumLinesCarryTheYawAsAQuaternionAboutZ) {
  const std::string text = TumText({{1.5, Pose2{1, 2, M_PI / 2}}});
  double t, x, y, z, qx, qy, qz, qw;
  ASSERT_EQ(std::sscanf(text.c_str(), "%lf %lf %lf %lf %lf %lf %lf %lf", &t, &x, &y, &z, &qx, &qy,
                        &qz, &qw),
            8);
  EXPECT_DOUBLE_EQ(t, 1.5);
  EXPECT_DOUBLE_EQ(y, 2);
  EXPECT_DOUBLE_EQ(z, 0);
  EXPECT_NEAR(qz, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(qw, std::sqrt(0.5), 1e-12);
}

}  // namespace
}  // namespace uwbsar
