// Line landmarks (backend/line_landmark.h, PoseGraph::AddLandmark / AddLineObservation): a
// straight wall that every keyframe along a corridor measures in its own frame. One line per
// wall holds the whole corridor straight, where the pairwise wall edges (wall_edge_test.cc) only
// tie keyframes 2-6 apart; a wrong observation is rejected by its chi2, and a removed node's
// observations leave with it.
#include "backend/line_landmark.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <vector>

#include "backend/pose_graph.h"
#include "core/errors.h"
#include "test/backend/calibration_routes.h"

namespace uwbsar {
namespace {

using testing::BuildOdometryChain;
using testing::DriveSteps;
using testing::GraphAte;
using testing::OdometryRun;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDriftRadPerM = 0.003;  // the simulator's wheel heading drift

TEST(LineLandmarkTest, ALineSeenFromAFrameGoesBackToTheWorldExactly) {
  const Pose2 T_world_frame{3.0, -2.0, 0.7};
  const Line2 world{2.1, 1.4};
  const Line2 seen = LineToFrame(T_world_frame, world);
  const Line2 back = LineToWorld(T_world_frame, seen);
  EXPECT_NEAR(back.normal_rad, world.normal_rad, 1e-12);
  EXPECT_NEAR(back.offset_m, world.offset_m, 1e-12);
  // A point of the world line is on the frame's line once moved into the frame.
  const double a = world.normal_rad;
  const Point2 p_world{world.offset_m * std::cos(a) - 5.0 * std::sin(a),
                       world.offset_m * std::sin(a) + 5.0 * std::cos(a)};
  const Pose2 p_frame = Between(T_world_frame, Pose2{p_world.x_m, p_world.y_m, 0.0});
  EXPECT_NEAR(std::cos(seen.normal_rad) * p_frame.x_m + std::sin(seen.normal_rad) * p_frame.y_m,
              seen.offset_m, 1e-12);
  // The same line with its normal turned over.
  const Line2 flipped = Facing({NormalizeAngle(a + kPi), -world.offset_m}, world);
  EXPECT_NEAR(flipped.normal_rad, world.normal_rad, 1e-12);
  EXPECT_NEAR(flipped.offset_m, world.offset_m, 1e-12);
}

TEST(LineLandmarkTest, TheResidualIsTheOffsetAtTheReferencePointAndTheAngleInSigmas) {
  const Pose2 T_world_node{1.0, 2.0, 0.3};
  const Line2 world{0.3 + kPi / 2, 5.0};  // a wall 1.2 m (or so) left of the node
  LineObservation o;
  o.line_node = LineToFrame(T_world_node, world);
  o.reference_node = {1.5, 0.0};
  o.offset_std_m = 0.02;
  o.normal_std_rad = 0.01;
  EXPECT_NEAR(LineObservationChi2(o, T_world_node, world), 0.0, 1e-18);
  // The landmark 2 cm further out: one sigma in offset.
  EXPECT_NEAR(LineObservationChi2(o, T_world_node, {world.normal_rad, world.offset_m + 0.02}), 1.0,
              1e-9);
  // Turned by 0.01 rad about the reference point (in the world): one sigma in angle, and no
  // offset error there.
  const Pose2 q = T_world_node * Pose2{o.reference_node.x_m, o.reference_node.y_m, 0.0};
  const double a = world.normal_rad + 0.01;
  const Line2 turned{a,
                     world.offset_m -
                         (std::cos(world.normal_rad) * q.x_m + std::sin(world.normal_rad) * q.y_m) +
                         std::cos(a) * q.x_m + std::sin(a) * q.y_m};
  EXPECT_NEAR(LineObservationChi2(o, T_world_node, turned), 1.0, 1e-9);
  // The angle residual wraps: a landmark block 2 pi further round is the same line.
  EXPECT_NEAR(LineObservationChi2(o, T_world_node, {world.normal_rad + 2 * kPi, world.offset_m}),
              0.0, 1e-12);
}

/// How far the graph's path bows: the largest distance of a node from the straight line fitted
/// through all of them (the gauge, a slightly turned corridor, does not count).
double Bow(const PoseGraph& g) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& [id, p] : g.GetPoses()) {
    n += 1, sx += p.x_m, sy += p.y_m, sxx += p.x_m * p.x_m, sxy += p.x_m * p.y_m;
  }
  const double b = (n * sxy - sx * sy) / (n * sxx - sx * sx), a = (sy - b * sx) / n;
  double worst_m = 0.0;
  for (const auto& [id, p] : g.GetPoses())
    worst_m = std::max(worst_m, std::abs(p.y_m - a - b * p.x_m) / std::hypot(1.0, b));
  return worst_m;
}

