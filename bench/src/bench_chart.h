// The bench matrix as an SVG chart, written by the small writer below (no third-party code):
//  1. per-pass time per device and run: stacked horizontal bars of the pass medians (ms),
//  2. frame time against pixel count: one line per device and voxel resolution (log-log axes,
//     so a power law is a straight line whose slope is the fitted exponent),
//  3. frame time against voxel count: one line per device and image size (log-log).
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "bench/src/bench_matrix.h"

namespace rp::bench {

// Minimal SVG 1.1 document builder: coordinates in px, y down; text is XML-escaped.
class SvgWriter {
 public:
  SvgWriter(double width, double height);
  void rect(double x, double y, double w, double h, const std::string& fill,
            const std::string& stroke = "none");
  void line(double x0, double y0, double x1, double y1, const std::string& stroke,
            double width = 1.0, const std::string& dash = "");
  void polyline(const std::vector<std::pair<double, double>>& points, const std::string& stroke,
                double width, const std::string& dash = "");
  void circle(double x, double y, double r, const std::string& fill);
  // anchor: "start", "middle" or "end".
  void text(double x, double y, const std::string& s, double size = 12.0,
            const std::string& anchor = "start", const std::string& fill = "#222");
  std::string finish() const;  // the complete document

 private:
  double width_, height_;
  std::string body_;
};

// One line of a line_chart: (x, ms) points, x ascending.
struct Series {
  std::string label;
  std::string colour, dash;
  std::vector<std::pair<double, double>> points;
};

// Log-log line chart of `series` in the box (x0, y0, w, h) (y: frame ms); x ticks at the data's
// x values, labelled by `x_label_of`. Returns the height used below the box by the legend.
double line_chart(SvgWriter& svg, double x0, double y0, double w, double h,
                  const std::string& title, const std::string& x_title,
                  const std::vector<Series>& series,
                  const std::function<std::string(double)>& x_label_of);

// The i-th of ten distinguishable colours (wraps).
const char* chart_colour(size_t i);

// "&amp;" etc. for &, <, >, " and '.
std::string xml_escape(const std::string& s);

// The chart of every device that ran (skipped devices are listed as such in the title block).
std::string matrix_svg(const BenchMatrix& matrix);

}  // namespace rp::bench
