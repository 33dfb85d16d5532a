#include "bench/src/bench_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <set>

namespace rp::bench {

using app::pipeline_rank;

namespace {

// Ten distinguishable colours (passes, then devices).
const char* const kPalette[] = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
                                "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac"};
constexpr size_t kPaletteSize = sizeof kPalette / sizeof kPalette[0];
const char* const kDashes[] = {"", "6,3", "2,3", "8,3,2,3"};

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

// Short tick label: up to 5 significant digits, no trailing zeros (1500, not 1.5e+03).
std::string tick_label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.5g", v);
  return buf;
}

// 1-2-5 steps covering [lo, hi] on a linear axis, about `count` of them.
double nice_step(double range, int count) {
  double raw = range / count, p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10.0 * p;
}

// Log-axis ticks: every 1, 2, 5 x 10^n inside [lo, hi].
std::vector<double> log_ticks(double lo, double hi) {
  std::vector<double> ticks;
  for (double decade = std::pow(10.0, std::floor(std::log10(lo))); decade <= hi; decade *= 10.0)
    for (double m : {1.0, 2.0, 5.0})
      if (m * decade >= lo && m * decade <= hi) ticks.push_back(m * decade);
  return ticks;
}

std::string short_name(const DeviceResult& d) {
  std::string n = d.name.size() > 26 ? d.name.substr(0, 25) + "~" : d.name;
  return str_cat("[", std::to_string(d.index), "] ", n);
}

std::string size_text(uint32_t w, uint32_t h) {
  return std::to_string(w) + "x" + std::to_string(h);
}

}  // namespace

double line_chart(SvgWriter& svg, double x0, double y0, double w, double h,
                  const std::string& title, const std::string& x_title,
                  const std::vector<Series>& series,
                  const std::function<std::string(double)>& x_label_of) {
  svg.text(x0 + w / 2, y0 - 12, title, 14, "middle");
  std::set<double> xs;
  double ylo = 1e300, yhi = 0.0;
  for (const Series& s : series)
    for (const auto& [x, y] : s.points) {
      xs.insert(x);
      ylo = std::min(ylo, y);
      yhi = std::max(yhi, y);
    }
  svg.rect(x0, y0, w, h, "#fbfbfb", "#999");
  if (xs.size() < 2) {
    svg.text(x0 + w / 2, y0 + h / 2, "needs at least two values to draw a line", 12, "middle",
             "#777");
    return 0.0;
  }
  double xlo = *xs.begin() / 1.15, xhi = *xs.rbegin() * 1.15;
  ylo /= 1.25;
  yhi *= 1.25;
  auto px = [&](double x) { return x0 + w * std::log(x / xlo) / std::log(xhi / xlo); };
  auto py = [&](double y) { return y0 + h - h * std::log(y / ylo) / std::log(yhi / ylo); };
  for (double t : log_ticks(ylo, yhi)) {
    svg.line(x0, py(t), x0 + w, py(t), "#e4e4e4");
    svg.text(x0 - 6, py(t) + 4, tick_label(t), 11, "end");
  }
  for (double x : xs) {
    svg.line(px(x), y0 + h, px(x), y0 + h + 5, "#999");
    svg.text(px(x), y0 + h + 18, x_label_of(x), 11, "middle");
  }
  svg.text(x0 + w / 2, y0 + h + 36, x_title, 12, "middle");
  svg.text(x0, y0 - 30, "frame ms (log)", 11, "start", "#555");
  for (const Series& s : series) {
    std::vector<std::pair<double, double>> pts;
    for (const auto& [x, y] : s.points) pts.push_back({px(x), py(y)});
    if (pts.size() >= 2) svg.polyline(pts, s.colour, 2.0, s.dash);
    for (const auto& [x, y] : pts) svg.circle(x, y, 3.0, s.colour);
  }
  double ly = y0 + h + 56;
  for (const Series& s : series) {
    svg.line(x0, ly - 4, x0 + 26, ly - 4, s.colour, 2.0, s.dash);
    svg.text(x0 + 32, ly, s.label, 11);
    ly += 16;
  }
  return ly - (y0 + h);
}

const char* chart_colour(size_t i) { return kPalette[i % kPaletteSize]; }

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

SvgWriter::SvgWriter(double width, double height) : width_(width), height_(height) {}

