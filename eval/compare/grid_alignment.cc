#include "eval/compare/grid_alignment.h"

#include <pcl/console/print.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/transformation_estimation_2D.h>
#include <pcl/registration/transformation_estimation_point_to_plane.h>
#include <pcl/registration/warp_point_rigid_3d.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>

#include "eval/compare/nearest_distances.h"

namespace uwbsar {
namespace {

using PointT = pcl::PointNormal;
using Cloud = pcl::PointCloud<PointT>;

/// PCL's ICP with its iteration count exposed (Registration keeps it protected).
template <class Base>
class CountingIcp : public Base {
 public:
  int Iterations() const { return this->nr_iterations_; }
};

Eigen::Matrix4f ToMatrix(const Pose2& T) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  const float c = static_cast<float>(std::cos(T.yaw_rad));
  const float s = static_cast<float>(std::sin(T.yaw_rad));
  m(0, 0) = c;
  m(0, 1) = -s;
  m(1, 0) = s;
  m(1, 1) = c;
  m(0, 3) = static_cast<float>(T.x_m);
  m(1, 3) = static_cast<float>(T.y_m);
  return m;
}

Pose2 FromMatrix(const Eigen::Matrix4f& m) {
  return {m(0, 3), m(1, 3), NormalizeAngle(std::atan2(m(1, 0), m(0, 0)))};
}

Cloud::Ptr ToCloud(const std::vector<Point2>& points) {
  auto cloud = std::make_shared<Cloud>();
  cloud->reserve(points.size());
  for (const Point2& p : points) {
    PointT q;
    q.x = static_cast<float>(p.x_m);
    q.y = static_cast<float>(p.y_m);
    q.z = 0.0f;
    q.normal_x = q.normal_y = q.normal_z = 0.0f;
    q.curvature = 0.0f;
    cloud->push_back(q);
  }
  return cloud;
}

/// In-plane normals: the direction of least spread of each point's k nearest neighbours.
/// PCL's NormalEstimation would return the plane's normal (0, 0, 1) for z = 0 points.
void Fit2dNormals(Cloud& cloud, int neighbours) {
  auto shared = std::make_shared<Cloud>(cloud);
  pcl::KdTreeFLANN<PointT> tree;
  tree.setInputCloud(shared);
  pcl::Indices index;
  std::vector<float> squared;
  for (PointT& p : cloud.points) {
    if (tree.nearestKSearch(p, neighbours, index, squared) < 3) continue;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto i : index) mean += Eigen::Vector2d((*shared)[i].x, (*shared)[i].y);
    mean /= static_cast<double>(index.size());
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (const auto i : index) {
      const Eigen::Vector2d d = Eigen::Vector2d((*shared)[i].x, (*shared)[i].y) - mean;
      cov += d * d.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
    const Eigen::Vector2d n = eig.eigenvectors().col(0);  // smallest eigenvalue first
    p.normal_x = static_cast<float>(n.x());
    p.normal_y = static_cast<float>(n.y());
  }
}

std::string StateName(pcl::registration::DefaultConvergenceCriteria<float>::ConvergenceState s) {
  using C = pcl::registration::DefaultConvergenceCriteria<float>;
  switch (s) {
    case C::CONVERGENCE_CRITERIA_ITERATIONS:
      return "iteration limit";
    case C::CONVERGENCE_CRITERIA_TRANSFORM:
      return "transform change below epsilon";
    case C::CONVERGENCE_CRITERIA_ABS_MSE:
      return "absolute MSE below epsilon";
    case C::CONVERGENCE_CRITERIA_REL_MSE:
      return "relative MSE change below epsilon";
    case C::CONVERGENCE_CRITERIA_NO_CORRESPONDENCES:
      return "too few correspondences";
    case C::CONVERGENCE_CRITERIA_FAILURE_AFTER_MAX_ITERATIONS:
      return "failure after iteration limit";
    default:
      return "not converged";
  }
}

/// Runs one ICP stage; returns false (with `why`) if PCL did not converge.
template <class Icp>
bool RunStage(Icp& icp, const Cloud::Ptr& source, const Cloud::Ptr& target, double distance_m,
              const CompareConfig& config, Pose2* T, int* iterations, std::string* why) {
  icp.setInputSource(source);
  icp.setInputTarget(target);
  icp.setMaxCorrespondenceDistance(distance_m);
  icp.setMaximumIterations(config.icp_max_iterations);
  icp.setTransformationEpsilon(config.icp_transformation_epsilon);
  icp.setEuclideanFitnessEpsilon(0.0);  // stop on the transform change only
  Cloud aligned;
  icp.align(aligned, ToMatrix(*T));
  *iterations += icp.Iterations();
  *why = StateName(icp.getConvergeCriteria()->getConvergenceState());
  if (!icp.hasConverged()) return false;
  *T = FromMatrix(icp.getFinalTransformation());
  return true;
}

}  // namespace

