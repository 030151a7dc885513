// report.html of `uwbsar map` (map_outputs.h): the page's content built from a captured
// run, the trajectories and loop counts already written, and the annotated map figure
// (slam/outputs/map_figure.h; docs/figures.md says what the figures show).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "slam/outputs/map_figure.h"
#include "slam/outputs/map_outputs.h"
#include "slam/outputs/report_html.h"

namespace uwbsar::slam {

/// A trajectory as written to the TUM files, stamps in nanoseconds.
using StampedPoses = std::vector<std::pair<TimestampNs, Pose2>>;

/// The trajectories of one run's outputs: corrected SLAM, odometry, and ground truth (empty
/// when the run has none).
struct MapTrajectories {
  StampedPoses slam;
  StampedPoses odometry;
  StampedPoses ground_truth;
};

/// The loop candidates of a run counted by outcome.
struct LoopCounts {
  int validated = 0;         ///< accepted by the validator
  int accepted = 0;          ///< in the graph now
  int backend_rejected = 0;  ///< validated, then switched off by the backend
};
LoopCounts CountLoops(const SlamSnapshot& slam);

/// The caption of a report's map figure.
inline const char* const kMapFigureCaption =
    "The SAR map (map.png's raster, linear intensity over its 99.5th percentile) with axes in "
    "metres, a scale bar, the colour bar, the paths with start (circle) and end (square) "
    "markers, and accepted loops drawn above the paths (legend on the right)";

/// A run's paths in drawing order, each in its palette colour: the SLAM path twice as wide at
/// the bottom, the odometry, and the ground truth dashed on top, so that on a straight run,
/// where the SLAM path lies on the ground truth within a pixel, both stay visible (loops
/// are drawn above all three). Every `every`-th pose (PlotPoints).
std::vector<FigurePath> RunFigurePaths(const MapTrajectories& trajectories, std::size_t every);

/// The same paths for the report's trajectory plot (CSS colours, widths in px).
std::vector<ReportTrajectory> RunReportTrajectories(const MapTrajectories& trajectories);

/// The annotated figure of `state`'s map (slam/outputs/map_figure.h): `map_bgr` is map.png's bare
/// raster on `grid`, under the RunFigurePaths and the loops.
cv::Mat MapReportFigure(const MapState& state, const MapTrajectories& trajectories,
                        const cv::Mat& map_bgr, const ImageGrid& grid);

/// The report of `state`: key figures (with `outputs`' ATEs when it has them), the map
/// figure (`figure_png`: MapReportFigure encoded as PNG), the trajectories, timing and loop
/// tables.
RunReport BuildMapReport(const MapState& state, const MapOutputs& outputs,
                         const MapTrajectories& trajectories, const std::string& figure_png);

/// Seconds per stage (StageTimes) with the thread each ran on, their sum, the `wall_s` of
/// the run and each as a share of it, with a note that the stages overlap when
/// `keyframe_thread` put features, matching and optimisation on a thread of their own.
ReportTable StageTimingTable(const StageTimes& times, double wall_s, bool keyframe_thread,
                             const std::string& title = "Time per stage");

/// Every `every`-th pose of `traj` as a plot point, and the last (where the end marker goes).
std::vector<Point2> PlotPoints(const std::vector<std::pair<TimestampNs, Pose2>>& traj,
                               std::size_t every = 5);

/// `v` with `digits` digits after the point (as the report and loops.csv print numbers).
std::string Fixed(double v, int digits);

}  // namespace uwbsar::slam
