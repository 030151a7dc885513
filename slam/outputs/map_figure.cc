#include "slam/outputs/map_figure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "imaging/enhance.h"

namespace uwbsar::slam {

const FigureColour FigurePalette::kSlam{"sky blue", cv::Scalar(233, 180, 86), "#56B4E9"};
const FigureColour FigurePalette::kOdometry{"vermillion", cv::Scalar(0, 94, 213), "#D55E00"};
const FigureColour FigurePalette::kGroundTruth{"bluish green", cv::Scalar(115, 158, 0), "#009E73"};
const FigureColour FigurePalette::kLoop{"yellow", cv::Scalar(66, 228, 240), "#F0E442"};

const FigureColour& FigurePalette::Run(std::size_t n) {
  static const FigureColour kRuns[] = {kSlam,
                                       {"orange", cv::Scalar(0, 159, 230), "#E69F00"},
                                       kGroundTruth,
                                       {"reddish purple", cv::Scalar(167, 121, 204), "#CC79A7"},
                                       {"white", cv::Scalar(255, 255, 255), "#FFFFFF"},
                                       kOdometry};
  return kRuns[n % (sizeof(kRuns) / sizeof(kRuns[0]))];
}

cv::Mat ScaledMapImage(const cv::Mat& map, const cv::Mat& observed, const std::string& colormap,
                       float* top_out) {
  std::vector<float> values;
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.cols; ++c) {
      if (observed.at<unsigned char>(r, c)) values.push_back(map.at<float>(r, c));
    }
  }
  float top = 1.0f;
  if (!values.empty()) {
    const auto k =
        static_cast<std::ptrdiff_t>(kMapScalePercentile * static_cast<double>(values.size() - 1));
    std::nth_element(values.begin(), values.begin() + k, values.end());
    top = std::max(values[static_cast<std::size_t>(k)], 1e-12f);
  }
  if (top_out != nullptr) *top_out = top;
  cv::Mat gray;
  map.convertTo(gray, CV_8U, 255.0 / top);
  cv::Mat png = Colorize(gray, colormap);
  png.setTo(kUnobservedBgr, ~observed);
  return png;
}

std::string EncodePng(const cv::Mat& image) {
  std::vector<unsigned char> bytes;
  if (!cv::imencode(".png", image, bytes)) throw std::runtime_error("PNG encoding failed");
  return std::string(bytes.begin(), bytes.end());
}

double NiceStep(double span_m, double ticks) {
  const double raw = std::max(span_m, 1e-9) / std::max(ticks, 1.0);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double n = raw / magnitude;
  return (n < 1.5 ? 1.0 : n < 3.5 ? 2.0 : n < 7.5 ? 5.0 : 10.0) * magnitude;
}

