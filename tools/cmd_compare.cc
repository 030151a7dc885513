// `uwbsar compare`: scores a SAR occupancy map, or a SAR intensity image described by a
// grid YAML (turned into occupancy by the paper's intensity rule), against a LiDAR grid
// (paper: cell-wise difference 1397 / 16800 = 8.3 %) and writes overlay.png + metrics.json.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "eval/jobs/compare_job.h"
#include "slam/app_config.h"
#include "tools/commands.h"

namespace uwbsar::tools {
namespace {

/// "x,y,yaw_deg" -> pose (yaw in radians); false if it is not three finite numbers.
bool ParsePose(const std::string& text, Pose2* T) {
  std::istringstream in(text);
  double v[3];
  char comma = 0;
  if (!(in >> v[0] >> comma) || comma != ',' || !(in >> v[1] >> comma) || comma != ',' ||
      !(in >> v[2])) {
    return false;
  }
  in >> std::ws;
  if (!in.eof() || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
    return false;
  }
  *T = {v[0], v[1], NormalizeAngle(v[2] * M_PI / 180.0)};
  return true;
}

std::string PoseCheck(const std::string& text) {
  Pose2 T;
  return ParsePose(text, &T) ? ""
                             : "expected x,y,yaw (metres, metres, degrees), got '" + text + "'";
}

struct CompareOptions {
  std::string sar, lidar, out_dir, align, init, method;
  int tolerance_cells = -1;
  bool json = false;
};

void AddCompareOptions(CLI::App* cmd, CompareOptions* opts) {
  cmd->add_option("SAR_MAP", opts->sar,
                  "SAR occupancy map (map_server YAML), or a SAR image's grid YAML (keys image, "
                  "x0_m, y0_m, resolution_m, as map_grid.yaml): occupancy by the paper's "
                  "intensity rule (slam.occupancy_resolution_m, slam.occupied_fraction, "
                  "slam.occupancy_reference_percentile)")
      ->required();
  cmd->add_option("LIDAR_MAP", opts->lidar, "LiDAR ground-truth grid (map_server YAML)")
      ->required();
  cmd->add_option("--out", opts->out_dir, "Output folder")->required()->check(OutputPath("--out"));
  cmd->add_option("--align", opts->align,
                  "icp (default: ICP from the map origins), origin (trust the origins), or a "
                  "fixed transform x,y,yaw (m, m, deg) of the SAR frame in the LiDAR frame")
      ->check([](const std::string& s) {
        return s == "icp" || s == "origin" ? std::string() : PoseCheck(s);
      });
  cmd->add_option("--init", opts->init, "ICP start x,y,yaw (m, m, deg) instead of the origins")
      ->check(PoseCheck);
  cmd->add_option("--method", opts->method, "ICP: point_to_point or point_to_plane")
      ->check(CLI::IsMember({"point_to_point", "point_to_plane"}));
  cmd->add_option("--tolerance", opts->tolerance_cells, "Match tolerance in cells (default 1)")
      ->check(CLI::Range(0, 50));
  cmd->add_flag("--json", opts->json, "Print metrics.json to stdout instead of the summary");
}

/// The alignment asked by --align (else compare.align), --method and --init.
AlignRequest MakeAlignRequest(const CompareOptions& opts, const AppConfig& config) {
  AlignRequest request;
  request.mode = opts.align.empty() ? EnumName(config.compare.align) : opts.align;
  request.method = opts.method;
  if (request.mode != "icp" && request.mode != "origin") {
    ParsePose(request.mode, &request.T_lidar_sar);
    request.mode = "fixed";
  }
  if (!opts.init.empty()) {
    if (request.mode != "icp") throw CLI::ValidationError("--init", "needs --align icp");
    ParsePose(opts.init, &request.T_lidar_sar);
  }
  return request;
}

void RunCompare(const CompareOptions& opts, const GlobalOptions& globals) {
  AppConfig config = LoadConfigFor(globals);
  RefuseOutputsOnInputs(globals, {{"--out", opts.out_dir}},
                        {{"the SAR map", opts.sar}, {"the LiDAR map", opts.lidar}});
  slam::CheckOutputFolder(opts.out_dir);  // before the work, creating nothing
  if (opts.tolerance_cells >= 0) config.compare.tolerance_cells = opts.tolerance_cells;
  const AlignRequest request = MakeAlignRequest(opts, config);
  const eval::CompareJobResult result =
      eval::RunCompareJob(config, opts.sar, opts.lidar, request, opts.out_dir);
  if (opts.json) {
    std::cout << result.json << "\n";
    return;
  }
  if (globals.quiet) return;
  for (const std::string& line : result.summary_lines) std::printf("%s\n", line.c_str());
  for (const std::string& f : result.files) std::printf("wrote %s\n", f.c_str());
}

}  // namespace

void AddCompareCommand(CLI::App& app, const GlobalOptions& globals) {
  auto opts = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare",
      "Score a SAR map against a LiDAR occupancy grid (both map_server YAML): cell-wise "
      "difference, precision/recall/F1 with a one-cell tolerance, IoU, distances; writes "
      "overlay.png and metrics.json");
  AddCompareOptions(cmd, opts.get());
  cmd->callback([opts, &globals] { RunCompare(*opts, globals); });
}

}  // namespace uwbsar::tools
