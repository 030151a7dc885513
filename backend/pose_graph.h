// The SE(2) pose graph on Ceres: nodes are keyframe poses in the world frame,
// edges are relative-pose measurements (odometry between consecutive keyframes,
// loops from place recognition). Optimize() solves it robustly:
//
//   0. on the first call with initialization = "chordal", the estimate is replaced by a
//      chordal relaxation (backend/chordal_init.h) over the edges that pass step 1;
//   1. support gate (min_loop_support > 0): loops that too few neighbouring loops
//      agree with (backend/loop_support.h) are held back from the first solves;
//   2. loops carry a robust loss (BackendConfig::robust_loss) and the graph is solved;
//      every loop's chi2 (e^T Omega e) is evaluated at the solution: loops above
//      loop_rejection_chi2 are rejected (their residual is switched off), rejected
//      loops that fit again are re-admitted, and the graph is re-solved, until the
//      set of accepted loops no longer changes (at most max_rejection_rounds);
//   3. held-back loops whose chi2 against that solution passes the same test are
//      admitted and step 2 repeats; the others stay rejected as "unsupported"
//      (a lone false loop into an otherwise unconstrained part of the map, e.g. the
//      end of a run, fits perfectly once accepted, so only this order rejects it);
//   4. consistency (max_odometry_chi2 > 0): while some odometry edge's chi2 exceeds
//      max_odometry_chi2, an accepted loop spanning it is rejected for good ("inconsistent")
//      and the graph re-solved (backend/odometry_consistency.h);
//   4b. trial (max_trial_solves per call, lowest chi2 first): a loop still held back is
//      tried once in a plain solve with it
//      added and kept when the map stays consistent: its chi2 and every other accepted
//      loop's within loop_rejection_chi2, every odometry edge within max_odometry_chi2,
//      and the total chi2 grown by at most trial_loop_chi2; otherwise the map is restored;
//   5. with final_least_squares, a last solve without loss on the accepted loops
//      gives the plain least-squares (maximum-likelihood) estimate of the inliers;
//   6. right angles (landmark_right_angle_std_deg > 0): landmark pairs that an accepted loop
//      now encloses are decided on that solution (backend/pose_graph_right_angles.cc); when a
//      prior is added, the warm update below runs once more.
// Later calls (incremental updates) start from the previous solution, which is already
// the map without the held-back loops: those are tested first (step 3), then one plain
// least-squares solve runs, and steps 2-4 follow only if some loop changes status.
// Odometry edges are never rejected. With odometry_calibration, the odometry edges of each
// trajectory (AddOdometryEdge's `trajectory`) share a calibration block
// (backend/odometry_calibration.h) with a weak prior at zero; it is free only while an
// accepted loop touches the trajectory, and constant at the prior's mean otherwise (wall edges
// alone do not free it: they see the heading drift, never the turns' scale). The gauge is
// held by the nodes marked fixed, or by the first node added when none is.
//
// Incremental use: the Ceres problem lives as long as the graph; AddNode/AddEdge
// queue new elements, Optimize() inserts them and re-solves from the current
// estimate without rebuilding anything.
//
// Locking contract: every public method is safe to call from any thread.
// Add*/Fix*/Get*/Edge* only take a short internal lock, never wait for a
// running solve, and see the estimate of the last finished Optimize() (nodes
// added since then have their initial guess). Optimize() calls are serialised
// with each other; a solve runs on the caller's thread (e.g. a background
// optimisation thread) while the frontend keeps adding keyframes.
#pragma once

#include <Eigen/Core>
#include <array>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "backend/backend_config.h"
#include "backend/line_landmark.h"
#include "core/pose2.h"

namespace ceres {
class LossFunction;
class Problem;
}  // namespace ceres

namespace uwbsar {

class GyroBiasTrack;  // backend/gyro_bias_track.h

/// kWall: the sideways offset between two keyframes of one straight stretch, measured by their
/// wall profiles (frontend/wall_profile.h); its information constrains (almost) only that
/// direction. It is robust and rejected by its chi2 like a loop, but never held back for
/// support, never counted or blamed as a loop. It does not free its trajectory's odometry
/// calibration: it observes the heading drift on straight stretches but not the turns' scale,
/// which only a loop ties to it (freed by wall edges alone, the drift was corrected and the
/// turns' error kept, and a loop-less lap moved away from the truth). Once a loop has freed
/// the calibration, it measures the drift between the loops.
/// kMarginal: what a removed node's edges said about its neighbours (PoseGraph::RemoveNode),
/// folded into one edge; plain least squares, never rejected, never counted as a loop.
enum class EdgeKind { kOdometry, kLoop, kWall, kMarginal };

/// "odometry", "loop", "wall", "marginal": the names the session file and the reports use.
inline const char* EdgeKindName(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::kLoop:
      return "loop";
    case EdgeKind::kWall:
      return "wall";
    case EdgeKind::kMarginal:
      return "marginal";
    case EdgeKind::kOdometry:
      break;
  }
  return "odometry";
}

