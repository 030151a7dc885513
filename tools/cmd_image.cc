// `uwbsar image`: the SAR strip image of a whole run (paper Fig. "SAR image
// post-processing steps"), from a text log or a built-in synthetic scene.
#include <cstdio>
#include <iostream>

#include "app/app_config_io.h"
#include "core/errors.h"
#include "slam/jobs/imaging_job.h"
#include "tools/commands.h"

namespace uwbsar::tools {

void AddImageCommand(CLI::App& app, const GlobalOptions& globals) {
  struct Options {
    std::string log_path, synthetic, out_dir = "out/image", mode, prefix = "strip";
    double resolution_m = 0.0;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("image", "Write the SAR strip image of a whole run");
  auto* log =
      cmd->add_option("--log", opts->log_path, "Text log (odom/scan records)")->check(InputFile());
  cmd->add_option("--synthetic", opts->synthetic, "Built-in scene: straight or arc")
      ->check(CLI::IsMember({"straight", "arc"}))
      ->excludes(log);
  cmd->add_option("--out", opts->out_dir, "Output folder")
      ->capture_default_str()
      ->check(OutputPath("--out"));
  cmd->add_option("--mode", opts->mode, "paper or coherent (overrides imaging.mode)")
      ->check(CLI::IsMember({"paper", "coherent"}));
  cmd->add_option("--resolution", opts->resolution_m, "Pixel size in metres")
      ->check(CheckPositiveFinite, "finite > 0");
  cmd->add_option("--prefix", opts->prefix, "Output file prefix")->capture_default_str();
  cmd->callback([opts, &globals] {
    Config config = LoadConfigFor(globals);
    RefuseOutputsOnInputs(globals, {{"--out", opts->out_dir}},
                          {{"the --log file", opts->log_path}});
    slam::EnsureDirectory(opts->out_dir);  // every output is checked before the work
    if (!opts->mode.empty()) EnumFromName(opts->mode, &config.imaging.mode);  // checked above
    if (opts->resolution_m > 0) {
      config.imaging.pixel_size_m = opts->resolution_m;
      ValidateConfig(config, "--resolution");  // the sizes it implies, before any work
    }
    slam::ImagingInput input;
    if (!opts->log_path.empty()) {
      input = slam::ReadImagingLog(opts->log_path, config.limits.max_input_file_mb);
    } else if (!opts->synthetic.empty()) {
      input = slam::SyntheticImagingRun(config, opts->synthetic);
    } else {
      throw CLI::RequiredError("--log or --synthetic");
    }
    slam::StripResult result;
    try {
      result = slam::ImageRun(config, input.odometry, input.scans);
    } catch (const InputError& e) {  // nothing imaged: name the input
      throw InputError(
          (opts->log_path.empty() ? "--synthetic " + opts->synthetic : opts->log_path) + ": " +
          e.what());
    }
    const auto files =
        slam::WriteStripOutputs(opts->out_dir, opts->prefix, result.strip, config.enhance);
    if (globals.quiet) return;
    const FrontendStats& s = result.stats;
    std::printf("scans: %lld received, %lld imaged, %lld gated, %lld rejected\n", s.scans_received,
                s.scans_imaged, s.scans_gated, s.scans_rejected());
    std::printf("image: %d x %d px at %.4f m (%s mode), %.3f s\n", result.strip.grid.cols,
                result.strip.grid.rows, result.strip.grid.resolution_m,
                EnumName(config.imaging.mode), result.seconds);
    for (const auto& f : files) std::printf("wrote %s\n", f.c_str());
  });
}

}  // namespace uwbsar::tools
