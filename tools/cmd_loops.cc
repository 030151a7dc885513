// `uwbsar loops`: the D x R loop matrix of the paper's AKAZE+ORB rule, either re-evaluated
// on recorded per-pair statistics (`--from-stats STATS.csv`, e.g. the stats.csv that
// `uwbsar detectors` writes, to tune thresholds without images) or measured on a folder of
// region images D<i>, R<j> (`--images DIR`, through the same matching as `uwbsar match`);
// eval/jobs/image_match_job.h.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "eval/jobs/image_match_job.h"
#include "slam/app_config.h"
#include "tools/commands.h"

namespace uwbsar::tools {
namespace {

void PrintMatrix(const LoopMatrix& m) {
  std::printf("d\\r");
  for (int r : m.r_ids) std::printf(" %3d", r);
  std::printf("\n");
  for (std::size_t i = 0; i < m.d_ids.size(); ++i) {
    std::printf("%3d", m.d_ids[i]);
    for (int v : m.loops[i]) std::printf(" %3d", v);
    std::printf("\n");
  }
}

void PrintReasons(const LoopMatrix& m) {
  for (std::size_t i = 0; i < m.d_ids.size(); ++i) {
    for (std::size_t j = 0; j < m.r_ids.size(); ++j) {
      if (!m.reasons[i][j].empty()) {
        std::fprintf(stderr, "D%d -> R%d: %s\n", m.d_ids[i], m.r_ids[j], m.reasons[i][j].c_str());
      }
    }
  }
}

}  // namespace

void AddLoopsCommand(CLI::App& app, const GlobalOptions& globals) {
  struct Options {
    std::string stats_path, images_dir, out_dir, detectors;
    double resolution_m = 0.005;
    bool json = false;
    bool reasons = false;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "loops", "Loop matrix of the AKAZE+ORB rule on recorded statistics or on D*/R* images");
  auto* stats = cmd->add_option("--from-stats", opts->stats_path,
                                "CSV: d,r,n_akaze,scale_akaze,tx_akaze_px,ty_akaze_px,"
                                "rot_akaze_deg,n_orb,scale_orb,tx_orb_px,ty_orb_px,rot_orb_deg")
                    ->check(InputFile());
  auto* images = cmd->add_option("--images", opts->images_dir,
                                 "Folder of region images D<i>, R<j> (.png/.pgm/.tif): every "
                                 "D x R pair through `uwbsar match`");
  stats->excludes(images);
  cmd->add_option("--resolution", opts->resolution_m,
                  "--images: metres per pixel when no grid YAML describes an image")
      ->capture_default_str();
  cmd->add_option("--detectors", opts->detectors,
                  "--images: comma-separated detectors (default: the loop rule's pair, "
                  "place_recognition.validation.detectors)");
  cmd->add_option("--out", opts->out_dir,
                  "--images: write pairs.csv, pairs.md, loops.json and matrix.png here")
      ->check(OutputPath("--out"));
  cmd->add_flag("--json", opts->json,
                "Print {\"loops\": [[...], ...], \"d\": [...], \"r\": [...]} (rows d, columns r; "
                "with --images also \"pairs\")");
  cmd->add_flag("--reasons", opts->reasons, "Also print why each listed pair was rejected");
  cmd->callback([opts, &globals] {
    if (opts->stats_path.empty() == opts->images_dir.empty()) {
      throw CLI::ValidationError("loops", "give exactly one of --from-stats or --images");
    }
    if (!opts->out_dir.empty() && opts->images_dir.empty()) {
      throw CLI::ValidationError("--out", "needs --images");
    }
    const Config config = LoadConfigFor(globals);
    RefuseOutputsOnInputs(
        globals, {{"--out", opts->out_dir}},
        {{"the --from-stats file", opts->stats_path}, {"the --images folder", opts->images_dir}});
    const eval::LoopMatrixJobResult result =
        !opts->stats_path.empty()
            ? eval::LoopMatrixFromStats(config, opts->stats_path)
            : eval::LoopMatrixFromImages(config, opts->images_dir, opts->resolution_m,
                                         opts->detectors, opts->out_dir);
    const LoopMatrix& m = result.matrix;
    const nlohmann::json& json = result.json;
    if (opts->json) {
      std::cout << json.dump() << "\n";
    } else {
      PrintMatrix(m);
    }
    if (opts->reasons) PrintReasons(m);
    PrintWritten(result.files, globals, opts->json);
  });
}

}  // namespace uwbsar::tools