void SvgWriter::rect(double x, double y, double w, double h, const std::string& fill,
                     const std::string& stroke) {
  body_ += "<rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(w) + "\" height=\"" +
           num(h) + "\" fill=\"" + fill + "\" stroke=\"" + stroke + "\"/>\n";
}

void SvgWriter::line(double x0, double y0, double x1, double y1, const std::string& stroke,
                     double width, const std::string& dash) {
  body_ += "<line x1=\"" + num(x0) + "\" y1=\"" + num(y0) + "\" x2=\"" + num(x1) + "\" y2=\"" +
           num(y1) + "\" stroke=\"" + stroke + "\" stroke-width=\"" + num(width) + "\"" +
           (dash.empty() ? "" : " stroke-dasharray=\"" + dash + "\"") + "/>\n";
}

void SvgWriter::polyline(const std::vector<std::pair<double, double>>& points,
                         const std::string& stroke, double width, const std::string& dash) {
  std::string pts;
  for (const auto& [x, y] : points) pts += str_cat(pts.empty() ? "" : " ", num(x), ",", num(y));
  body_ += "<polyline points=\"" + pts + "\" fill=\"none\" stroke=\"" + stroke +
           "\" stroke-width=\"" + num(width) + "\"" +
           (dash.empty() ? "" : " stroke-dasharray=\"" + dash + "\"") + "/>\n";
}

void SvgWriter::circle(double x, double y, double r, const std::string& fill) {
  body_ += "<circle cx=\"" + num(x) + "\" cy=\"" + num(y) + "\" r=\"" + num(r) + "\" fill=\"" +
           fill + "\"/>\n";
}

void SvgWriter::text(double x, double y, const std::string& s, double size,
                     const std::string& anchor, const std::string& fill) {
  body_ += "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" font-size=\"" + num(size) +
           "\" text-anchor=\"" + anchor + "\" fill=\"" + fill + "\">" + xml_escape(s) +
           "</text>\n";
}

std::string SvgWriter::finish() const {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
         "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" +
         num(width_) + "\" height=\"" + num(height_) + "\" viewBox=\"0 0 " + num(width_) + " " +
         num(height_) + "\" font-family=\"DejaVu Sans, Arial, sans-serif\">\n" +
         "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n" + body_ + "</svg>\n";
}