/// 40 m of straight corridor in 1 m steps (keyframes), driven with a heading drift.
OdometryRun Corridor() {
  return DriveSteps({0.0, kDriftRadPerM, 0.0}, std::vector<Pose2>(40, {1.0, 0.0, 0.0}));
}

/// Walls along the corridor: y = 1.0 (left) and y = -1.25 (right), one landmark each, seen by
/// every node with 1 cm and 0.3 deg of noise (fixed seed) at 1 m ahead; with `wrong_at` >= 0
/// that node sees the left wall 20 cm off. The landmarks start where node 0's view puts them.
std::vector<int> AddWalls(const OdometryRun& run, int wrong_at, PoseGraph* g) {
  std::mt19937 rng(7);
  std::normal_distribution<double> offset_noise(0.0, 0.01), angle_noise(0.0, 0.005);
  const Line2 walls[2] = {{kPi / 2, 1.0}, {-kPi / 2, 1.25}};
  for (int w = 0; w < 2; ++w)
    g->AddLandmark(w, LineToWorld(Pose2{}, LineToFrame(run.truth[0], walls[w])));
  std::vector<int> indices;
  for (int k = 0; k < static_cast<int>(run.truth.size()); ++k) {
    for (int w = 0; w < 2; ++w) {
      LineObservation o;
      o.landmark_id = w;
      o.node_id = k;
      o.line_node = LineToFrame(run.truth[k], walls[w]);
      o.line_node.normal_rad += angle_noise(rng);
      o.line_node.offset_m += offset_noise(rng) + (k == wrong_at && w == 0 ? 0.2 : 0.0);
      o.reference_node = {1.0, 0.0};
      o.offset_std_m = 0.02;
      o.normal_std_rad = 1.0 * kPi / 180;
      indices.push_back(g->AddLineObservation(o));
    }
  }
  return indices;
}

TEST(LineLandmarkTest, AStraightCorridorIsStraightenedByTwoWalls) {
  const OdometryRun run = Corridor();
  PoseGraph odometry_only;
  BuildOdometryChain(run, &odometry_only);
  odometry_only.Optimize();
  PoseGraph g;
  BuildOdometryChain(run, &g);
  AddWalls(run, -1, &g);
  const OptimizeResult r = g.Optimize();
  EXPECT_TRUE(r.converged) << r.termination;
  EXPECT_EQ(r.num_loops, 0);
  const double ate_odometry = GraphAte(odometry_only, run.truth), ate = GraphAte(g, run.truth);
  std::printf("landmarks: ATE %.2f cm (odometry alone %.2f cm), bow %.2f cm (odometry %.2f cm)\n",
              ate * 100, ate_odometry * 100, Bow(g) * 100, Bow(odometry_only) * 100);
  EXPECT_GT(ate_odometry, 0.1);
  EXPECT_GT(Bow(odometry_only), 0.3);
  EXPECT_LT(ate, 0.01);
  EXPECT_LT(Bow(g), 0.015);  // the corridor no longer bows
  // The walls come out where they are, 2.25 m apart, in the frame of the fixed first node.
  const std::map<int, Line2> walls = g.GetLandmarks();
  ASSERT_EQ(walls.size(), 2u);
  EXPECT_NEAR(walls.at(0).offset_m + walls.at(1).offset_m, 2.25, 0.01);
  EXPECT_NEAR(NormalizeAngle(walls.at(0).normal_rad - kPi / 2), 0.0, 0.002);
  for (const LineObservationReport& report : g.LineObservationReports())
    EXPECT_FALSE(report.rejected) << report.node_id;
  EXPECT_EQ(g.OdometryCalibrations().at(0), (OdometryCalibration{0.0, 0.0, 0.0}));
}

