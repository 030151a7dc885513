// `uwbsar match A B`: two SAR images (from uwbsar or another tool) matched as place
// recognition matches two keyframe tiles, with the AKAZE+ORB rule and the fused metric
// transform (eval/jobs/image_match_job.h). A rejection is an outcome (exit 0); bad input exits 3
// with one line.
#include <cstdio>
#include <iostream>

#include "eval/jobs/image_match_job.h"
#include "slam/app_config.h"
#include "tools/commands.h"

namespace uwbsar::tools {
namespace {

void PrintText(const ImageMatch& m) {
  for (const auto& [kind, r] : m.matches) {
    std::printf("%-6s keypoints %d / %d, ratio matches %d, good %d", DetectorName(kind),
                r.keypoints_b, r.keypoints_a, r.ratio_matches, r.good_matches);
    const auto t = m.detector_transforms.find(kind);
    if (t != m.detector_transforms.end()) {
      std::printf(", scale %.3f, x %+.3f m, y %+.3f m, yaw %+.2f deg", r.scale, t->second.x_m,
                  t->second.y_m, t->second.yaw_deg);
    }
    std::printf("\n");
  }
  if (m.accepted()) {
    std::printf("accepted: x %+.3f m, y %+.3f m, yaw %+.2f deg\n", m.transform.x_m, m.transform.y_m,
                m.transform.yaw_deg);
  } else {
    std::printf("rejected: %s\n", m.validation.reason.c_str());
  }
}

}  // namespace

void AddMatchCommand(CLI::App& app, const GlobalOptions& globals) {
  struct Options : eval::ImageMatchJobOptions {
    bool json = false;
  };
  auto opts = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "match",
      "Match two SAR images as place recognition matches keyframe tiles (AKAZE+ORB rule).\n"
      "Prints the transform that maps A's scene onto B: a scatterer at (x, y) in A (metres; x\n"
      "along columns to the right, y upwards) is found in B at R(yaw) ((x, y) - c) + c +\n"
      "(x_m, y_m), with c the centre of A (the centre of its middle pixel) and yaw\n"
      "counter-clockwise. Inputs: 8/16-bit PNG/PGM (an enhanced SAR image), a float TIFF as\n"
      "`uwbsar image` writes it, or a grid YAML with an `image` key; a `<stem>_grid.yaml`\n"
      "beside the image gives its resolution.");
  cmd->add_option("A", opts->a, "First SAR image")->required();
  cmd->add_option("B", opts->b, "Second SAR image")->required();
  cmd->add_option("--resolution", opts->resolution_m,
                  "Metres per pixel when no grid YAML describes an image")
      ->capture_default_str();
  cmd->add_option("--detectors", opts->detectors,
                  "Comma-separated detectors (default: the loop rule's pair, "
                  "place_recognition.validation.detectors; also sift,surf,brisk,akaze,orb)");
  cmd->add_flag("--json", opts->json, "Print the result as one JSON document");
  cmd->add_option("--out", opts->out_dir, "Also write match.png (good matches) and match.json")
      ->check(OutputPath("--out"));
  cmd->callback([opts, &globals] {
    const Config config = LoadConfigFor(globals);
    RefuseOutputsOnInputs(globals, {{"--out", opts->out_dir}},
                          {{"the image", opts->a}, {"the image", opts->b}});
    const eval::ImageMatchJobResult result = eval::RunImageMatchJob(config, *opts);
    const nlohmann::json& json = result.json;
    if (opts->json) {
      std::cout << json.dump() << "\n";
    } else if (!globals.quiet) {
      PrintText(result.match);
    }
    PrintWritten(result.files, globals, opts->json);
  });
}

}  // namespace uwbsar::tools