struct PoseGraphEdge {
  int from_id = 0;
  int to_id = 0;
  Pose2 T_from_to;  ///< measurement: pose of `to` in the frame of `from`
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();  ///< over (x, y, yaw), SPD
  EdgeKind kind = EdgeKind::kLoop;
  int trajectory = -1;   ///< odometry: edges of one trajectory share an odometry calibration
                         ///< (BackendConfig::odometry_calibration); -1: not calibrated
  double path_m = -1.0;  ///< odometry: the robot's path over the edge (calibration); < 0: |t|
  double turn_rad = std::numeric_limits<double>::quiet_NaN();  ///< odometry: the robot's own
                                                               ///< turn; NaN: the yaw of T
  double begin_s = std::numeric_limits<double>::quiet_NaN();   ///< odometry: the step's times
  double end_s = std::numeric_limits<double>::quiet_NaN();     ///< (gyro bias); NaN: unknown
};

/// The state of one edge after the last Optimize().
struct EdgeReport {
  int index = 0;  ///< the index AddEdge returned
  int from_id = 0;
  int to_id = 0;
  EdgeKind kind = EdgeKind::kLoop;
  bool rejected = false;  ///< only loops and wall edges are ever rejected
  std::string reason;     ///< why rejected: "chi2" (residual test), "unsupported" or
                          ///< "inconsistent" (bent the odometry, backend/odometry_consistency.h)
  int support = -1;       ///< loops: neighbouring loops that agree (-1: not computed)
  double chi2 = 0.0;      ///< e^T Omega e at the last solution (0 before the first)
};

/// The state of one landmark observation after the last Optimize().
struct LineObservationReport {
  int index = 0;  ///< the index AddLineObservation returned
  int landmark_id = 0;
  int node_id = 0;
  bool rejected = false;  ///< its chi2 exceeded loop_rejection_chi2 (the wall ended, a corner)
  double chi2 = 0.0;      ///< at the last solution (0 before the first)
};

struct OptimizeResult {
  bool converged = false;     ///< the last Ceres solve reported CONVERGENCE
  std::string termination;    ///< the last solve's termination type and message
  int iterations = 0;         ///< Ceres iterations, summed over all solves of this call
  int solves = 0;             ///< Ceres solves of this call (rejection rounds + final)
  double initial_cost = 0.0;  ///< 0.5 * sum of chi2 of all edges at the initial estimate
  double final_cost = 0.0;    ///< 0.5 * sum of chi2 of the accepted edges at the solution
  double solve_time_s = 0.0;  ///< wall time of this call (insertion, solves, rejection)
  int num_nodes = 0;
  int num_edges = 0;
  int num_loops = 0;
  std::vector<EdgeReport> rejected;  ///< every loop rejected at the end, with its chi2
};

class PoseGraph {
 public:
  explicit PoseGraph(const BackendConfig& config = {});
  ~PoseGraph();
  PoseGraph(const PoseGraph&) = delete;
  PoseGraph& operator=(const PoseGraph&) = delete;

  /// Adds a node with its initial estimate. With `reseed_from_odometry`, the first
  /// odometry edge that reaches the node before it is first optimised replaces the
  /// guess by estimate(from) * T_from_to, so that a keyframe added during a solve
  /// starts on the corrected trajectory. Throws InputError on a duplicate id or a
  /// non-finite pose; the graph is then unchanged.
  void AddNode(int id, const Pose2& T_world_node, bool reseed_from_odometry = true);

  /// Holds a node constant (the gauge). Throws InputError on an unknown id.
  void FixNode(int id);

  /// Adds an edge; returns its index. Throws InputError (graph unchanged) when a node
  /// is unknown, from == to, the measurement is not finite, or the information is not
  /// symmetric positive definite.
  int AddEdge(const PoseGraphEdge& edge);

