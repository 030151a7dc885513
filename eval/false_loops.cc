#include "eval/false_loops.h"

#include <cmath>
#include <random>
#include <stdexcept>

namespace uwbsar {

std::vector<std::size_t> AddRandomFalseLoops(G2oGraph* graph, const FalseLoopOptions& options) {
  const int n = static_cast<int>(graph->vertices.size());
  if (options.count > 0 && n <= options.min_id_gap) {
    throw std::invalid_argument("AddRandomFalseLoops: graph too small for the id gap");
  }
  std::mt19937 rng(options.seed);
  std::uniform_int_distribution<int> pick(0, n - 1);
  std::uniform_real_distribution<double> offset(-options.max_translation_m,
                                                options.max_translation_m);
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI);
  std::vector<std::size_t> added;
  while (static_cast<int>(added.size()) < options.count) {
    const int a = pick(rng), b = pick(rng);
    if (std::abs(a - b) < options.min_id_gap) continue;
    G2oEdge e;
    e.from_id = graph->vertices[static_cast<std::size_t>(a)].id;
    e.to_id = graph->vertices[static_cast<std::size_t>(b)].id;
    const double x = offset(rng), y = offset(rng), t = yaw(rng);
    e.T_from_to = {x, y, t};
    e.information = options.information;
    added.push_back(graph->edges.size());
    graph->edges.push_back(e);
  }
  return added;
}

}  // namespace uwbsar
