#include "apps/scale_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

namespace snee {

namespace {

constexpr double kWidth = 780, kHeight = 380;
constexpr double kPlotW = 300, kPlotH = 230, kTop = 80;
constexpr double kLeft[2] = {70, 450};
constexpr const char* kMeasured = "#1f5fa8";
constexpr const char* kIdeal = "#888888";

std::string fmt(const char* format, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, a);
  return buf;
}

std::string escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '<') {
      out += "&lt;";
    } else if (c == '>') {
      out += "&gt;";
    } else if (c == '&') {
      out += "&amp;";
    } else {
      out += c;
    }
  }
  return out;
}

std::string text(double x, double y, const std::string& s, const char* anchor = "middle",
                 int size = 12, const char* extra = "") {
  return "<text x=\"" + fmt("%.1f", x) + "\" y=\"" + fmt("%.1f", y) + "\" text-anchor=\"" + anchor +
         "\" font-size=\"" + std::to_string(size) + "\"" + extra + ">" + escape(s) + "</text>\n";
}

std::string line(double x0, double y0, double x1, double y1, const char* color, double width,
                 const char* dash = nullptr) {
  std::string s = "<line x1=\"" + fmt("%.1f", x0) + "\" y1=\"" + fmt("%.1f", y0) + "\" x2=\"" +
                  fmt("%.1f", x1) + "\" y2=\"" + fmt("%.1f", y1) + "\" stroke=\"" + color +
                  "\" stroke-width=\"" + fmt("%.1f", width) + "\"";
  if (dash) s += std::string(" stroke-dasharray=\"") + dash + "\"";
  return s + "/>\n";
}

// One panel: axes with ticks, the ideal line, the measured polyline with labelled dots.
std::string panel(double left, const std::vector<ScalePoint>& points, int max_threads, double y_max,
                  double y_tick, const std::string& y_label,
                  const std::function<double(const ScalePoint&)>& value,
                  const std::function<double(double)>& ideal,
                  const std::function<std::string(double)>& tick_label,
                  const std::function<std::string(double)>& value_label) {
  auto px = [&](double t) { return left + kPlotW * t / max_threads; };
  auto py = [&](double v) { return kTop + kPlotH * (1 - v / y_max); };
  std::string s;
  const double bottom = kTop + kPlotH;
  s += line(left, bottom, left + kPlotW, bottom, "black", 1);
  s += line(left, kTop, left, bottom, "black", 1);
  const int x_step = std::max(1, max_threads / 8);
  for (int t = 0; t <= max_threads; t += x_step) {
    s += line(px(t), bottom, px(t), bottom + 5, "black", 1);
    s += text(px(t), bottom + 18, std::to_string(t));
  }
  for (double v = 0; v <= y_max + 1e-9; v += y_tick) {
    s += line(left - 5, py(v), left, py(v), "black", 1);
    s += line(left, py(v), left + kPlotW, py(v), "#e4e4e4", 1);
    s += text(left - 8, py(v) + 4, tick_label(v), "end");
  }
  s += text(left + kPlotW / 2, bottom + 38, "threads", "middle", 13);
  s += text(left - 48, kTop + kPlotH / 2, y_label, "middle", 13,
            (" transform=\"rotate(-90 " + fmt("%.1f", left - 48) + " " +
             fmt("%.1f", kTop + kPlotH / 2) + ")\"")
                .c_str());
  s += line(px(1), py(ideal(1)), px(max_threads), py(ideal(max_threads)), kIdeal, 1.5, "6 4");
  std::string polyline;
  for (const ScalePoint& p : points)
    polyline += fmt("%.1f", px(p.threads)) + "," + fmt("%.1f", py(value(p))) + " ";
  s += "<polyline points=\"" + polyline + "\" fill=\"none\" stroke=\"" + kMeasured +
       "\" stroke-width=\"2\"/>\n";
  for (const ScalePoint& p : points) {
    s += "<circle cx=\"" + fmt("%.1f", px(p.threads)) + "\" cy=\"" + fmt("%.1f", py(value(p))) +
         "\" r=\"4\" fill=\"" + kMeasured + "\"/>\n";
    s += text(px(p.threads), py(value(p)) - 10, value_label(value(p)), "middle", 11);
  }
  return s;
}

}  // namespace

std::string scale_plot_svg(const std::vector<ScalePoint>& points, const std::string& title,
                           const std::string& subtitle) {
  int max_threads = 2;
  double max_speedup = 2;
  for (const ScalePoint& p : points) {
    max_threads = std::max(max_threads, p.threads);
    max_speedup = std::max(max_speedup, p.speedup);
  }
  const double speedup_top = std::ceil(std::max<double>(max_threads, max_speedup));
  const double speedup_tick = std::max(1.0, std::ceil(speedup_top / 8));
  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + fmt("%.0f", kWidth) +
                  "\" height=\"" + fmt("%.0f", kHeight) + "\" viewBox=\"0 0 " +
                  fmt("%.0f", kWidth) + " " + fmt("%.0f", kHeight) +
                  "\" font-family=\"sans-serif\">\n";
  s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s += text(kWidth / 2, 24, title, "middle", 15, " font-weight=\"bold\"");
  s += text(kWidth / 2, 44, subtitle, "middle", 12);
  s += panel(
      kLeft[0], points, max_threads, speedup_top, speedup_tick, "speedup",
      [](const ScalePoint& p) { return p.speedup; }, [](double t) { return t; },
      [](double v) { return fmt("%.0f", v); }, [](double v) { return fmt("%.2fx", v); });
  s += panel(
      kLeft[1], points, max_threads, 1.2, 0.2, "parallel efficiency",
      [](const ScalePoint& p) { return p.efficiency; }, [](double) { return 1.0; },
      [](double v) { return fmt("%.0f%%", 100 * v); },
      [](double v) { return fmt("%.1f%%", 100 * v); });
  // Legend.
  const double ly = kHeight - 16;
  s += line(250, ly - 4, 280, ly - 4, kMeasured, 2);
  s += text(286, ly, "measured (median of the repeats)", "start");
  s += line(500, ly - 4, 530, ly - 4, kIdeal, 1.5, "6 4");
  s += text(536, ly, "ideal", "start");
  return s + "</svg>\n";
}

}  // namespace snee