  /// An odometry edge whose information is config's per-metre information divided by
  /// the travelled distance |t_from_to| (at least odometry_min_distance_m), calibrated with
  /// the trajectory's odometry calibration (see the file comment).
  /// `path_m` and `turn_rad`: the robot's own path and turn over the edge when the nodes'
  /// frames are not the robot's (keyframe anchors keep the world orientation; defaults:
  /// |t| and the yaw of T_from_to).
  /// `begin_s`, `end_s`: the times of the two nodes (s, any fixed origin), over which a gyro
  /// base's bias acted (backend.odometry_model gyro; NaN: unknown, no bias applies).
  int AddOdometryEdge(int from_id, int to_id, const Pose2& T_from_to, int trajectory = 0,
                      double path_m = -1.0,
                      double turn_rad = std::numeric_limits<double>::quiet_NaN(),
                      double begin_s = std::numeric_limits<double>::quiet_NaN(),
                      double end_s = std::numeric_limits<double>::quiet_NaN());

  /// The next node of an odometry chain: adds node `to_id` and the odometry edge
  /// AddOdometryEdge(from_id, to_id, ...) with the same arguments. The node starts on the
  /// corrected trajectory: the estimate of `from_id` composed with T_from_to, corrected by
  /// the base's calibration mean (BackendConfig::CalibrationMean, backend/odometry_calibration.h)
  /// when odometry_calibration is on and `trajectory` >= 0 (all zero, the default mean,
  /// leaves the step exactly as measured). Returns that estimate. Throws as AddNode and
  /// AddOdometryEdge, and std::out_of_range on an unknown `from_id` (graph unchanged).
  Pose2 AddOdometryNode(int from_id, int to_id, const Pose2& T_from_to, int trajectory = 0,
                        double path_m = -1.0,
                        double turn_rad = std::numeric_limits<double>::quiet_NaN(),
                        double begin_s = std::numeric_limits<double>::quiet_NaN(),
                        double end_s = std::numeric_limits<double>::quiet_NaN());

  /// A direct measurement of `trajectory`'s gyro bias at time `t_s` (a standstill:
  /// backend/gyro_stillness.h), `bias_radps` +- `sigma_radps`. Ignored unless odometry_model is
  /// gyro and odometry_calibration is on. Throws InputError on a non-finite value or sigma <= 0.
  void AddGyroBiasMeasurement(int trajectory, double t_s, double bias_radps, double sigma_radps);

  /// A loop edge with the configured default information.
  int AddLoopEdge(int from_id, int to_id, const Pose2& T_from_to);

  /// Adds a line landmark, a straight wall (backend/line_landmark.h), with its initial estimate
  /// in the world. A `fixed` landmark (a saved map's wall, as a run localised in the map sees
  /// it) stays at line_world; the others are re-seeded from their first observation and solved.
  /// Landmarks never free the odometry calibration. Throws InputError on a duplicate id or a
  /// non-finite line.
  void AddLandmark(int id, const Line2& line_world, bool fixed = false);

  /// Adds one node's observation of a landmark; returns its index. It carries the loops' robust
  /// loss and is rejected by its chi2 like a loop (a wall that bends or ends), never held back.
  /// Throws InputError (graph unchanged) on an unknown node or landmark, a non-finite
  /// measurement, or a standard deviation that is not > 0.
  int AddLineObservation(const LineObservation& observation);

  /// Inserts what was added since the last call and solves (see the file comment).
  OptimizeResult Optimize();

  /// Folds node `id` out of the graph, as a reduced pose graph does with a keyframe the map no
  /// longer needs (Johannsson, Kaess, Fallon and Leonard, "Temporally scalable visual SLAM using
  /// a reduced pose graph", ICRA 2013). Its odometry, marginal and accepted loop edges are
  /// composed through the neighbour they tie it to most strongly (the hub): every other
  /// neighbour gets one kMarginal edge to the hub whose measurement composes the two edges'
  /// measurements and whose covariance composes theirs (a marginal edge already between the
  /// two absorbs it: informations add). A fixed node (a frozen saved map) folds into its
  /// strongest fixed neighbour through their exact relative pose, and leaves FixedNodes().
  /// Rejected loops and wall edges of the node are dropped. The node and its edges leave the
  /// graph: Edges() and EdgeReports() no longer list them, and the other edges keep their
  /// indices. Returns the hub's id (-1 when the node had no neighbour left) and, in
  /// `T_hub_node`, the node's pose in the hub's frame at the last solution. Throws InputError
  /// for an unknown or never-solved node, and for a fixed one with no fixed neighbour.
  int RemoveNode(int id, Pose2* T_hub_node = nullptr);

