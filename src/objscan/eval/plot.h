#pragma once
// Small line and bar plots for the benchmark report, written both as SVG (for documents) and as PNG
// (io::Canvas, for quick looks). One layout is computed per plot and rendered to either format, so
// the two files show the same thing.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "objscan/io/canvas.h"

namespace objscan::eval {

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;  // same length
  io::Rgb color = {31, 119, 180};
  bool line = true;      // connect the points
  bool markers = false;  // draw every point as a small dot
  // Highlighted points drawn as red dots on top (e.g. where the robot switched to the next object).
  std::vector<double> highlight_x, highlight_y;

  static PlotSeries Line(std::string label, std::vector<double> x, std::vector<double> y, io::Rgb color) {
    PlotSeries s;
    s.label = std::move(label);
    s.x = std::move(x);
    s.y = std::move(y);
    s.color = color;
    return s;
  }
};

struct LinePlot {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
  std::optional<double> y_min, y_max;  // default: from the data
  std::string highlight_label;         // legend entry of the highlighted points (none when empty)
  std::string note;                    // one line under the plot
};

struct BarSeries {
  std::string label;
  std::vector<double> values;  // one per group; NaN leaves the bar out
  io::Rgb color = {31, 119, 180};
};

struct BarPlot {
  std::string title, y_label;
  std::vector<std::string> groups;
  std::vector<BarSeries> series;
  std::optional<double> y_min, y_max;
  std::string note;
};

// A qualitative palette: colour i (cycling).
io::Rgb PlotColor(int i);

// "Nice" axis ticks (1, 2, 2.5, 5 x 10^k steps) covering [lo, hi], about `target` of them.
std::vector<double> NiceTicks(double lo, double hi, int target = 6);

std::string RenderSvg(const LinePlot& plot);
std::string RenderSvg(const BarPlot& plot);
io::Canvas RenderCanvas(const LinePlot& plot);
io::Canvas RenderCanvas(const BarPlot& plot);

// Writes `<path_stem>.svg` and `<path_stem>.png` atomically; throws InputError naming the file.
void SavePlot(const LinePlot& plot, const std::string& path_stem);
void SavePlot(const BarPlot& plot, const std::string& path_stem);

}  // namespace objscan::eval