std::string matrix_svg(const BenchMatrix& m) {
  // Bars: one per (device that ran, run).
  struct Bar {
    std::string label;
    const RunResult* run;
  };
  std::vector<Bar> bars;
  std::vector<std::string> skipped;
  for (const DeviceResult& d : m.devices) {
    if (!d.ok()) skipped.push_back(short_name(d));
    for (const RunResult& r : d.runs)
      bars.push_back({short_name(d) + "  " + size_text(r.width, r.height) + " " +
                          std::to_string(r.voxels) + "^3",
                      &r});
  }
  std::vector<std::string> passes;
  for (const Bar& b : bars)
    for (const PassResult& p : b.run->passes)
      if (std::find(passes.begin(), passes.end(), p.name) == passes.end())
        passes.push_back(p.name);
  std::stable_sort(passes.begin(), passes.end(), [](const std::string& a, const std::string& b) {
    return pipeline_rank(a) < pipeline_rank(b);
  });

  // Line series: frame time against pixels per (device, voxels); against voxels per (device, size).
  std::vector<Series> by_pixels, by_voxels;
  size_t device_no = 0;
  for (const DeviceResult& d : m.devices) {
    if (!d.ok()) continue;
    const std::string colour = kPalette[device_no++ % kPaletteSize];
    size_t dash_no = 0;
    for (uint32_t v : m.voxels) {
      Series s{short_name(d) + ", " + std::to_string(v) + "^3 voxels", colour,
               kDashes[dash_no++ % 4], {}};
      for (const RunResult& r : d.runs)
        if (r.voxels == v) s.points.push_back({r.pixels(), r.frame.median_ms});
      if (!s.points.empty()) by_pixels.push_back(s);
    }
    dash_no = 0;
    for (const auto& [w, h] : m.sizes) {
      Series s{short_name(d) + ", " + size_text(w, h), colour, kDashes[dash_no++ % 4], {}};
      for (const RunResult& r : d.runs)
        if (r.width == w && r.height == h)
          s.points.push_back({double(r.voxels) * r.voxels * r.voxels, r.frame.median_ms});
      if (!s.points.empty()) by_voxels.push_back(s);
    }
  }
  for (std::vector<Series>* list : {&by_pixels, &by_voxels})
    for (Series& s : *list) std::sort(s.points.begin(), s.points.end());

  const double width = 1000, bar_h = 18, bar_gap = 6, label_w = 300;
  const double bars_top = 110;
  const double bars_bottom = bars_top + double(bars.size()) * (bar_h + bar_gap);
  const double legend_rows = std::ceil(double(passes.size()) / 6.0);
  const double lines_top = bars_bottom + 50 + legend_rows * 18 + 60;
  const double lines_h = 300;
  const double legend_h = 60 + 16.0 * double(std::max(by_pixels.size(), by_voxels.size()));
  SvgWriter svg(width, lines_top + lines_h + legend_h + 20);

  svg.text(20, 28, "rolypoly bench: scene " + m.scene + ", seed " + std::to_string(m.seed) + ", " +
                       std::to_string(m.frames) + " measured frames (" +
                       std::to_string(m.warmup) + " warm-up)",
           16);
  std::string skip_line = skipped.empty() ? "" : "skipped (failed): ";
  for (size_t i = 0; i < skipped.size(); ++i) skip_line += (i ? ", " : "") + skipped[i];
  if (!skip_line.empty()) svg.text(20, 48, skip_line, 12, "start", "#b00");
  svg.text(20, bars_top - 30, "Per-pass device time (median ms, stacked) per device and run", 14);

  double max_total = 0.0;
  for (const Bar& b : bars) {
    double total = 0.0;
    for (const PassResult& p : b.run->passes) total += p.ms.median_ms;
    max_total = std::max(max_total, total);
  }
  const double plot_x = label_w, plot_w = width - label_w - 40;
  if (max_total > 0.0) {
    double step = nice_step(max_total, 5), axis_max = std::ceil(max_total / step) * step;
    auto sx = [&](double ms) { return plot_x + plot_w * ms / axis_max; };
    for (double t = 0.0; t <= axis_max + step * 0.01; t += step) {
      svg.line(sx(t), bars_top - 8, sx(t), bars_bottom, "#e4e4e4");
      svg.text(sx(t), bars_bottom + 16, tick_label(t), 11, "middle");
    }
    svg.text(plot_x + plot_w / 2, bars_bottom + 34, "ms per frame (sum of pass medians)", 12,
             "middle");
    for (size_t i = 0; i < bars.size(); ++i) {
      double y = bars_top + double(i) * (bar_h + bar_gap), x = 0.0;
      svg.text(plot_x - 8, y + bar_h - 5, bars[i].label, 11, "end");
      for (const PassResult& p : bars[i].run->passes) {
        size_t c = size_t(std::find(passes.begin(), passes.end(), p.name) - passes.begin());
        svg.rect(sx(x), y, sx(x + p.ms.median_ms) - sx(x), bar_h, kPalette[c % kPaletteSize]);
        x += p.ms.median_ms;
      }
    }
  } else {
    svg.text(plot_x, bars_top + 10, "no device completed a run", 12, "start", "#b00");
  }
  for (size_t i = 0; i < passes.size(); ++i) {
    double x = 20 + double(i % 6) * 160, y = bars_bottom + 54 + std::floor(double(i) / 6.0) * 18;
    svg.rect(x, y - 10, 12, 12, kPalette[i % kPaletteSize]);
    svg.text(x + 18, y, passes[i], 12);
  }

  line_chart(svg, 80, lines_top, 380, lines_h, "Frame time against resolution",
             "pixels per frame (log)", by_pixels, [](double px) {
               double side = std::sqrt(px);
               return std::fabs(side - std::round(side)) < 1e-6
                          ? std::to_string(long(std::round(side))) + "^2"
                          : tick_label(px);
             });
  line_chart(svg, 580, lines_top, 380, lines_h, "Frame time against voxel count",
             "voxels in the GI volume (log)", by_voxels, [](double n) {
               return std::to_string(long(std::round(std::cbrt(n)))) + "^3";
             });
  return svg.finish();
}

}  // namespace rp::bench