namespace {

/// The largest 1, 2 or 5 times a power of ten that is at most `limit`.
double NiceAtMost(double limit) {
  const double magnitude = std::pow(10.0, std::floor(std::log10(std::max(limit, 1e-9))));
  const double n = limit / magnitude;
  return (n >= 5.0 ? 5.0 : n >= 2.0 ? 2.0 : 1.0) * magnitude;
}

const cv::Scalar kInk(0, 0, 0);
const cv::Scalar kPaper(255, 255, 255);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

/// `v` as a tick label with as many decimals as `step` needs (no "-0").
std::string TickLabel(double v, double step) {
  const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  if (std::fabs(v) < 0.5 * step) v = 0.0;
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}

/// Text drawing at one font scale, measured so that the layout is computed before drawing.
struct Pen {
  double scale;
  int thickness;
  cv::Size Measure(const std::string& s) const {
    int baseline = 0;
    return cv::getTextSize(s, kFont, scale, thickness, &baseline);
  }
  int line() const { return static_cast<int>(Measure("Ag").height * 1.9); }
  /// `s` with its baseline-left corner at `at`.
  void Write(cv::Mat* image, const std::string& s, cv::Point at) const {
    cv::putText(*image, s, at, kFont, scale, kInk, thickness, cv::LINE_AA);
  }
};

/// Start (filled circle) and end (filled square) of a path, outlined so they show on any map.
/// The circle is the larger, so a path that ends where it started shows both.
void DrawMarker(cv::Mat* image, cv::Point at, bool start, const cv::Scalar& colour, int size) {
  const int outline = std::max(1, size / 4);
  if (start) {
    const int radius = size * 3 / 2;
    cv::circle(*image, at, radius, colour, cv::FILLED, cv::LINE_AA);
    cv::circle(*image, at, radius, kInk, outline, cv::LINE_AA);
  } else {
    const int half = std::max(2, size * 3 / 4);
    const cv::Rect box(at.x - half, at.y - half, 2 * half + 1, 2 * half + 1);
    cv::rectangle(*image, box, colour, cv::FILLED);
    cv::rectangle(*image, box, kInk, outline);
  }
}

/// `points` joined by lines `width` pixels wide; dashed (`dash` pixels on, 3/4 of that off,
/// along the whole path) when `dash` > 0.
void DrawPolyline(cv::Mat* image, const std::vector<cv::Point2d>& points, const cv::Scalar& colour,
                  int width, int dash) {
  auto px = [](const cv::Point2d& p) {
    return cv::Point(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y)));
  };
  const double on = dash, period = 1.75 * dash;
  double travelled = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const cv::Point2d a = points[i - 1], d = points[i] - points[i - 1];
    const double length = std::hypot(d.x, d.y);
    if (dash <= 0) {
      cv::line(*image, px(a), px(points[i]), colour, width, cv::LINE_AA);
      continue;
    }
    for (double s = 0.0; s < length;) {
      const double phase = std::fmod(travelled + s, period);
      const double e = std::min(length, s + (phase < on ? on - phase : period - phase));
      if (phase < on) {
        cv::line(*image, px(a + d * (s / length)), px(a + d * (e / length)), colour, width,
                 cv::LINE_AA);
      }
      s = e;
    }
    travelled += length;
  }
}

}  // namespace