  bool HasNode(int id) const;
  /// Current estimate of a node; throws std::out_of_range on an unknown id.
  Pose2 GetPose(int id) const;
  std::map<int, Pose2> GetPoses() const;
  std::vector<PoseGraphEdge> Edges() const;
  std::vector<EdgeReport> EdgeReports() const;
  std::vector<int> FixedNodes() const;
  /// The landmarks' estimates (world frame) after the last Optimize() (or as added).
  std::map<int, Line2> GetLandmarks() const;
  /// The observations of the nodes still in the graph, and their state.
  std::vector<LineObservation> LineObservations() const;
  std::vector<LineObservationReport> LineObservationReports() const;
  /// Right-angle priors made between landmarks so far (backend.landmark_right_angle_*).
  int RightAnglePriors() const;
  /// The rms departure (deg) of the first enclosed walls from one rectilinear frame, on which
  /// the right-angle priors were allowed or refused; NaN until decided.
  double BuildingSpreadDeg() const;
  /// Each calibrated trajectory's odometry calibration after the last Optimize()
  /// ([scale, heading_drift_rad_per_m, rotation_scale]; zero while no loop constrains it).
  std::map<int, std::array<double, 3>> OdometryCalibrations() const;
  /// Each trajectory's gyro bias after the last Optimize(): (segment start s, rad/s) in time
  /// order (backend/gyro_bias_track.h); empty unless odometry_model is gyro.
  std::map<int, std::vector<std::pair<double, double>>> GyroBiases() const;
  int NumNodes() const;
  int NumEdges() const;
  const BackendConfig& config() const { return config_; }

 private:
  struct SolverNode;
  struct SolverEdge;
  struct SolverLandmark;
  struct SolverObservation;
  struct CalibrationBlock;
  struct PendingBiasMeasurement {
    int trajectory = 0;
    double t_s = 0.0, bias_radps = 0.0, sigma_radps = 0.0;
  };
  struct PendingNode {
    int id = 0;
    Pose2 guess;
    bool reseed = false;
  };

  // Solver side, guarded by solve_mutex_.
  /// Moves the nodes, edges and fixes added since the last solve into the solver.
  void TakePending();
  /// Solve / reject / re-admit with the loop rules (warm when not `first`), trial solves and
  /// the odometry consistency rounds.
  void SolveWithLoopHandling(bool first, OptimizeResult* result);
  /// Copies the solution and edge states to the caller's side (takes data_mutex_).
  void PublishSolution(OptimizeResult* result);
  void InsertPending(std::vector<PendingNode> nodes, const std::vector<int>& edge_indices,
                     const std::vector<PoseGraphEdge>& edges, const std::vector<int>& fixed);
  void SetLoopLosses(bool robust);
  void RunSolve(OptimizeResult* result);
  bool UpdateLoopStatus();  ///< returns true when some loop changed status
  void RejectionRounds(bool robust, OptimizeResult* result);
  void ComputeSupport();
  void ConsistencyRounds(OptimizeResult* result);  ///< backend/odometry_consistency.h
  bool AdmitConfirmedLoops();  ///< admits held-back loops that the estimate confirms
  void ChordalStart();
  // backend/pose_graph_calibration.cc (also AddOdometryNode)
  CalibrationBlock* CalibrationFor(int trajectory);
  /// The gyro bias block an odometry edge reads (a constant zero for a wheel base or an edge
  /// of unknown times).
  double* GyroBiasFor(const PoseGraphEdge& edge);
  GyroBiasTrack* GyroBiasTrackFor(int trajectory);
  bool UsesGyroBias(int trajectory) const;  ///< odometry_model gyro, calibrated trajectory
  void UpdateCalibrationFreedom();  ///< free a block while an accepted loop touches its nodes
  double TotalChi2() const;         ///< accepted edges and the free blocks' priors
  void TrialSolveHeldBackLoops(OptimizeResult* result);
  double HalfChi2Sum(bool accepted_only) const;
  // backend/pose_graph_reduction.cc
  void EraseSolverNode(int id);
  // backend/pose_graph_landmarks.cc
  void InsertPendingLandmarks(const std::vector<std::pair<int, Line2>>& landmarks,
                              const std::vector<int>& observation_indices,
                              const std::vector<LineObservation>& observations);
  bool UpdateObservationStatus();  ///< chi2 rejection; true when some observation changed
  void SetObservationLosses();
  /// Each landmark (or those in `only`) from its first accepted observation and that node's
  /// pose.
  void ReseedLandmarks(const std::set<int>* only = nullptr);
  /// Pairs landmark `id` (just inserted) with the landmark_right_angle_pairs before it as
  /// candidates for a right-angle prior.
  void AddRightAngleCandidates(int id);
  /// Decides the candidates that an accepted loop now encloses (see BackendConfig); returns
  /// true when a prior was added.
  bool DecideRightAngles();
  double ObservationChi2Sum() const;
  std::vector<std::array<double, 2>> LandmarkStates() const;
  void RestoreLandmarkStates(const std::vector<std::array<double, 2>>& states);
  void PublishLandmarks();  ///< with data_mutex_ held

