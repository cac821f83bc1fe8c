#include "apps/scale_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

namespace snee {

namespace {

constexpr double kWidth = 780, kHeight = 390;
constexpr double kPlotW = 300, kPlotH = 230, kTop = 80;
constexpr double kLeft[2] = {70, 450};
constexpr const char* kWall = "#1f5fa8";
constexpr const char* kCpu = "#d9822b";
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
                 int size = 12, const std::string& extra = "") {
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

// Maps threads and values of one panel to SVG coordinates.
struct Frame {
  double left;
  int max_threads;
  double y_max;
  double x(double threads) const { return left + kPlotW * threads / max_threads; }
  double y(double v) const { return kTop + kPlotH * (1 - v / y_max); }
};

std::string axes(const Frame& f, double y_tick, const std::string& y_label,
                 const std::function<std::string(double)>& tick_label) {
  std::string s;
  const double bottom = kTop + kPlotH;
  for (double v = 0; v <= f.y_max + 1e-9; v += y_tick) {
    s += line(f.left, f.y(v), f.left + kPlotW, f.y(v), "#e4e4e4", 1);
    s += line(f.left - 5, f.y(v), f.left, f.y(v), "black", 1);
    s += text(f.left - 8, f.y(v) + 4, tick_label(v), "end");
  }
  s += line(f.left, bottom, f.left + kPlotW, bottom, "black", 1);
  s += line(f.left, kTop, f.left, bottom, "black", 1);
  const int x_step = std::max(1, f.max_threads / 8);
  for (int t = 0; t <= f.max_threads; t += x_step) {
    s += line(f.x(t), bottom, f.x(t), bottom + 5, "black", 1);
    s += text(f.x(t), bottom + 18, std::to_string(t));
  }
  s += text(f.left + kPlotW / 2, bottom + 38, "threads", "middle", 13);
  const double lx = f.left - 48, ly = kTop + kPlotH / 2;
  s += text(lx, ly, y_label, "middle", 13,
            " transform=\"rotate(-90 " + fmt("%.1f", lx) + " " + fmt("%.1f", ly) + ")\"");
  return s;
}

// A measured series: polyline, dots and a value label above (or below) each dot.
std::string series(const Frame& f, const std::vector<ScalePoint>& points,
                   const std::function<double(const ScalePoint&)>& value,
                   const std::function<std::string(double)>& label, const char* color,
                   double label_offset) {
  std::string polyline, s;
  for (const ScalePoint& p : points)
    polyline += fmt("%.1f", f.x(p.threads)) + "," + fmt("%.1f", f.y(value(p))) + " ";
  s += "<polyline points=\"" + polyline + "\" fill=\"none\" stroke=\"" + color +
       "\" stroke-width=\"2\"/>\n";
  for (const ScalePoint& p : points) {
    s += "<circle cx=\"" + fmt("%.1f", f.x(p.threads)) + "\" cy=\"" + fmt("%.1f", f.y(value(p))) +
         "\" r=\"4\" fill=\"" + color + "\"/>\n";
    s += text(f.x(p.threads), f.y(value(p)) + label_offset, label(value(p)), "middle", 11,
              std::string(" fill=\"") + color + "\"");
  }
  return s;
}

std::string legend_entry(double x, double y, const char* color, const char* dash,
                         const std::string& label) {
  return line(x, y - 4, x + 30, y - 4, color, 2, dash) + text(x + 36, y, label, "start");
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
  const Frame speedup{kLeft[0], max_threads, std::ceil(std::max<double>(max_threads, max_speedup))};
  const Frame efficiency{kLeft[1], max_threads, 1.2};
  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + fmt("%.0f", kWidth) +
                  "\" height=\"" + fmt("%.0f", kHeight) + "\" viewBox=\"0 0 " +
                  fmt("%.0f", kWidth) + " " + fmt("%.0f", kHeight) +
                  "\" font-family=\"sans-serif\">\n";
  s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s += text(kWidth / 2, 24, title, "middle", 15, " font-weight=\"bold\"");
  s += text(kWidth / 2, 44, subtitle, "middle", 12);

  s += axes(speedup, std::max(1.0, std::ceil(speedup.y_max / 8)), "speedup",
            [](double v) { return fmt("%.0f", v); });
  s += line(speedup.x(1), speedup.y(1), speedup.x(max_threads), speedup.y(max_threads), kIdeal, 1.5,
            "6 4");
  s += series(
      speedup, points, [](const ScalePoint& p) { return p.speedup; },
      [](double v) { return fmt("%.2fx", v); }, kWall, -10);

  auto percent = [](double v) { return fmt("%.1f%%", 100 * v); };
  s +=
      axes(efficiency, 0.2, "parallel efficiency", [](double v) { return fmt("%.0f%%", 100 * v); });
  s += line(efficiency.x(1), efficiency.y(1), efficiency.x(max_threads), efficiency.y(1), kIdeal,
            1.5, "6 4");
  s += series(
      efficiency, points, [](const ScalePoint& p) { return p.work_efficiency; }, percent, kCpu, 18);
  s += series(
      efficiency, points, [](const ScalePoint& p) { return p.efficiency; }, percent, kWall, -10);

  const double ly = kHeight - 14;
  s += legend_entry(70, ly, kWall, nullptr, "wall clock (median of the repeats)");
  s += legend_entry(345, ly, kCpu, nullptr, "by CPU time (efficiency only)");
  s += legend_entry(600, ly, kIdeal, "6 4", "ideal");
  return s + "</svg>\n";
}

}  // namespace snee