cv::Mat RenderMapFigure(const MapFigure& f, MapFigureLayout* layout_out) {
  MapFigureLayout layout;
  const ImageGrid& g = f.grid;
  // Text and lines grow with the raster, which the browser scales down to the page width.
  const double scale = std::max(0.45, std::max(g.cols, g.rows) / 1800.0);
  const Pen pen{scale, std::max(1, static_cast<int>(std::lround(1.5 * scale)))};
  const int line_px = std::max(2, static_cast<int>(std::lround(2.5 * scale)));
  const int pad = pen.line() / 2;
  const int tick_px = pen.line() / 3;

  // The plot: the map with the paths, loops above them and the markers above both.
  cv::Mat plot = f.map_bgr.clone();
  auto pixel = [&](const Point2& p) {
    return cv::Point(static_cast<int>(std::lround(g.XToCol(p.x_m))),
                     static_cast<int>(std::lround(g.YToRow(p.y_m))));
  };
  auto width_px = [&](const FigurePath& path) {
    return std::max(1, static_cast<int>(std::lround(path.width * line_px)));
  };
  for (const FigurePath& path : f.paths) {
    if (!path.line) continue;
    std::vector<cv::Point2d> points;
    for (const Point2& p : path.points) points.push_back({g.XToCol(p.x_m), g.YToRow(p.y_m)});
    DrawPolyline(&plot, points, path.colour.bgr, width_px(path),
                 path.dashed ? 4 * width_px(path) : 0);
  }
  for (const auto& [a, b] : f.loops) {
    cv::line(plot, pixel(a), pixel(b), FigurePalette::kLoop.bgr, std::max(1, line_px - 1),
             cv::LINE_AA);
    for (const Point2& end : {a, b}) {
      cv::circle(plot, pixel(end), line_px, FigurePalette::kLoop.bgr, cv::FILLED, cv::LINE_AA);
    }
  }
  const int marker_px = 2 * line_px + 2;
  for (const FigurePath& path : f.paths) {
    if (!path.markers || path.points.empty()) continue;
    DrawMarker(&plot, pixel(path.points.front()), true, path.colour.bgr, marker_px);
    DrawMarker(&plot, pixel(path.points.back()), false, path.colour.bgr, marker_px);
  }

  // Ticks: pixel centres sit at ColToX(c), so the raster spans half a pixel more each side.
  const double x_lo = g.ColToX(-0.5), x_hi = g.ColToX(g.cols - 0.5);
  const double y_lo = g.RowToY(g.rows - 0.5), y_hi = g.RowToY(-0.5);
  const double step = NiceStep(std::max(x_hi - x_lo, y_hi - y_lo), 6.0);
  layout.tick_step_m = step;
  std::vector<double> x_ticks, y_ticks;
  for (double v = std::ceil(x_lo / step) * step; v <= x_hi; v += step) x_ticks.push_back(v);
  for (double v = std::ceil(y_lo / step) * step; v <= y_hi; v += step) y_ticks.push_back(v);
  int y_label_w = 0;
  for (double v : y_ticks) y_label_w = std::max(y_label_w, pen.Measure(TickLabel(v, step)).width);

  // Legend rows: each path and the loops as a line swatch, then the two marker shapes.
  struct LegendRow {
    std::string text;
    cv::Scalar colour;
    int kind;  // 0 line, 1 start marker, 2 end marker
    int width_px = 0;
    bool dashed = false;
  };
  std::vector<LegendRow> legend;
  for (const FigurePath& p : f.paths) {
    legend.push_back({p.label, p.colour.bgr, 0, width_px(p), p.dashed});
  }
  if (!f.loops.empty()) legend.push_back({f.loop_label, FigurePalette::kLoop.bgr, 0, line_px});
  for (const auto& [text, colour] : f.raster_legend) legend.push_back({text, colour, 0, line_px});
  legend.push_back({"start", cv::Scalar(200, 200, 200), 1});
  legend.push_back({"end", cv::Scalar(200, 200, 200), 2});
  const int swatch_w = 3 * pen.line() / 2;
  const std::string bar_title = "linear intensity / p99.5";
  int panel_w = pen.Measure(bar_title).width;
  for (const LegendRow& r : legend) {
    panel_w = std::max(panel_w, swatch_w + pad + pen.Measure(r.text).width);
  }
  panel_w = std::max(panel_w, pen.Measure("not observed").width + swatch_w + pad);
  const int bar_h = f.colour_bar ? std::max(4 * pen.line(), std::min(g.rows, 10 * pen.line())) : 0;
  const int panel_h = static_cast<int>(legend.size() + 3) * pen.line() + bar_h + 2 * pen.line();

  const int left = pad + y_label_w + tick_px + pad;
  const int top = pen.line() + pad;
  const int bottom = tick_px + 4 * pen.line() + pad;
  const int right = 2 * pad + panel_w + pad;
  const int height = std::max(top + g.rows + bottom, top + panel_h + pad);
  cv::Mat figure(height, left + g.cols + right, CV_8UC3, kPaper);
  layout.plot = cv::Rect(left, top, g.cols, g.rows);
  plot.copyTo(figure(layout.plot));
  cv::rectangle(figure, cv::Rect(left - 1, top - 1, g.cols + 2, g.rows + 2), kInk, 1);

  // Axes: x ticks under the plot, y ticks left of it, labels in metres of the frame.
  const int text_h = pen.Measure("0").height;
  for (double v : x_ticks) {
    const int c = left + static_cast<int>(std::lround(g.XToCol(v)));
    cv::line(figure, {c, top + g.rows}, {c, top + g.rows + tick_px}, kInk, pen.thickness);
    const std::string s = TickLabel(v, step);
    pen.Write(&figure, s, {c - pen.Measure(s).width / 2, top + g.rows + tick_px + pad + text_h});
  }
  for (double v : y_ticks) {
    const int r = top + static_cast<int>(std::lround(g.YToRow(v)));
    cv::line(figure, {left - tick_px, r}, {left - 1, r}, kInk, pen.thickness);
    const std::string s = TickLabel(v, step);
    pen.Write(&figure, s, {left - tick_px - pad / 2 - pen.Measure(s).width, r + text_h / 2});
  }
  const std::string x_title = "x (m, " + f.frame + " frame)";
  const int title_y = top + g.rows + tick_px + pad + text_h + pen.line();
  pen.Write(&figure, x_title, {left + g.cols / 2 - pen.Measure(x_title).width / 2, title_y});
  pen.Write(&figure, "y (m)", {pad, top - pad});

  // Scale bar: its own line under the x title, a round length of at most a fifth of the plot.
  const double bar_m = NiceAtMost(g.width_m() / 5.0);
  layout.scale_bar_m = bar_m;
  const int bar_px = std::max(1, static_cast<int>(std::lround(bar_m / g.resolution_m)));
  const int bar_y = title_y + pen.line();
  cv::rectangle(figure, cv::Rect(left, bar_y - text_h / 2 - line_px, bar_px, 2 * line_px), kInk,
                cv::FILLED);
  pen.Write(&figure, "scale: " + TickLabel(bar_m, bar_m) + " m", {left + bar_px + pad, bar_y});

  // The panel: legend, then the colour bar of the raster's scale and the unobserved grey.
  const int px0 = left + g.cols + 2 * pad;
  int y = top + pen.line() / 2;
  for (const LegendRow& row : legend) {
    const cv::Point swatch(px0 + swatch_w / 2, y);
    if (row.kind == 0) {
      cv::rectangle(figure, cv::Rect(px0, y - pen.line() / 4, swatch_w, pen.line() / 2),
                    f.background, cv::FILLED);
      DrawPolyline(&figure, {cv::Point2d(px0 + 2, y), cv::Point2d(px0 + swatch_w - 2, y)},
                   row.colour, row.width_px, row.dashed ? swatch_w / 4 : 0);
      layout.legend_swatches.push_back(swatch);
    } else {
      DrawMarker(&figure, swatch, row.kind == 1, row.colour, marker_px);
    }
    pen.Write(&figure, row.text, {px0 + swatch_w + pad, y + text_h / 2});
    y += pen.line();
  }
  if (f.colour_bar) {
    y += pen.line() / 2;
    pen.Write(&figure, bar_title, {px0, y + text_h / 2});
    y += pen.line() / 2 + pad;
    cv::Mat ramp(bar_h, 1, CV_8UC1);
    for (int r = 0; r < bar_h; ++r) {
      ramp.at<unsigned char>(r) =
          static_cast<unsigned char>(255 - (255 * r) / std::max(1, bar_h - 1));
    }
    cv::Mat ramp_bgr;
    cv::resize(Colorize(ramp, f.colormap), ramp_bgr, cv::Size(swatch_w, bar_h), 0, 0,
               cv::INTER_NEAREST);
    layout.colour_bar = cv::Rect(px0, y, swatch_w, bar_h);
    ramp_bgr.copyTo(figure(layout.colour_bar));
    cv::rectangle(figure, cv::Rect(px0 - 1, y - 1, swatch_w + 2, bar_h + 2), kInk, 1);
    for (const auto& [fraction, label] :
         std::vector<std::pair<double, std::string>>{{1.0, ">= 1"}, {0.5, "0.5"}, {0.0, "0"}}) {
      const int r = y + static_cast<int>(std::lround((1.0 - fraction) * (bar_h - 1)));
      cv::line(figure, {px0 + swatch_w, r}, {px0 + swatch_w + tick_px, r}, kInk, pen.thickness);
      pen.Write(&figure, label, {px0 + swatch_w + tick_px + pad / 2, r + text_h / 2});
    }
    y += bar_h + pen.line() / 2;
    cv::rectangle(figure, cv::Rect(px0, y, swatch_w, pen.line() / 2), kUnobservedBgr, cv::FILLED);
    pen.Write(&figure, "not observed", {px0 + swatch_w + pad, y + text_h / 2 + pen.line() / 4});
  }

  if (layout_out != nullptr) *layout_out = layout;
  return figure;
}

}  // namespace uwbsar::slam
