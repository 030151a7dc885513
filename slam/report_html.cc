#include "slam/report_html.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

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

/// Trajectories as an SVG plot with equal axis scales (x right, y up).
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
  const double width_px = 800.0;
  const double scale = width_px / (hi_x - lo_x + 2 * pad > 0 ? hi_x - lo_x + 2 * pad : 1.0);
  const double height_px = std::max(200.0, (hi_y - lo_y + 2 * pad) * scale);
  auto X = [&](double x) { return (x - lo_x + pad) * scale; };
  auto Y = [&](double y) { return height_px - (y - lo_y + pad) * scale; };
  std::ostringstream svg;
  char buf[128];
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width_px << "\" height=\""
      << height_px << "\" style=\"background:#fafafa;border:1px solid #ccc\">\n";
  for (const auto& seg : r.loop_segments) {
    std::snprintf(buf, sizeof(buf), "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" ",
                  X(seg.first.x_m), Y(seg.first.y_m), X(seg.second.x_m), Y(seg.second.y_m));
    svg << buf << "stroke=\"#2a9d8f\" stroke-width=\"1\" stroke-dasharray=\"3,2\"/>\n";
  }
  int legend_y = 18;
  for (const auto& t : r.trajectories) {
    svg << "<polyline fill=\"none\" stroke=\"" << HtmlEscape(t.colour)
        << "\" stroke-width=\"1.5\" points=\"";
    for (const Point2& p : t.points) {
      std::snprintf(buf, sizeof(buf), "%.1f,%.1f ", X(p.x_m), Y(p.y_m));
      svg << buf;
    }
    svg << "\"/>\n<text x=\"10\" y=\"" << legend_y << "\" fill=\"" << HtmlEscape(t.colour)
        << "\" font-size=\"13\">" << HtmlEscape(t.label) << "</text>\n";
    legend_y += 16;
  }
  svg << "</svg>\n";
  return svg.str();
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
          "img{max-width:100%;border:1px solid #ccc}figure{margin:1em 0}\n"
       << "</style></head><body>\n<h1>" << HtmlEscape(r.title) << "</h1>\n";
  html << "<h2>Summary</h2>\n<table id=\"summary\">\n";
  for (const auto& [key, value] : r.summary) {
    html << "<tr><th>" << HtmlEscape(key) << "</th><td>" << HtmlEscape(value) << "</td></tr>\n";
  }
  html << "</table>\n";
  for (const auto& [caption, png] : r.images) {
    html << "<figure><img alt=\"" << HtmlEscape(caption) << "\" src=\"data:image/png;base64,"
         << Base64(png) << "\"><figcaption>" << HtmlEscape(caption) << "</figcaption></figure>\n";
  }
  html << "<h2>Trajectory</h2>\n" << TrajectorySvg(r);
  for (const ReportTable& t : r.tables) {
    html << "<h2>" << HtmlEscape(t.title) << "</h2>\n<table>\n<tr>";
    for (const auto& h : t.header) html << "<th>" << HtmlEscape(h) << "</th>";
    html << "</tr>\n";
    for (const auto& row : t.rows) {
      html << "<tr>";
      for (const auto& cell : row) html << "<td>" << HtmlEscape(cell) << "</td>";
      html << "</tr>\n";
    }
    html << "</table>\n";
  }
  html << "</body></html>\n";
  return html.str();
}

}  // namespace uwbsar::slam
