// The comparison report as metrics.json and as the human summary (CLI and overlay legend).
#pragma once

#include <string>
#include <vector>

#include "eval/compare/map_comparison.h"

namespace uwbsar {

/// metrics.json: inputs, evaluation rule, alignment (transform, fitness), cell counts and
/// metrics. Undefined values (e.g. precision with no SAR-occupied cell) are null.
std::string ComparisonToJson(const ComparisonReport& report);

/// A few lines: alignment, cell-wise difference, P/R/F1/IoU, distances.
std::vector<std::string> ComparisonSummaryLines(const ComparisonReport& report);

}  // namespace uwbsar
