// `uwbsar export-pcd`: a map as a PCD v0.7 point cloud (PCL, CloudCompare): the occupied
// cells of a map_server map, or the peaks of a float SAR map with their intensity
// (eval/jobs/compare_job.h).
#include <cstdio>

#include "eval/jobs/compare_job.h"
#include "slam/app_config.h"
#include "tools/commands.h"

namespace uwbsar::tools {

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
  cmd->add_option("--out", opts->out, "Output .pcd file")->required()->check(OutputPath("--out"));
  cmd->add_option("--grid", opts->grid,
                  "Pixel geometry of a float TIFF (default: <prefix>_grid.yaml)");
  cmd->add_flag("--ascii", opts->ascii, "ASCII PCD instead of binary");
  cmd->callback([opts, &globals] {
    const AppConfig config = LoadConfigFor(globals);
    RefuseOutputsOnInputs(globals, {{"--out", opts->out}},
                          {{"the input map", opts->map}, {"the --grid file", opts->grid}});
    slam::CheckOutputFile(opts->out);  // before the work
    if (!opts->grid.empty() && !eval::IsFloatSarMapPath(opts->map)) {
      throw CLI::ValidationError("--grid", "only for a float TIFF MAP");
    }
    const eval::PcdExportResult result =
        eval::ExportPcdJob(config, opts->map, opts->grid, opts->out, !opts->ascii);
    if (!globals.quiet) {
      std::printf("wrote %s: %zu %s\n", opts->out.c_str(), result.points, result.what.c_str());
    }
  });
}

}  // namespace uwbsar::tools
