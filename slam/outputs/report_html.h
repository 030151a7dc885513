// report.html: one self-contained page (images inlined as base64, plots as
// inline SVG, no scripts, no external resources) that a person opens in a
// browser to judge a mapping run: the map, the trajectory against ground
// truth, the loop table and the timing breakdown (docs/figures.md says what each shows).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/pose2.h"

namespace uwbsar::slam {

struct ReportTable {
  std::string title;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::string note;  ///< printed under the table (what the numbers do not say themselves)
};

struct ReportTrajectory {
  std::string label;
  std::string colour;  ///< CSS colour (FigurePalette's, slam/outputs/map_figure.h)
  std::vector<Point2> points;
  double width = 2.0;   ///< stroke width, px
  bool dashed = false;  ///< dashed: a path under it shows between the dashes
};

struct RunReport {
  std::string title;
  std::vector<std::pair<std::string, std::string>> summary;  ///< key figures, in order
  std::vector<std::pair<std::string, std::string>> images;   ///< caption, PNG file bytes
  std::vector<ReportTrajectory> trajectories;
  /// Accepted loops, drawn above the paths with a dot at each end (a loop between two passes
  /// along one line has no length).
  std::vector<std::pair<Point2, Point2>> loop_segments;
  std::vector<ReportTable> tables;
  /// Parts of the page with the same content, each under its title after the tables (one
  /// per run of a joined session).
  std::vector<RunReport> sections;
};

/// Renders the report as HTML text.
std::string RenderReportHtml(const RunReport& report);
/// Standard base64 (RFC 4648) of `bytes`.
std::string Base64(const std::string& bytes);
/// Escapes &, <, >, " for HTML text and attributes.
std::string HtmlEscape(const std::string& text);

}  // namespace uwbsar::slam
