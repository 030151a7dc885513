// `uwbsar detectors BAG`: the paper's detector experiment on a depart-and-return log
// (eval/jobs/detectors_job.h). The run is split where it turns back; each pass is imaged into
// the world frame and cut into regions (default 2 m every 1 m); SIFT, SURF, BRISK, AKAZE and
// ORB match every D_i -> R_j. Writes Table III (loops D_i -> R_i) and Table IV (AKAZE and ORB
// on non-loops |i - j| >= 2) as CSV and Markdown, the per-pair statistics for
// `uwbsar loops --from-stats`, the loop matrix of the AKAZE+ORB rule, and match images.
#include <cstdio>

#include "eval/jobs/detectors_job.h"
#include "slam/app_config.h"
#include "tools/commands.h"

namespace uwbsar::tools {
namespace {

void AddDetectorsOptions(CLI::App* cmd, eval::DetectorsJobOptions* opts) {
  cmd->add_option("BAG", opts->bag, "ROS 2 bag (directory, .db3 or .mcap)")
      ->required()
      ->check(InputPath());
  cmd->add_option("--out", opts->out_dir, "Output folder")
      ->capture_default_str()
      ->check(OutputPath("--out"));
  cmd->add_option("--regions", opts->regions, "Region length and step in metres (default 2,1)")
      ->expected(2)
      ->delimiter(',');
  cmd->add_option("--detectors", opts->detectors,
                  "Comma-separated subset of sift,surf,brisk,akaze,orb (default: all built)");
  cmd->add_option("--split-path-m", opts->split_path_m,
                  "Path length where the returning pass starts (default: farthest point)")
      ->check(CheckPositiveFinite, "finite > 0");
  cmd->add_flag("--no-images", opts->no_images, "Do not write match images");
}

void RunDetectors(eval::DetectorsJobOptions opts, const GlobalOptions& globals) {
  const Config config = LoadConfigFor(globals);
  RefuseOutputsOnInputs(globals, {{"--out", opts.out_dir}}, {{"the input bag", opts.bag}});
  opts.progress = !globals.quiet;
  const eval::DetectorsJobResult r = eval::RunDetectorsJob(config, opts);
  if (globals.quiet) return;
  std::printf("%zu scans (%zu departing, %zu returning), %zu regions of %.2f m every %.2f m\n\n",
              r.scans, r.departing, r.returning, r.regions, r.region_length_m, r.region_step_m);
  std::printf("Table III - detectors on loop closing events\n%s\n", r.table3_md.c_str());
  std::printf("Table IV - AKAZE and ORB on non-loop events\n%s\n", r.table4_md.c_str());
  std::printf(
      "Loops (AKAZE+ORB rule)\n%s\nwrote %s{table3,table4}.{csv,md}, stats.csv, "
      "loops.{csv,md}%s\n",
      r.loops_md.c_str(), r.dir.c_str(), opts.no_images ? "" : ", matches/");
}

}  // namespace

void AddDetectorsCommand(CLI::App& app, const GlobalOptions& globals) {
  auto opts = std::make_shared<eval::DetectorsJobOptions>();
  CLI::App* cmd = app.add_subcommand(
      "detectors", "The paper's detector comparison on a depart-and-return bag (Tables III, IV)");
  AddDetectorsOptions(cmd, opts.get());
  cmd->callback([opts, &globals] { RunDetectors(*opts, globals); });
}

}  // namespace uwbsar::tools
