#include "imaging/occupancy_grid.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <utility>

#include "core/bounded_file.h"
#include "core/yaml_file.h"
#include "imaging/image_header.h"

namespace uwbsar {
namespace {

template <class T>
T Get(const std::string& file, const YAML::Node& node, const char* key) {
  return YamlValue<T>(file, node, key, "map");
}

double GetFinite(const std::string& file, const YAML::Node& node, const char* key) {
  const double v = Get<double>(file, node, key);
  if (!std::isfinite(v))
    throw InputError(YamlWhere(file, node) + ": map key '" + key + "' must be finite");
  return v;
}

/// Reads one whitespace-separated PGM header token, skipping '#' comments.
bool NextToken(std::istream& in, std::string* token) {
  token->clear();
  int c;
  while ((c = in.get()) != EOF) {
    if (c == '#') {
      while ((c = in.get()) != EOF && c != '\n' && c != '\r') {
      }
      if (!token->empty()) return true;
    } else if (std::isspace(c)) {
      if (!token->empty()) return true;
    } else {
      token->push_back(static_cast<char>(c));
    }
  }
  return !token->empty();
}

/// Reads a PGM (P2 or P5) with its header checked and exactly width * height samples (cv::imread
/// silently accepts some truncated files). The samples are returned raw, 0..maxval, as 16-bit:
/// OpenCV scales some maxvals and not others (P2 below 256 to 255, P5 never).
cv::Mat ReadPgm(const std::string& path, double max_pixels, long* maxval) {
  std::ifstream in = OpenInputFile(path, "map image");
  std::string magic, token;
  NextToken(in, &magic);
  if (magic != "P2" && magic != "P5") {
    throw InputError(path + ": bad PGM header: magic '" + magic.substr(0, 8) +
                     "' (expected P2 or P5)");
  }
  long values[3] = {0, 0, 0};
  const char* names[3] = {"width", "height", "maxval"};
  for (int i = 0; i < 3; ++i) {
    if (!NextToken(in, &token)) throw InputError(path + ": bad PGM header: missing " + names[i]);
    char* end = nullptr;
    values[i] = std::strtol(token.c_str(), &end, 10);
    if (*end != '\0' || values[i] <= 0 || values[i] > (i == 2 ? 65535 : 1 << 20)) {
      throw InputError(path + ": bad PGM header: invalid " + names[i] + " '" + token + "'");
    }
  }
  const long long count = static_cast<long long>(values[0]) * values[1];
  // The declared size against the budget before the samples are allocated (image_header.h).
  if (static_cast<double>(count) > max_pixels) CheckImageSize(path, max_pixels, "map image");
  *maxval = values[2];
  cv::Mat image(static_cast<int>(values[1]), static_cast<int>(values[0]), CV_16UC1);
  auto* out = image.ptr<std::uint16_t>(0);  // continuous
  if (magic == "P5") {
    const int width = values[2] > 255 ? 2 : 1;  // Netpbm: big-endian when 2 bytes
    const long long bytes = count * width;
    const std::streamoff data_start = in.tellg();
    in.seekg(0, std::ios::end);
    const std::streamoff available = in.tellg() - data_start;
    if (available < bytes) {
      throw InputError(path + ": bad PGM size: header says " + std::to_string(values[0]) + " x " +
                       std::to_string(values[1]) + " (" + std::to_string(bytes) +
                       " bytes) but the file holds " + std::to_string(available));
    }
    in.seekg(data_start);
    std::vector<unsigned char> raw(static_cast<std::size_t>(bytes));
    in.read(reinterpret_cast<char*>(raw.data()), static_cast<std::streamsize>(raw.size()));
    for (long long i = 0; i < count; ++i) {
      const std::size_t k = static_cast<std::size_t>(i);
      out[i] = static_cast<std::uint16_t>(width == 1 ? raw[k] : raw[2 * k] << 8 | raw[2 * k + 1]);
    }
  } else {
    long long n = 0;
    while (NextToken(in, &token)) {
      char* end = nullptr;
      const long v = std::strtol(token.c_str(), &end, 10);
      if (*end != '\0' || v < 0 || v > values[2]) {
        throw InputError(path + ": bad PGM sample '" + token.substr(0, 12) + "' (sample " +
                         std::to_string(n) + ", maxval " + std::to_string(values[2]) + ")");
      }
      if (n < count) out[n] = static_cast<std::uint16_t>(v);
      ++n;
    }
    if (n != count) {
      throw InputError(path + ": bad PGM size: header says " + std::to_string(count) +
                       " samples but the file holds " + std::to_string(n));
    }
  }
  return image;
}

}  // namespace

bool OccupancyGrid::CellOf(const Point2& p_world, int* row, int* col) const {
  double r = 0.0, c = 0.0;
  WorldToCell(p_world, &r, &c);
  if (!(r >= 0.0 && c >= 0.0 && r < rows && c < cols)) return false;
  *row = static_cast<int>(r);
  *col = static_cast<int>(c);
  return true;
}

MapMetadata LoadMapMetadata(const std::string& yaml_path) {
  const YAML::Node root = LoadYamlMappingFile(yaml_path, "map");
  MapMetadata m;
  auto require = [&](const char* key) {
    const YAML::Node node = root[key];
    if (!node) throw InputError(yaml_path + ": missing map key '" + key + "'");
    return node;
  };
  const std::string image = Get<std::string>(yaml_path, require("image"), "image");
  if (image.empty()) throw InputError(yaml_path + ": map key 'image' is empty");
  const std::filesystem::path image_path(image);
  m.image_path = image_path.is_absolute()
                     ? image
                     : (std::filesystem::path(yaml_path).parent_path() / image_path).string();
  const YAML::Node resolution = require("resolution");
  m.resolution_m = GetFinite(yaml_path, resolution, "resolution");
  if (m.resolution_m <= 0.0) {
    throw InputError(YamlWhere(yaml_path, resolution) + ": map key 'resolution' must be > 0");
  }
  const YAML::Node origin = require("origin");
  if (!origin.IsSequence() || origin.size() != 3) {
    throw InputError(YamlWhere(yaml_path, origin) + ": map key 'origin' must be [x, y, yaw]");
  }
  m.origin = {GetFinite(yaml_path, origin[0], "origin"), GetFinite(yaml_path, origin[1], "origin"),
              NormalizeAngle(GetFinite(yaml_path, origin[2], "origin"))};
  const std::pair<const char*, double> coordinates[] = {{"x", m.origin.x_m}, {"y", m.origin.y_m}};
  for (const auto& [axis, v] : coordinates) {
    if (std::abs(v) <= kMaxWorldCoordinateM) continue;
    std::ostringstream what;
    what << YamlWhere(yaml_path, origin) << ": map key 'origin' " << axis << " is " << v
         << " m, beyond " << kMaxWorldCoordinateM << " m";
    throw InputError(what.str());
  }
  if (const YAML::Node mode = root["mode"]) {
    m.mode = Get<std::string>(yaml_path, mode, "mode");
    if (m.mode != "trinary" && m.mode != "scale" && m.mode != "raw") {
      throw InputError(YamlWhere(yaml_path, mode) + ": map key 'mode' is '" + m.mode +
                       "' (expected trinary, scale or raw)");
    }
  }
  if (const YAML::Node negate = root["negate"]) {
    // map_server writes 0/1; accept true/false too.
    const std::string v = Get<std::string>(yaml_path, negate, "negate");
    if (v == "0" || v == "false") {
      m.negate = false;
    } else if (v == "1" || v == "true") {
      m.negate = true;
    } else {
      throw InputError(YamlWhere(yaml_path, negate) + ": map key 'negate' must be 0 or 1, not '" +
                       v + "'");
    }
  }
  if (const YAML::Node occ = root["occupied_thresh"]) {
    m.occupied_thresh = GetFinite(yaml_path, occ, "occupied_thresh");
  }
  if (const YAML::Node free = root["free_thresh"]) {
    m.free_thresh = GetFinite(yaml_path, free, "free_thresh");
  }
  if (!(m.free_thresh >= 0.0 && m.free_thresh < m.occupied_thresh && m.occupied_thresh <= 1.0)) {
    throw InputError(yaml_path +
                     ": map keys need 0 <= free_thresh < occupied_thresh <= 1 (free_thresh " +
                     std::to_string(m.free_thresh) + ", occupied_thresh " +
                     std::to_string(m.occupied_thresh) + ")");
  }
  return m;
}

std::vector<std::int8_t> PixelsToCells(const std::vector<double>& pixels, double max_value,
                                       const MapMetadata& m) {
  std::vector<std::int8_t> cells(pixels.size(), OccupancyGrid::kUnknown);
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const double v = pixels[i];
    if (std::isnan(v)) continue;  // transparent pixel: unknown
    if (m.mode == "raw") {
      // Raw: the (negated) grey value is the cell value; outside 0..100 is unknown (Nav2).
      const double raw = std::round(m.negate ? max_value - v : v);
      if (raw >= 0 && raw <= 100) cells[i] = static_cast<std::int8_t>(raw);
      continue;
    }
    const double occ = m.negate ? v / max_value : (max_value - v) / max_value;
    if (occ > m.occupied_thresh) {
      cells[i] = OccupancyGrid::kOccupied;
    } else if (occ < m.free_thresh) {
      cells[i] = OccupancyGrid::kFree;
    } else if (m.mode == "scale") {
      cells[i] = static_cast<std::int8_t>(
          std::lround(99.0 * (occ - m.free_thresh) / (m.occupied_thresh - m.free_thresh)));
    }
  }
  return cells;
}

