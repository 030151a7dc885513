// `uwbsar optimize IN.g2o --out OUT.g2o [--json]`: solves a pose graph file with the
// backend (robust loss, loop rejection, support gate; backend.* configuration) and
// prints iterations, costs, solve time, termination and the rejected loops
// (slam/jobs/optimize_job.h).
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "slam/app_config.h"
#include "slam/jobs/optimize_job.h"
#include "tools/commands.h"

namespace uwbsar::tools {

namespace {

struct OptimizeOptions {
  std::string in, out, tum, png, init;
  bool json = false, skip_bad_lines = false, drop_rejected = false;
};

void AddOptimizeOptions(CLI::App* cmd, OptimizeOptions* opts) {
  cmd->add_option("input", opts->in, "g2o file (VERTEX_SE2, EDGE_SE2, FIX)")
      ->required()
      ->check(InputFile());
  cmd->add_option("--out", opts->out, "Write the optimised graph (g2o)")
      ->check(OutputPath("--out"));
  cmd->add_option("--tum", opts->tum, "Write the optimised trajectory (TUM; time = vertex id)")
      ->check(OutputPath("--tum"));
  cmd->add_option("--png", opts->png, "Write a picture of the optimised graph")
      ->check(OutputPath("--png"));
  cmd->add_option("--init", opts->init,
                  "First solve starts from: guess or chordal "
                  "(overrides backend.initialization)")
      ->check(CLI::IsMember({"guess", "chordal"}));
  cmd->add_flag("--json", opts->json, "Print the result as JSON");
  cmd->add_flag("--skip-bad-lines", opts->skip_bad_lines,
                "Skip (and report) bad lines instead of failing");
  cmd->add_flag("--drop-rejected", opts->drop_rejected, "Leave rejected loops out of --out");
}

void PrintOptimizeJson(const std::string& input, const OptimizeResult& r,
                       const std::vector<std::string>& skipped_lines) {
  nlohmann::json j;
  j["input"] = input;
  j["nodes"] = r.num_nodes;
  j["edges"] = r.num_edges;
  j["loops"] = r.num_loops;
  j["converged"] = r.converged;
  j["termination"] = r.termination;
  j["iterations"] = r.iterations;
  j["solves"] = r.solves;
  j["initial_cost"] = r.initial_cost;
  j["final_cost"] = r.final_cost;
  j["solve_time_s"] = r.solve_time_s;
  j["skipped_lines"] = skipped_lines;
  j["rejected"] = nlohmann::json::array();
  for (const EdgeReport& e : r.rejected) {
    j["rejected"].push_back({{"edge", e.index},
                             {"from", e.from_id},
                             {"to", e.to_id},
                             {"chi2", e.chi2},
                             {"reason", e.reason},
                             {"support", e.support}});
  }
  std::cout << j.dump(2) << "\n";
}

void PrintOptimizeText(const OptimizeResult& r) {
  std::printf("graph: %d nodes, %d edges (%d loops)\n", r.num_nodes, r.num_edges, r.num_loops);
  std::printf("termination: %s\n", r.termination.c_str());
  std::printf("iterations: %d in %d solves, %.3f s\n", r.iterations, r.solves, r.solve_time_s);
  std::printf("cost: %.6g -> %.6g\n", r.initial_cost, r.final_cost);
  std::printf("rejected loops: %zu\n", r.rejected.size());
  for (const EdgeReport& e : r.rejected) {
    std::printf("  edge %d: %d -> %d  chi2 %.3f  %s (support %d)\n", e.index, e.from_id, e.to_id,
                e.chi2, e.reason.c_str(), e.support);
  }
}

void Optimize(const OptimizeOptions& opts, const GlobalOptions& globals) {
  Config config = LoadConfigFor(globals);
  RefuseOutputsOnInputs(globals, {{"--out", opts.out}, {"--tum", opts.tum}, {"--png", opts.png}},
                        {{"the input graph", opts.in}});
  if (!opts.init.empty()) EnumFromName(opts.init, &config.backend.initialization);  // checked
  slam::OptimizeJobOptions options;
  options.input = opts.in;
  options.out_g2o = opts.out;
  options.out_tum = opts.tum;
  options.out_png = opts.png;
  options.skip_bad_lines = opts.skip_bad_lines;
  options.drop_rejected = opts.drop_rejected;
  const slam::OptimizeJobResult job =
      slam::RunOptimizeJob(config, options, [&globals](const std::string& s) {
        if (!globals.quiet) std::cerr << "uwbsar: warning: skipped " << s << "\n";
      });
  const OptimizeResult& r = job.result;
  if (!job.failure.empty()) {
    if (!opts.json && !globals.quiet) {
      std::printf("termination: %s\ncost: %.6g -> %.6g\n", r.termination.c_str(), r.initial_cost,
                  r.final_cost);
    }
    throw std::runtime_error(job.failure + "; no output written");
  }
  if (opts.json) {
    PrintOptimizeJson(opts.in, r, job.skipped_lines);
  } else if (!globals.quiet) {
    PrintOptimizeText(r);
  }
  std::vector<std::string> written;
  for (const std::string* f : {&opts.out, &opts.tum, &opts.png}) {
    if (!f->empty()) written.push_back(*f);
  }
  PrintWritten(written, globals, opts.json);
}

}  // namespace

void AddOptimizeCommand(CLI::App& app, const GlobalOptions& globals) {
  auto opts = std::make_shared<OptimizeOptions>();
  CLI::App* cmd = app.add_subcommand("optimize", "Optimise a g2o pose graph (SE(2))");
  AddOptimizeOptions(cmd, opts.get());
  cmd->callback([opts, &globals] { Optimize(*opts, globals); });
}

}  // namespace uwbsar::tools
