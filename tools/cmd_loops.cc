// `uwbsar loops --from-stats STATS.csv [--json]`: re-evaluates the paper's AKAZE+ORB
// loop rule (with the configured thresholds) on recorded per-pair statistics, e.g. the
// stats.csv that `uwbsar detectors` writes, and prints the D x R loop matrix of 0/1.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "frontend/place_recognition/loop_stats.h"
#include "tools/commands.h"

namespace uwbsar::tools {

void AddLoopsCommand(CLI::App& app, const GlobalOptions& globals) {
  struct Options {
    std::string stats_path;
    bool json = false;
    bool reasons = false;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "loops", "Loop matrix of the AKAZE+ORB rule on recorded per-pair statistics");
  cmd->add_option("--from-stats", opts->stats_path,
                  "CSV: d,r,n_akaze,scale_akaze,tx_akaze_px,ty_akaze_px,rot_akaze_deg,n_orb,"
                  "scale_orb,tx_orb_px,ty_orb_px,rot_orb_deg")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_flag("--json", opts->json, "Print {\"loops\": [[...], ...]} (rows d, columns r)");
  cmd->add_flag("--reasons", opts->reasons, "Also print why each listed pair was rejected");
  cmd->callback([opts, &globals] {
    const Config config = LoadConfigFor(globals);
    const LoopMatrix m = EvaluateLoopMatrix(ReadPairStatsFile(opts->stats_path),
                                            config.place_recognition.validation);
    if (opts->json) {
      nlohmann::json out;
      out["loops"] = m.loops;
      out["d"] = m.d_ids;
      out["r"] = m.r_ids;
      std::cout << out.dump() << "\n";
    } else {
      std::printf("d\\r");
      for (int r : m.r_ids) std::printf(" %3d", r);
      std::printf("\n");
      for (std::size_t i = 0; i < m.d_ids.size(); ++i) {
        std::printf("%3d", m.d_ids[i]);
        for (int v : m.loops[i]) std::printf(" %3d", v);
        std::printf("\n");
      }
    }
    if (opts->reasons) {
      for (std::size_t i = 0; i < m.d_ids.size(); ++i) {
        for (std::size_t j = 0; j < m.r_ids.size(); ++j) {
          if (!m.reasons[i][j].empty()) {
            std::fprintf(stderr, "D%d -> R%d: %s\n", m.d_ids[i], m.r_ids[j],
                         m.reasons[i][j].c_str());
          }
        }
      }
    }
  });
}

}  // namespace uwbsar::tools