// A saved map's wall, as `uwbsar localize` uses it: the landmark is fixed where the map has it
// (here 5 cm further left than the run's own start puts it), never re-seeded from the run's
// view, and the run's nodes move to see it where they do.
TEST(LineLandmarkTest, AFixedLandmarkStaysWhereTheMapHasItAndPlacesTheNodes) {
  const OdometryRun run = Corridor();
  const Line2 map_wall{kPi / 2, 1.05};  // the truth: y = 1.0
  for (const bool fixed : {true, false}) {
    SCOPED_TRACE(fixed);
    PoseGraph g;
    BuildOdometryChain(run, &g);
    g.AddLandmark(0, map_wall, fixed);
    for (int k = 0; k < static_cast<int>(run.truth.size()); ++k) {
      LineObservation o;
      o.node_id = k;
      o.line_node = LineToFrame(run.truth[k], {kPi / 2, 1.0});
      o.reference_node = {1.0, 0.0};
      o.offset_std_m = 0.02;
      o.normal_std_rad = 1.0 * kPi / 180;
      g.AddLineObservation(o);
    }
    EXPECT_TRUE(g.Optimize().converged);
    const Line2 wall = g.GetLandmarks().at(0);
    double far_y_m = 0.0;  // the nodes past the first 10 m, where node 0's pull has gone
    for (int k = 10; k < static_cast<int>(run.truth.size()); ++k) far_y_m += g.GetPose(k).y_m;
    far_y_m /= static_cast<double>(run.truth.size()) - 10;
    if (fixed) {
      EXPECT_EQ(wall.offset_m, map_wall.offset_m);
      EXPECT_EQ(wall.normal_rad, map_wall.normal_rad);
      EXPECT_NEAR(far_y_m, 0.05, 0.01);
    } else {  // a free landmark is re-seeded from node 0's view: the map's place is lost
      EXPECT_NEAR(wall.offset_m, 1.0, 0.01);
    }
  }
}

/// A ring of four 10 m legs that turn left by `turn_deg` (true turns summing to 360 deg) while
/// the odometry reports each turn `turn_error_deg` off. Each leg's nodes see the wall 1 m to their
/// left exactly. Solved first without the loop that closes the ring, then with it.
struct RingResult {
  int priors_before_loop = -1;
  int priors = -1;
  std::vector<double> corner_error_deg;  ///< between consecutive walls, estimate minus truth
  double ate_m = 0.0;
};