OccupancyGrid LoadOccupancyGrid(const std::string& yaml_path, double max_image_pixels,
                                MapPixels* pixels_out) {
  const MapMetadata m = LoadMapMetadata(yaml_path);
  std::error_code ec;  // a FIFO or a device is named by the image's reader
  if (!std::filesystem::exists(m.image_path, ec)) {
    throw InputError(yaml_path + ": map image '" + m.image_path + "' does not exist");
  }
  std::string extension = std::filesystem::path(m.image_path).extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(c));
  long pgm_maxval = 0;
  cv::Mat image;
  if (extension == ".pgm") {
    image = ReadPgm(m.image_path, max_image_pixels, &pgm_maxval);
  } else {
    CheckImageSize(m.image_path, max_image_pixels, "map image");
    try {
      image = cv::imread(m.image_path, cv::IMREAD_UNCHANGED);
    } catch (const cv::Exception& e) {
      throw InputError(m.image_path + ": cannot decode map image: " + e.err);
    }
  }
  if (image.empty()) throw InputError(m.image_path + ": cannot decode map image");
  if (image.depth() != CV_8U && image.depth() != CV_16U) {
    throw InputError(m.image_path + ": map image must have 8 or 16 bits per sample");
  }
  // A PGM's samples run 0..maxval (any value 1..65535, Netpbm); other formats use the
  // whole range of their depth.
  const double max_value =
      pgm_maxval > 0 ? static_cast<double>(pgm_maxval) : (image.depth() == CV_8U ? 255.0 : 65535.0);
  const int channels = image.channels();
  const int colour = channels >= 3 ? 3 : 1;  // grey, grey+alpha, BGR or BGRA
  const bool has_alpha = channels == 2 || channels == 4;
  std::vector<double> pixels(static_cast<std::size_t>(image.rows) * image.cols);
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      auto sample = [&](int ch) {
        return image.depth() == CV_8U
                   ? static_cast<double>(image.ptr<std::uint8_t>(r)[c * channels + ch])
                   : static_cast<double>(image.ptr<std::uint16_t>(r)[c * channels + ch]);
      };
      double sum = 0.0;
      for (int ch = 0; ch < colour; ++ch) sum += sample(ch);
      double v = sum / colour;
      // map_server (scale mode): a pixel that is not fully opaque is unknown.
      if (has_alpha && m.mode == "scale" && sample(channels - 1) < max_value) v = std::nan("");
      pixels[static_cast<std::size_t>(r) * image.cols + c] = v;
    }
  }
  OccupancyGrid grid;
  grid.rows = image.rows;
  grid.cols = image.cols;
  grid.resolution_m = m.resolution_m;
  grid.origin = m.origin;
  grid.cells = PixelsToCells(pixels, max_value, m);
  if (pixels_out != nullptr) {
    pixels_out->grey = std::move(pixels);
    pixels_out->max_value = max_value;
  }
  return grid;
}

std::vector<std::int8_t> GridCellsBottomUp(const OccupancyGrid& grid) {
  std::vector<std::int8_t> cells(grid.cells.size());
  const std::size_t cols = static_cast<std::size_t>(grid.cols);
  for (int row = 0; row < grid.rows; ++row) {
    const std::size_t from = static_cast<std::size_t>(row) * cols;
    const std::size_t to = static_cast<std::size_t>(grid.rows - 1 - row) * cols;
    std::memcpy(cells.data() + to, grid.cells.data() + from, cols);
  }
  return cells;
}

}  // namespace uwbsar
