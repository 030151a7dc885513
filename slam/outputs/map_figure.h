// The annotated map figures of report.html (docs/figures.md): a map raster framed by axes in
// metres of its frame, with a scale bar, a colour bar saying what the colours mean, a legend,
// paths with start and end markers, and loops drawn above the paths. map.png stays the bare
// raster that map_grid.yaml describes pixel for pixel (docs/make_navigation_figure.py crops
// it by that geometry), so the annotations live in the report's figure only.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/pose2.h"
#include "imaging/image_grid.h"

namespace uwbsar::slam {

/// A colour of the Okabe-Ito palette (safe for the common colour-vision deficiencies), as BGR
/// for the raster figures and CSS for the SVG plots, so both name the same colour.
struct FigureColour {
  const char* name;
  cv::Scalar bgr;
  const char* css;
};

/// The colours every figure uses for the same thing. The figures have a dark background (the
/// unobserved grey, inferno's black), so the palette's light members carry the paths.
struct FigurePalette {
  static const FigureColour kSlam;         ///< sky blue: the optimised (SLAM) trajectory
  static const FigureColour kOdometry;     ///< vermillion: odometry
  static const FigureColour kGroundTruth;  ///< bluish green: ground truth
  static const FigureColour kLoop;         ///< yellow: accepted loops
  /// One colour per run of a joined session (none of them the loops' yellow).
  static const FigureColour& Run(std::size_t n);
};

/// Unobserved map pixels (dark grey) in map.png and the figures.
inline const cv::Scalar kUnobservedBgr(40, 40, 40);
/// The percentile of the observed pixels that the map's colour scale puts at its top.
constexpr double kMapScalePercentile = 0.995;

/// The map raster of map.png: `map` (CV_32FC1, linear SAR intensity) scaled so that its
/// kMapScalePercentile of the `observed` pixels is 255 (higher values clip), colour-mapped
/// with `colormap`, unobserved pixels kUnobservedBgr. `top` (optional) gets that percentile.
cv::Mat ScaledMapImage(const cv::Mat& map, const cv::Mat& observed, const std::string& colormap,
                       float* top = nullptr);

struct FigurePath {
  std::string label;
  FigureColour colour;
  std::vector<Point2> points;  ///< in the figure's frame, in time order
  bool markers = true;         ///< start (circle) and end (square) markers
  bool line = true;            ///< false: markers only (the line is in the raster already)
  double width = 1.0;          ///< times the figure's line width
  bool dashed = false;         ///< dashed: a path under it shows between the dashes
};

struct MapFigure {
  cv::Mat map_bgr;  ///< CV_8UC3, one pixel per cell of `grid` (ScaledMapImage)
  ImageGrid grid;
  std::string frame = "world";    ///< named in the axis labels
  std::string colormap;           ///< what ScaledMapImage used, for the colour bar
  std::vector<FigurePath> paths;  ///< drawn in order
  /// Drawn above every path, with a dot at each end (a loop between two passes along one
  /// line has no length).
  std::vector<std::pair<Point2, Point2>> loops;
  std::string loop_label = "accepted loop";
  /// Legend lines for what the raster holds already (e.g. a pose-graph plot's edges), after
  /// the paths' and the loops'.
  std::vector<std::pair<std::string, cv::Scalar>> raster_legend;
  bool colour_bar = true;                  ///< false for a raster that is not a SAR map
  cv::Scalar background = kUnobservedBgr;  ///< behind the legend's line swatches, as in the raster
};

/// Where RenderMapFigure put things (for tests and captions).
struct MapFigureLayout {
  cv::Rect plot;                           ///< the map raster inside the figure
  std::vector<cv::Point> legend_swatches;  ///< centre of each legend line swatch, in order
  cv::Rect colour_bar;
  double tick_step_m = 0.0;
  double scale_bar_m = 0.0;
};

/// The figure: white margins with ticks labelled in metres (left: y, bottom: x), a scale bar
/// under the plot, and a panel on the right with the legend (paths, loops, start and end
/// markers) and the colour bar (0 to 1 times the scale's top, and the unobserved grey).
cv::Mat RenderMapFigure(const MapFigure& figure, MapFigureLayout* layout = nullptr);

/// The PNG file bytes of `image` (to inline in report.html).
std::string EncodePng(const cv::Mat& image);

/// A tick step of 1, 2 or 5 times a power of ten giving about `ticks` ticks over `span_m`.
double NiceStep(double span_m, double ticks);

}  // namespace uwbsar::slam