RingResult SolveRing(const BackendConfig& config, const std::array<double, 4>& turn_deg,
                     const std::array<double, 4>& turn_error_deg) {
  OdometryRun run;
  run.truth.push_back({});
  std::vector<int> leg_first;
  for (int leg = 0; leg < 4; ++leg) {
    leg_first.push_back(static_cast<int>(run.truth.size()) - 1);
    for (int k = 0; k < 10; ++k) {
      run.measured.push_back({1.0, 0.0, 0.0});
      run.truth.push_back(run.truth.back() * Pose2{1.0, 0.0, 0.0});
    }
    const double turn_rad = turn_deg[leg] * kPi / 180;
    run.measured.push_back({0.0, 0.0, turn_rad + turn_error_deg[leg] * kPi / 180});
    run.truth.push_back(run.truth.back() * Pose2{0.0, 0.0, turn_rad});
  }
  PoseGraph g(config);
  BuildOdometryChain(run, &g);
  std::vector<Line2> walls;
  for (int leg = 0; leg < 4; ++leg) {
    const int first = leg_first[leg];
    walls.push_back(LineToWorld(run.truth[first], {kPi / 2, 1.0}));
    g.AddLandmark(leg, LineToWorld(g.GetPose(first), {kPi / 2, 1.0}));
    for (int k = first; k < first + 11; ++k) {
      LineObservation o;
      o.landmark_id = leg;
      o.node_id = k;
      o.line_node = LineToFrame(run.truth[k], walls.back());
      o.offset_std_m = 0.03;
      o.normal_std_rad = 10.0 * kPi / 180;
      g.AddLineObservation(o);
    }
  }
  RingResult result;
  EXPECT_TRUE(g.Optimize().converged);
  result.priors_before_loop = g.RightAnglePriors();
  const int last = static_cast<int>(run.truth.size()) - 1;  // where node 0 is
  g.AddLoopEdge(0, last, Between(run.truth[0], run.truth[last]));
  EXPECT_TRUE(g.Optimize().converged);
  result.priors = g.RightAnglePriors();
  const std::map<int, Line2> est = g.GetLandmarks();
  for (int leg = 0; leg < 4; ++leg) {
    const int next = (leg + 1) % 4;
    const double est_rad = NormalizeAngle(est.at(next).normal_rad - est.at(leg).normal_rad);
    const double true_rad = NormalizeAngle(walls[next].normal_rad - walls[leg].normal_rad);
    result.corner_error_deg.push_back(NormalizeAngle(est_rad - true_rad) * 180 / kPi);
  }
  result.ate_m = GraphAte(g, run.truth);
  return result;
}

double WorstCornerDeg(const RingResult& r) {
  double worst = 0.0;
  for (const double e : r.corner_error_deg) worst = std::max(worst, std::abs(e));
  return worst;
}

// backend.landmark_right_angle_*: a square ring whose corners the odometry turned 0.7 deg wrong
// (alternately, so the loop alone cannot tell) keeps those errors without the prior; with it,
// once the closing loop encloses the walls, the corners are squared. Before the loop, no pair is
// decided.
TEST(LineLandmarkTest,
     TheRightAnglePriorSquaresCornersTheOdometryTurnedWrongOnceALoopEnclosesThem) {
  const std::array<double, 4> square = {90, 90, 90, 90};
  const std::array<double, 4> errors = {0.7, -0.7, 0.7, -0.7};
  BackendConfig config;
  const RingResult with = SolveRing(config, square, errors);  // on by default
  config.landmark_right_angle_std_deg = 0.0;
  const RingResult without = SolveRing(config, square, errors);
  EXPECT_EQ(without.priors, 0);
  std::printf(
      "square ring, corners turned 0.7 deg wrong: worst corner %.3f deg, ATE %.2f cm "
      "without the prior; %.3f deg, %.2f cm with %d priors\n",
      WorstCornerDeg(without), without.ate_m * 100, WorstCornerDeg(with), with.ate_m * 100,
      with.priors);
  EXPECT_EQ(with.priors_before_loop, 0);
  EXPECT_EQ(with.priors, 6);  // every pair of the four walls: 4 corners and 2 parallels
  EXPECT_GT(WorstCornerDeg(without), 0.5);
  EXPECT_LT(WorstCornerDeg(with), 0.5 * WorstCornerDeg(without));
  EXPECT_LT(with.ate_m, 0.5 * without.ate_m);
}

