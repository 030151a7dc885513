#include "slam/outputs/report_html.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "slam/outputs/map_figure.h"

namespace uwbsar::slam {

std::string Base64(const std::string& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i < bytes.size()) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string HtmlEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

namespace {

/// `v` with as many decimals as `step` needs, "-0" printed as "0".
/// A path's stroke-width (and dashes: a path drawn under it shows between them).
std::string StrokeStyle(double width, bool dashed) {
  char buf[80];
  std::snprintf(buf, sizeof(buf), "stroke-width=\"%.1f\"%s", width,
                dashed ? " stroke-dasharray=\"6 4\"" : "");
  return buf;
}

std::string Tick(double v, double step) {
  const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  if (std::fabs(v) < 0.5 * step) v = 0.0;
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}

/// Trajectories as an SVG plot with equal axis scales (x right, y up): axes with ticks in
/// metres, a dark plot area like the map figures' (so the colours are the same), loops above
/// the paths, start (circle) and end (square) markers, and a legend under the axes.
std::string TrajectorySvg(const RunReport& r) {
  double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
  for (const auto& t : r.trajectories) {
    for (const Point2& p : t.points) {
      lo_x = std::min(lo_x, p.x_m), hi_x = std::max(hi_x, p.x_m);
      lo_y = std::min(lo_y, p.y_m), hi_y = std::max(hi_y, p.y_m);
    }
  }
  if (lo_x > hi_x) return "<p>No trajectory.</p>";
  const double span = std::max({hi_x - lo_x, hi_y - lo_y, 0.5});
  const double pad = 0.05 * span;
  lo_x -= pad, hi_x += pad, lo_y -= pad, hi_y += pad;
  const double plot_w = 720.0, left = 60.0, top = 10.0;
  const double scale = plot_w / std::max(hi_x - lo_x, 1e-9);
  const double plot_h = std::max(160.0, (hi_y - lo_y) * scale);
  const double legend_rows = std::ceil(static_cast<double>(r.trajectories.size() + 3) / 4.0);
  const double width = left + plot_w + 20, height = top + plot_h + 50 + 18 * legend_rows;
  // A short plot keeps its scale: centre the y range in it.
  const double y_mid = 0.5 * (lo_y + hi_y);
  auto X = [&](double x) { return left + (x - lo_x) * scale; };
  auto Y = [&](double y) { return top + 0.5 * plot_h - (y - y_mid) * scale; };
  std::ostringstream svg;
  char buf[200];
  std::snprintf(buf, sizeof(buf),
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
                "font-size=\"12\" font-family=\"sans-serif\">\n",
                width, height);
  svg << buf;
  std::snprintf(buf, sizeof(buf),
                "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"#282828\" "
                "stroke=\"#000\"/>\n",
                left, top, plot_w, plot_h);
  svg << buf;
  // Equal scales, but each axis its own tick step: a flat plot still gets several y ticks.
  const double step = NiceStep(hi_x - lo_x, 8.0);
  const double y_step = NiceStep(plot_h / scale, std::max(3.0, 8.0 * plot_h / plot_w));
  for (double v = std::ceil(lo_x / step) * step; v <= hi_x; v += step) {
    std::snprintf(buf, sizeof(buf),
                  "<line class=\"tick\" x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" "
                  "stroke=\"#000\"/><text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">",
                  X(v), top + plot_h, X(v), top + plot_h + 5, X(v), top + plot_h + 18);
    svg << buf << Tick(v, step) << "</text>\n";
  }
  const double y_hi = y_mid + 0.5 * plot_h / scale;
  for (double v = std::ceil((y_mid - 0.5 * plot_h / scale) / y_step) * y_step; v <= y_hi;
       v += y_step) {
    std::snprintf(buf, sizeof(buf),
                  "<line class=\"tick\" x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" "
                  "stroke=\"#000\"/><text x=\"%.1f\" y=\"%.1f\" text-anchor=\"end\">",
                  left - 5, Y(v), left, Y(v), left - 8, Y(v) + 4);
    svg << buf << Tick(v, y_step) << "</text>\n";
  }
  std::snprintf(buf, sizeof(buf),
                "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">x (m)</text>"
                "<text x=\"4\" y=\"%.1f\">y (m)</text>\n",
                left + plot_w / 2, top + plot_h + 34, top + 12);
  svg << buf;
  for (const auto& t : r.trajectories) {
    svg << "<polyline fill=\"none\" stroke=\"" << HtmlEscape(t.colour) << "\" "
        << StrokeStyle(t.width, t.dashed) << " points=\"";
    for (const Point2& p : t.points) {
      std::snprintf(buf, sizeof(buf), "%.1f,%.1f ", X(p.x_m), Y(p.y_m));
      svg << buf;
    }
    svg << "\"/>\n";
  }
  // Loops after (above) every path, markers above both.
  for (const auto& seg : r.loop_segments) {
    std::snprintf(buf, sizeof(buf),
                  "<line class=\"loop\" x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" ",
                  X(seg.first.x_m), Y(seg.first.y_m), X(seg.second.x_m), Y(seg.second.y_m));
    svg << buf << "stroke=\"" << FigurePalette::kLoop.css << "\" stroke-width=\"1.5\"/>\n";
    for (const Point2& end : {seg.first, seg.second}) {
      std::snprintf(buf, sizeof(buf),
                    "<circle class=\"loop-end\" cx=\"%.1f\" cy=\"%.1f\" r=\"2.5\" ", X(end.x_m),
                    Y(end.y_m));
      svg << buf << "fill=\"" << FigurePalette::kLoop.css << "\"/>\n";
    }
  }
  for (const auto& t : r.trajectories) {
    if (t.points.empty()) continue;
    const Point2 a = t.points.front(), b = t.points.back();
    std::snprintf(buf, sizeof(buf),
                  "<circle class=\"start\" cx=\"%.1f\" cy=\"%.1f\" r=\"5\" stroke=\"#000\" "
                  "fill=\"",
                  X(a.x_m), Y(a.y_m));
    svg << buf << HtmlEscape(t.colour) << "\"/>\n";
    std::snprintf(buf, sizeof(buf),
                  "<rect class=\"end\" x=\"%.1f\" y=\"%.1f\" width=\"9\" height=\"9\" "
                  "stroke=\"#000\" fill=\"",
                  X(b.x_m) - 4.5, Y(b.y_m) - 4.5);
    svg << buf << HtmlEscape(t.colour) << "\"/>\n";
  }
  // The legend: four entries a row, under the axis title.
  std::vector<ReportTrajectory> entries;  // the paths' styles, then the loops and markers
  for (const auto& t : r.trajectories)
    entries.push_back({t.label, t.colour, {}, t.width, t.dashed});
  if (!r.loop_segments.empty()) {
    entries.push_back({"accepted loop", FigurePalette::kLoop.css, {}, 2.0, false});
  }
  entries.push_back({"start", "", {}});
  entries.push_back({"end", "", {}});
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const double ex = left + 180.0 * static_cast<double>(i % 4);
    const double ey = top + plot_h + 52 + 18 * static_cast<double>(i / 4);
    const std::string& label = entries[i].label;
    const std::string& colour = entries[i].colour;
    if (label == "start" && colour.empty()) {
      std::snprintf(buf, sizeof(buf),
                    "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"5\" fill=\"#ccc\" stroke=\"#000\"/>",
                    ex + 12, ey - 4);
    } else if (colour.empty()) {
      std::snprintf(buf, sizeof(buf),
                    "<rect x=\"%.1f\" y=\"%.1f\" width=\"9\" height=\"9\" fill=\"#ccc\" "
                    "stroke=\"#000\"/>",
                    ex + 7.5, ey - 8.5);
    } else {
      std::snprintf(buf, sizeof(buf),
                    "<rect x=\"%.1f\" y=\"%.1f\" width=\"26\" height=\"10\" fill=\"#282828\"/>"
                    "<line class=\"swatch\" x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" ",
                    ex - 1, ey - 9, ex + 1, ey - 4, ex + 23, ey - 4);
    }
    svg << buf;
    if (!colour.empty()) {
      svg << StrokeStyle(std::max(3.0, entries[i].width), entries[i].dashed) << " stroke=\"";
    }
    if (!colour.empty()) svg << HtmlEscape(colour) << "\"/>";
    std::snprintf(buf, sizeof(buf), "<text x=\"%.1f\" y=\"%.1f\">", ex + 30, ey);
    svg << buf << HtmlEscape(label) << "</text>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace

namespace {

/// The parts of `r` (summary, figures, trajectory plot, tables, then its sections), their
/// headings at level `h` (a section's own heading one level up).
void RenderParts(const RunReport& r, int h, bool top_level, std::ostringstream& html) {
  const std::string open = "<h" + std::to_string(h) + ">",
                    close = "</h" + std::to_string(h) + ">\n";
  if (!r.summary.empty()) {
    html << open << "Summary" << close
         << (top_level ? "<table id=\"summary\">\n" : "<table class=\"summary\">\n");
    for (const auto& [key, value] : r.summary) {
      html << "<tr><th>" << HtmlEscape(key) << "</th><td>" << HtmlEscape(value) << "</td></tr>\n";
    }
    html << "</table>\n";
  }
  for (const auto& [caption, png] : r.images) {
    html << "<figure><img alt=\"" << HtmlEscape(caption) << "\" src=\"data:image/png;base64,"
         << Base64(png) << "\"><figcaption>" << HtmlEscape(caption) << "</figcaption></figure>\n";
  }
  if (!r.trajectories.empty()) html << open << "Trajectory" << close << TrajectorySvg(r);
  for (const ReportTable& t : r.tables) {
    html << open << HtmlEscape(t.title) << close << "<table>\n<tr>";
    for (const auto& head : t.header) html << "<th>" << HtmlEscape(head) << "</th>";
    html << "</tr>\n";
    for (const auto& row : t.rows) {
      html << "<tr>";
      for (const auto& cell : row) html << "<td>" << HtmlEscape(cell) << "</td>";
      html << "</tr>\n";
    }
    html << "</table>\n";
    if (!t.note.empty()) html << "<p class=\"note\">" << HtmlEscape(t.note) << "</p>\n";
  }
  for (const RunReport& section : r.sections) {
    html << "<section>\n<h" << h << ">" << HtmlEscape(section.title) << close;
    RenderParts(section, h + 1, false, html);
    html << "</section>\n";
  }
}

}  // namespace

std::string RenderReportHtml(const RunReport& r) {
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>"
       << HtmlEscape(r.title) << "</title>\n<style>\n"
       << "body{font-family:sans-serif;margin:2em;color:#222}"
          "table{border-collapse:collapse;margin:1em 0}"
          "td,th{border:1px solid #bbb;padding:3px 8px;font-size:13px;text-align:right}"
          "th{background:#eee}td:first-child,th:first-child{text-align:left}"
          "img{max-width:100%;border:1px solid #ccc}figure{margin:1em 0}"
          ".note{font-size:13px;color:#444;max-width:60em}"
          "section{border-top:2px solid #ccc;margin-top:2em}\n"
       << "</style></head><body>\n<h1>" << HtmlEscape(r.title) << "</h1>\n";
  RenderParts(r, 2, true, html);
  html << "</body></html>\n";
  return html.str();
}

}  // namespace uwbsar::slam
