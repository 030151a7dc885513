// The parts of a joined session's report.html (`uwbsar map --resume`, `uwbsar merge`;
// slam/outputs/session_outputs.h) that a plain map's report has too: the loop table, the annotated
// map figures (slam/outputs/map_figure.h) and one section per run with its own figure, so that the
// runs joined earlier keep theirs (docs/figures.md).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "backend/trajectory_metrics.h"
#include "imaging/image_grid.h"
#include "slam/app_config.h"
#include "slam/outputs/report_html.h"
#include "slam/session/session_data.h"

namespace uwbsar::slam {

/// Every loop record of `session`: query and match keyframes and their runs, the good
/// matches per detector, the constraint, the validator's and the backend's outcome, chi2 and
/// the reason.
ReportTable SessionLoopTable(const SessionData& session);

/// The accepted loops between keyframes of `session` (both ends on run `run`; any run when
/// `run` < 0), as segments between their optimised poses.
std::vector<std::pair<Point2, Point2>> SessionLoopSegments(const SessionData& session,
                                                           int run = -1);

/// The figure of the whole session: the mosaic `raster` (ScaledMapImage) on `grid` in the
/// map frame, each run's corrected trajectory in FigurePalette::Run(n), the loops above.
cv::Mat SessionFigure(const SessionData& session, const Config& config, const cv::Mat& raster,
                      const ImageGrid& grid);

/// Run `run`'s section: its input, keyframes, path length and (when `ate` has poses) ATE;
/// the figure of its own keyframes' mosaic with its corrected trajectory, its odometry
/// (placed in the map frame by its first keyframe) and its loops; the same as a plot.
RunReport SessionRunSection(const SessionData& session, const Config& config, int run,
                            const AteResult& ate);

}  // namespace uwbsar::slam