// A building that is not square (a parallelogram with corners of 92 and 88 deg), driven with
// exact odometry: its walls spread by 1 deg about the best rectilinear frame, more than
// landmark_right_angle_max_spread_deg, so no pair gets a prior and the corners stay as built.
// Without that check, a gate of 1 deg still lets the parallel walls be held (harmless), and a
// gate of 3 deg squares the corners and bends the building.
TEST(LineLandmarkTest, TheRightAnglePriorLeavesABuildingThatIsNotSquareAsItIs) {
  const std::array<double, 4> sheared = {92, 88, 92, 88};
  const std::array<double, 4> exact = {0, 0, 0, 0};
  BackendConfig config;
  const RingResult checked = SolveRing(config, sheared, exact);
  EXPECT_EQ(checked.priors, 0);
  EXPECT_LT(WorstCornerDeg(checked), 0.05);
  EXPECT_LT(checked.ate_m, 0.002);
  config.landmark_right_angle_max_spread_deg = 10.0;  // the check off
  const RingResult gated = SolveRing(config, sheared, exact);
  EXPECT_EQ(gated.priors, 2);
  EXPECT_LT(WorstCornerDeg(gated), 0.05);
  config.landmark_right_angle_gate_deg = 3.0;
  const RingResult wide = SolveRing(config, sheared, exact);
  std::printf(
      "sheared ring: worst corner error %.3f deg with the spread check, %.3f deg "
      "without it and a 3 deg gate\n",
      WorstCornerDeg(checked), WorstCornerDeg(wide));
  EXPECT_EQ(wide.priors, 6);
  EXPECT_GT(WorstCornerDeg(wide), 0.5);
}

TEST(LineLandmarkTest, AWrongObservationIsRejectedAndDoesNotBendTheMap) {
  const OdometryRun run = Corridor();
  PoseGraph g;
  BuildOdometryChain(run, &g);
  const std::vector<int> indices = AddWalls(run, 20, &g);
  g.Optimize();
  int rejected = 0;
  for (const LineObservationReport& report : g.LineObservationReports()) {
    if (!report.rejected) continue;
    EXPECT_EQ(report.node_id, 20);
    EXPECT_EQ(report.landmark_id, 0);
    ++rejected;
  }
  EXPECT_EQ(rejected, 1);  // 20 cm = 10 sigma
  EXPECT_EQ(indices.size(), 82u);
  EXPECT_LT(GraphAte(g, run.truth), 0.01);
}

TEST(LineLandmarkTest, ARemovedNodesObservationsLeaveWithItAndTheRestStillHoldTheCorridor) {
  const OdometryRun run = Corridor();
  PoseGraph g;
  BuildOdometryChain(run, &g);
  AddWalls(run, -1, &g);
  g.Optimize();
  for (const int id : {10, 11, 25}) g.RemoveNode(id);
  EXPECT_EQ(g.LineObservations().size(), 82u - 6u);
  for (const LineObservation& o : g.LineObservations()) {
    EXPECT_NE(o.node_id, 10);
    EXPECT_NE(o.node_id, 25);
  }
  const OptimizeResult r = g.Optimize();
  EXPECT_TRUE(r.converged) << r.termination;
  EXPECT_LT(Bow(g), 0.015);
}

TEST(LineLandmarkTest, BadLandmarksAndObservationsAreRefusedAndTheGraphIsUnchanged) {
  PoseGraph g;
  EXPECT_THROW(g.AddLandmark(0, {0.0, 1.0}), InputError);  // no node yet: no frame
  g.AddNode(0, Pose2{});
  g.AddLandmark(0, {0.0, 1.0});
  EXPECT_THROW(g.AddLandmark(0, {0.0, 2.0}), InputError);  // duplicate
  EXPECT_THROW(g.AddLandmark(1, {NAN, 2.0}), InputError);
  LineObservation o;
  o.landmark_id = 0;
  o.node_id = 0;
  o.line_node = {0.0, 1.0};
  LineObservation bad = o;
  bad.node_id = 5;
  EXPECT_THROW(g.AddLineObservation(bad), InputError);
  bad = o;
  bad.landmark_id = 3;
  EXPECT_THROW(g.AddLineObservation(bad), InputError);
  bad = o;
  bad.offset_std_m = 0.0;
  EXPECT_THROW(g.AddLineObservation(bad), InputError);
  bad = o;
  bad.line_node.offset_m = INFINITY;
  EXPECT_THROW(g.AddLineObservation(bad), InputError);
  EXPECT_TRUE(g.LineObservations().empty());
  EXPECT_EQ(g.AddLineObservation(o), 0);
}

}  // namespace
}  // namespace uwbsar
