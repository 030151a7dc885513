// `uwbsar export-pcd`: a map as a PCD v0.7 point cloud (PCL, CloudCompare): the occupied
// cells of a map_server map, or the peaks of a float SAR map with their intensity.
#include <cstdio>
#include <filesystem>

#include "eval/compare/pcd_export.h"
#include "eval/compare/sar_peaks.h"
#include "slam/app_config.h"
#include "tools/commands.h"

namespace uwbsar::tools {
namespace {

bool HasTiffExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(c));
  return ext == ".tif" || ext == ".tiff";
}

/// `<prefix>_float.tif` -> `<prefix>_grid.yaml` (slam/imaging_job.cc's naming).
std::string DefaultGridYaml(const std::string& tiff) {
  const std::string stem = std::filesystem::path(tiff).stem().string();
  const std::string suffix = "_float";
  const std::string prefix =
      stem.size() > suffix.size() &&
              stem.compare(stem.size() - suffix.size(), suffix.size(), suffix) == 0
          ? stem.substr(0, stem.size() - suffix.size())
          : stem;
  return (std::filesystem::path(tiff).parent_path() / (prefix + "_grid.yaml")).string();
}

}  // namespace

void AddExportPcdCommand(CLI::App& app, const GlobalOptions& globals) {
  struct Options {
    std::string map, out, grid;
    bool ascii = false;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "export-pcd",
      "Write a map as a PCD v0.7 cloud (x y z intensity): the occupied cells of a map_server "
      "YAML, or the peaks of a float SAR map (*_float.tif + *_grid.yaml) with their intensity");
  cmd->add_option("MAP", opts->map, "map_server YAML, or float SAR TIFF")->required();
  cmd->add_option("--out", opts->out, "Output .pcd file")->required();
  cmd->add_option("--grid", opts->grid,
                  "Pixel geometry of a float TIFF (default: <prefix>_grid.yaml)");
  cmd->add_flag("--ascii", opts->ascii, "ASCII PCD instead of binary");
  cmd->callback([opts, &globals] {
    const Config config = LoadConfigFor(globals);
    pipeline::CheckOutputFile(opts->out);  // before the work
    std::vector<IntensityPoint> points;
    const char* what = "occupied cells";
    if (HasTiffExtension(opts->map)) {
      const std::string grid = opts->grid.empty() ? DefaultGridYaml(opts->map) : opts->grid;
      points = SarPeaks(LoadFloatSarMap(opts->map, grid, config.limits.max_map_image_pixels),
                        config.compare.pcd_peak_fraction, config.compare.pcd_peak_radius_m);
      what = "SAR peaks";
    } else {
      if (!opts->grid.empty()) throw CLI::ValidationError("--grid", "only for a float TIFF MAP");
      points = OccupiedCellPoints(LoadOccupancyGrid(opts->map, config.limits.max_map_image_pixels));
    }
    WritePcd(opts->out, points, !opts->ascii);
    if (!globals.quiet) std::printf("wrote %s: %zu %s\n", opts->out.c_str(), points.size(), what);
  });
}

}  // namespace uwbsar::tools