std::vector<Point2> OccupiedCellCenters(const OccupancyGrid& grid) {
  std::vector<Point2> points;
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      if (grid.IsOccupied(r, c)) points.push_back(grid.CellCenter(r, c));
    }
  }
  return points;
}

namespace {

/// The ICP stages of `config.icp_max_correspondence_m`, coarse to fine, from `*T`; false
/// (with `result->reason`) when a stage did not converge.
bool RunStages(const Cloud::Ptr& source, const Cloud::Ptr& target, const CompareConfig& config,
               Pose2* T, AlignmentResult* result, std::string* why) {
  const bool to_plane = config.icp_method == "point_to_plane";
  if (to_plane) Fit2dNormals(*target, config.icp_normal_neighbours);
  for (double distance_m : config.icp_max_correspondence_m) {
    bool ok = false;
    if (to_plane) {
      CountingIcp<pcl::IterativeClosestPointWithNormals<PointT, PointT>> icp;
      auto estimator = std::make_shared<
          pcl::registration::TransformationEstimationPointToPlane<PointT, PointT, float>>();
      estimator->setWarpFunction(
          std::make_shared<pcl::registration::WarpPointRigid3D<PointT, PointT, float>>());
      icp.setTransformationEstimation(estimator);
      ok = RunStage(icp, source, target, distance_m, config, T, &result->iterations, why);
    } else {
      CountingIcp<pcl::IterativeClosestPoint<PointT, PointT>> icp;
      icp.setTransformationEstimation(
          std::make_shared<pcl::registration::TransformationEstimation2D<PointT, PointT>>());
      ok = RunStage(icp, source, target, distance_m, config, T, &result->iterations, why);
    }
    ++result->stages;
    if (!ok) {
      std::ostringstream msg;
      msg << "ICP failed at the " << distance_m << " m stage: " << *why;
      result->reason = msg.str();
      return false;
    }
  }
  return true;
}

/// Inlier fraction and fitness of `source` moved by `T` against `target`, over the last
/// stage's distance (PCL's getFitnessScore rule).
void ScoreAlignment(const std::vector<Point2>& source, const std::vector<Point2>& target,
                    const Pose2& T, double distance_m, AlignmentResult* result) {
  std::vector<Point2> moved;
  moved.reserve(source.size());
  for (const Point2& p : source) moved.push_back(T * p);
  long long inliers = 0;
  double sum_sq = 0.0;
  for (double v : NearestDistances(moved, target)) {
    if (v <= distance_m) {
      ++inliers;
      sum_sq += v * v;
    }
  }
  result->inlier_fraction = static_cast<double>(inliers) / static_cast<double>(source.size());
  result->fitness_m2 = inliers > 0 ? sum_sq / static_cast<double>(inliers) : 0.0;
  result->inlier_rmse_m = std::sqrt(result->fitness_m2);
}

}  // namespace

AlignmentResult AlignPointSets(const std::vector<Point2>& source, const std::vector<Point2>& target,
                               const Pose2& T_initial, const CompareConfig& config) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // our result struct reports
  AlignmentResult result;
  result.T_initial = T_initial;
  result.T_target_source = T_initial;
  result.source_points = static_cast<long long>(source.size());
  result.target_points = static_cast<long long>(target.size());
  if (source.size() < 3 || target.size() < 3) {
    result.reason = "too few occupied cells to align (source " + std::to_string(source.size()) +
                    ", target " + std::to_string(target.size()) + ")";
    return result;
  }
  Pose2 T = T_initial;
  std::string why;
  if (!RunStages(ToCloud(source), ToCloud(target), config, &T, &result, &why)) return result;
  const double last_m = config.icp_max_correspondence_m.back();
  ScoreAlignment(source, target, T, last_m, &result);
  std::ostringstream msg;
  msg.precision(3);
  if (result.inlier_fraction < config.icp_min_inlier_fraction) {
    msg << "ICP rejected: only " << 100.0 * result.inlier_fraction << " % of the source cells lie"
        << " within " << last_m << " m of a target cell (need "
        << 100.0 * config.icp_min_inlier_fraction << " %)";
    result.reason = msg.str();
    return result;
  }
  result.T_target_source = T;
  result.accepted = true;
  msg << "converged (" << why << ")";
  result.reason = msg.str();
  return result;
}

}  // namespace uwbsar
