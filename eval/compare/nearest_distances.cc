#include "eval/compare/nearest_distances.h"

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace uwbsar {

std::vector<double> NearestDistances(const std::vector<Point2>& queries,
                                     const std::vector<Point2>& reference) {
  if (reference.empty()) return {};
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  cloud->reserve(reference.size());
  for (const Point2& p : reference) {
    cloud->push_back(pcl::PointXYZ(static_cast<float>(p.x_m), static_cast<float>(p.y_m), 0.0f));
  }
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
  tree.setInputCloud(cloud);
  std::vector<double> distances(queries.size());
  pcl::Indices index(1);
  std::vector<float> squared(1);
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const pcl::PointXYZ q(static_cast<float>(queries[i].x_m), static_cast<float>(queries[i].y_m),
                          0.0f);
    // The tree stores floats: recompute the distance in double from the found point.
    if (tree.nearestKSearch(q, 1, index, squared) < 1) {
      distances[i] = std::numeric_limits<double>::infinity();
      continue;
    }
    const Point2& r = reference[static_cast<std::size_t>(index[0])];
    distances[i] = std::hypot(queries[i].x_m - r.x_m, queries[i].y_m - r.y_m);
  }
  return distances;
}

DistanceStats SummarizeDistances(std::vector<double> d) {
  DistanceStats s;
  s.count = static_cast<long long>(d.size());
  if (d.empty()) {
    s.mean_m = s.p95_m = s.max_m = std::numeric_limits<double>::quiet_NaN();
    return s;
  }
  s.mean_m = std::accumulate(d.begin(), d.end(), 0.0) / static_cast<double>(d.size());
  const std::size_t rank =
      static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(d.size())));
  const std::size_t k = std::min(d.size(), std::max<std::size_t>(rank, 1)) - 1;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(k), d.end());
  s.p95_m = d[k];
  s.max_m = *std::max_element(d.begin(), d.end());
  return s;
}

}  // namespace uwbsar
