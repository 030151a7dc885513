#include "eval/compare/pcd_export.h"

#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/point_types.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "core/bounded_file.h"
#include "core/errors.h"

namespace uwbsar {
namespace {

/// PCL 1.13's reader crashes on some files without a PCD header: check the header's keys
/// before handing the file over.
void CheckPcdHeader(const std::string& path) {
  std::ifstream in = OpenInputFile(path, "PCD");
  std::set<std::string> keys;
  std::string line;
  for (int n = 0; n < 64 && std::getline(in, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    std::string key;
    words >> key;
    keys.insert(key);
    if (key == "DATA") break;
  }
  for (const char* key : {"FIELDS", "SIZE", "TYPE", "WIDTH", "HEIGHT", "POINTS", "DATA"}) {
    if (!keys.count(key)) {
      throw InputError(path + ": not a PCD file (header has no " + key + " line)");
    }
  }
}

}  // namespace

std::vector<IntensityPoint> OccupiedCellPoints(const OccupancyGrid& grid) {
  std::vector<IntensityPoint> points;
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      if (!grid.IsOccupied(r, c)) continue;
      const Point2 p = grid.CellCenter(r, c);
      points.push_back({p.x_m, p.y_m, static_cast<float>(grid.At(r, c)) / 100.0f});
    }
  }
  return points;
}

void WritePcd(const std::string& path, const std::vector<IntensityPoint>& points, bool binary) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  pcl::PointCloud<pcl::PointXYZI> cloud;
  cloud.reserve(points.size());
  for (const IntensityPoint& p : points) {
    pcl::PointXYZI q;
    q.x = static_cast<float>(p.x_m);
    q.y = static_cast<float>(p.y_m);
    q.z = 0.0f;
    q.intensity = p.intensity;
    cloud.push_back(q);
  }
  cloud.width = static_cast<std::uint32_t>(cloud.size());
  cloud.height = 1;
  cloud.is_dense = true;
  const std::string tmp = path + ".tmp" + std::to_string(::getpid()) + ".pcd";
  int status = -1;
  try {
    // PCL refuses an empty cloud in binary; ASCII writes a valid file with 0 points.
    pcl::PCDWriter writer;
    status =
        binary && !cloud.empty() ? writer.writeBinary(tmp, cloud) : writer.writeASCII(tmp, cloud);
  } catch (const std::exception& e) {
    status = -1;
  }
  if (status != 0) {
    std::remove(tmp.c_str());
    throw InputError(path + ": cannot write PCD file");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw InputError(path + ": cannot rename temporary file into place");
  }
}

std::vector<IntensityPoint> ReadPcd(const std::string& path) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  CheckPcdHeader(path);
  pcl::PointCloud<pcl::PointXYZI> cloud;
  int status = -1;
  try {
    status = pcl::io::loadPCDFile(path, cloud);
  } catch (const std::exception& e) {
    throw InputError(path + ": cannot read PCD file: " + e.what());
  }
  if (status != 0) throw InputError(path + ": cannot read PCD file");
  std::vector<IntensityPoint> points;
  points.reserve(cloud.size());
  for (const pcl::PointXYZI& p : cloud) points.push_back({p.x, p.y, p.intensity});
  return points;
}

}  // namespace uwbsar
