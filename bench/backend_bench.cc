// Pose-graph backend benchmarks:
//  - BM_M3500FromOdometry: batch solve of M3500 from its odometry guess,
//    single-threaded (default backend config); counters: ATE, cost, iterations.
//  - BM_M3500FalseLoops/N: the same with N random false loops added.
//  - BM_IncrementalLoop1000: re-solve a 1,000-node graph after adding one
//    loop; counter median_ms over the iterations.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>

#include "backend/g2o_io.h"
#include "backend/pose_graph.h"
#include "backend/trajectory_metrics.h"
#include "eval/false_loops.h"

namespace uwbsar {
namespace {

/// The public data sets are read where they lie: $UWBSAR_SHARED_DATA/posegraph, else
/// <source>/../shared/data/posegraph (never copied into the repository).
std::string DataDir() {
  const char* env = std::getenv("UWBSAR_SHARED_DATA");
  const std::string root = env != nullptr && *env != '\0'
                               ? std::string(env)
                               : std::string(UWBSAR_SOURCE_DIR) + "/../shared/data";
  return root + "/posegraph/";
}
const std::string kData = DataDir();

const G2oGraph* M3500() {
  static const G2oGraph* graph = [] {
    const std::string path = kData + "manhattanOlson3500.g2o";
    return std::filesystem::exists(path) ? new G2oGraph(ReadG2o(path)) : nullptr;
  }();
  return graph;
}

double Ate(const PoseGraph& g) {
  static const std::vector<Pose2> truth =
      ReadGroundTruthChain(kData + "manhattanOlson3500_groundtruth.txt");
  std::vector<Pose2> est;
  for (const auto& [id, p] : g.GetPoses()) est.push_back(p);
  return ComputeAte(est, truth).rmse_m;
}

void SolveFile(benchmark::State& state, const G2oGraph& file) {
  OptimizeResult last;
  double ate = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    auto graph = std::make_unique<PoseGraph>();
    LoadIntoPoseGraph(file, graph.get());
    state.ResumeTiming();
    last = graph->Optimize();
    state.PauseTiming();
    ate = Ate(*graph);
    graph.reset();
    state.ResumeTiming();
  }
  state.counters["ate_m"] = ate;
  state.counters["final_cost"] = last.final_cost;
  state.counters["iterations"] = last.iterations;
  state.counters["solves"] = last.solves;
  state.counters["converged"] = last.converged;
  state.counters["rejected"] = static_cast<double>(last.rejected.size());
}

void BM_M3500FromOdometry(benchmark::State& state) {
  if (!M3500()) return state.SkipWithError(("no M3500 data in " + kData).c_str());
  SolveFile(state, *M3500());
}
BENCHMARK(BM_M3500FromOdometry)->Unit(benchmark::kMillisecond)->Iterations(5);

void BM_M3500FalseLoops(benchmark::State& state) {
  if (!M3500()) return state.SkipWithError(("no M3500 data in " + kData).c_str());
  G2oGraph file = *M3500();
  FalseLoopOptions options;
  options.count = static_cast<int>(state.range(0));
  AddRandomFalseLoops(&file, options);
  SolveFile(state, file);
}
BENCHMARK(BM_M3500FalseLoops)->Arg(20)->Arg(100)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_IncrementalLoop1000(benchmark::State& state) {
  if (!M3500()) return state.SkipWithError(("no M3500 data in " + kData).c_str());
  // The first 1,000 nodes of M3500 with their edges, less the last 150 loops, which are
  // then added one per iteration, each followed by a re-solve.
  constexpr int kNodes = 1000;
  std::vector<G2oEdge> edges, held_out;
  for (const G2oEdge& e : M3500()->edges) {
    if (e.from_id < kNodes && e.to_id < kNodes) edges.push_back(e);
  }
  for (auto it = edges.end(); it != edges.begin() && held_out.size() < 150;) {
    --it;
    if (ClassifyG2oEdge(*it) == EdgeKind::kLoop) {
      held_out.insert(held_out.begin(), *it);
      it = edges.erase(it);
    }
  }
  G2oGraph base;
  for (const G2oVertex& v : M3500()->vertices) {
    if (v.id < kNodes) base.vertices.push_back(v);
  }
  base.edges = edges;
  PoseGraph graph;
  LoadIntoPoseGraph(base, &graph);
  graph.Optimize();
  std::vector<double> times_ms;
  std::size_t next = 0;
  for (auto _ : state) {
    if (next == held_out.size()) {
      state.SkipWithError("ran out of held-out loops");
      break;
    }
    const G2oEdge& e = held_out[next++];
    PoseGraphEdge edge{e.from_id, e.to_id, e.T_from_to, e.information, EdgeKind::kLoop};
    const auto t0 = std::chrono::steady_clock::now();
    graph.AddEdge(edge);
    const OptimizeResult r = graph.Optimize();
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    state.SetIterationTime(ms * 1e-3);
    times_ms.push_back(ms);
    if (!r.converged) state.SkipWithError(r.termination.c_str());
  }
  if (!times_ms.empty()) {
    std::sort(times_ms.begin(), times_ms.end());
    state.counters["median_ms"] = times_ms[times_ms.size() / 2];
    state.counters["max_ms"] = times_ms.back();
  }
}
BENCHMARK(BM_IncrementalLoop1000)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(100);

}  // namespace
}  // namespace uwbsar