  const BackendConfig config_;

  // Locking contract: data_mutex_ guards what callers see (the members from here up to
  // solve_mutex_) and is held only briefly, never during a solve; solve_mutex_ guards the
  // solver side (the members after it) and is held by Optimize() for the whole solve, which
  // serialises solves. Lock order: solve_mutex_, then data_mutex_. config_ is immutable.
  mutable std::mutex data_mutex_;  // guards everything below up to solve_mutex_
  std::map<int, Pose2> estimates_;
  std::vector<PoseGraphEdge> edges_;
  std::vector<EdgeReport> reports_;
  std::vector<bool> removed_;  // by edge index: an edge of a removed node (RemoveNode)
  std::vector<int> fixed_ids_;
  std::map<int, std::array<double, 3>> calibrations_out_;
  std::map<int, std::vector<std::pair<double, double>>> gyro_biases_out_;
  std::vector<PendingBiasMeasurement> pending_bias_measurements_;
  std::vector<PendingNode> pending_nodes_;
  std::vector<int> pending_edges_;
  std::vector<int> pending_fixed_;
  std::map<int, Line2> landmarks_;  // world frame
  std::vector<LineObservation> observations_;
  std::vector<LineObservationReport> observation_reports_;
  std::vector<bool> observation_removed_;  // by index: an observation of a removed node
  std::vector<std::pair<int, Line2>> pending_landmarks_;
  std::set<int> fixed_landmarks_;
  int right_angle_priors_ = 0;
  double building_spread_deg_ = std::numeric_limits<double>::quiet_NaN();
  std::vector<int> pending_observations_;

  std::mutex solve_mutex_;  // guards the solver side below
  std::unique_ptr<ceres::Problem> problem_;
  std::unordered_map<int, std::unique_ptr<SolverNode>> solver_nodes_;
  std::vector<std::unique_ptr<SolverEdge>> solver_edges_;
  std::map<int, std::unique_ptr<CalibrationBlock>> calibrations_;   // by trajectory
  std::map<int, std::unique_ptr<GyroBiasTrack>> gyro_bias_tracks_;  // by trajectory (gyro)
  double no_gyro_bias_ = 0.0;  // the constant zero bias block (added on first use)
  std::map<int, std::unique_ptr<SolverLandmark>> solver_landmarks_;
  std::vector<std::unique_ptr<SolverObservation>> solver_observations_;
  std::vector<int> landmark_order_;  // ids in insertion order (right-angle candidates' partners)
  std::vector<std::pair<int, int>> right_angle_candidates_;  // landmark pairs not yet decided
  enum class Rectilinear { kUnknown, kYes, kNo };
  Rectilinear rectilinear_ = Rectilinear::kUnknown;  // the building, for right-angle priors
  std::vector<std::unique_ptr<ceres::LossFunction>> right_angle_losses_;  // the problem's, owned
  std::unordered_map<int, int> node_trajectory_;  // node -> trajectory of its odometry
  int first_node_id_ = -1;
  // The solver works in the world frame translated to the first node's initial position,
  // so that poses far from the world origin (UTM, building coordinates) keep their
  // precision: Ceres' relative parameter tolerance and the residuals see local values.
  // Estimates in and out are in the world frame.
  Point2 solver_origin_;
  bool explicit_gauge_ = false;
  bool solved_once_ = false;
};

}  // namespace uwbsar
