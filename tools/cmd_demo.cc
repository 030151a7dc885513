// `uwbsar demo`: the embedded default. Until the end-to-end SLAM pipeline lands
// it is the imaging demo: a simulated 3 m pass along a wall and six metal poles,
// imaged in both modes, with the point-target quality figures printed.
#include <cmath>
#include <cstdio>

#include "frontend/enhance.h"
#include "frontend/psf_metrics.h"
#include "tools/commands.h"
#include "tools/imaging_job.h"

namespace uwbsar::tools {

void AddDemoCommand(CLI::App& app, const GlobalOptions& globals) {
  auto out_dir = std::make_shared<std::string>("out/demo");
  CLI::App* cmd = app.add_subcommand("demo", "Run the built-in example and print a summary");
  cmd->add_option("--out", *out_dir, "Output folder")->capture_default_str();
  cmd->callback([out_dir, &globals] {
    const Config base = LoadConfigFor(globals);
    EnsureDirectory(*out_dir);
    SyntheticPath path;
    const SyntheticRun run = SimulateRun(base, path, DemoScatterers(), EchoModel{}, 1);
    for (const char* mode : {"paper", "coherent"}) {
      Config config = base;
      config.imaging.mode = mode;
      const StripResult result = ImageRun(config, run.odometry, run.scans);
      WriteStripOutputs(*out_dir, mode, result.strip, config.enhance);
      const cv::Mat detected = config.imaging.mode == "coherent"
                                   ? MagnitudeImage(result.strip.image)
                                   : EnhancedFloat(result.strip.image, config.enhance);
      double error = 0, range_w = 0, cross_w = 0, pslr = -99;
      int found = 0;
      for (const Point2& t : DemoPointTargets()) {
        const Point2 range_dir{0.0, t.y_m > 0 ? 1.0 : -1.0};
        const PsfMetrics m = MeasurePsf(detected, result.strip.grid, t, range_dir);
        if (!m.found) continue;
        ++found;
        error = std::max(error, m.position_error_m);
        range_w += m.range_width_m;
        cross_w += m.cross_range_width_m;
        pslr = std::max(pslr, m.pslr_db);
      }
      std::printf(
          "%-8s %lld scans imaged in %.2f s; %d/6 poles found, worst position error %.1f mm, "
          "mean -3 dB width range %.1f mm / cross-range %.1f mm, worst PSLR %.1f dB\n",
          mode, result.stats.scans_imaged, result.seconds, found, error * 1e3,
          found ? range_w / found * 1e3 : 0.0, found ? cross_w / found * 1e3 : 0.0, pslr);
    }
    std::printf("images: %s/paper_*.png, %s/coherent_*.png\n", out_dir->c_str(), out_dir->c_str());
  });
}

}  // namespace uwbsar::tools
