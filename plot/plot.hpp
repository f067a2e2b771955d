// Line and scatter plots, drawn once with cairo and written both as PNG and as SVG (the same
// drawing code on two cairo surfaces). Used by the simulation's report (sim/) and the
// diagnosis's report (gen/diagnose/); it depends on nothing else of the project.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace dyncc::plot {

/// A line, or with `markers` a dot per sample and no line (a scatter). Samples are (x[i], y[i])
/// for i below the shorter length; a NaN or infinite sample breaks the line (a scatter skips
/// it). An empty label leaves the series out of the legend.
struct Series {
  std::string label;
  std::vector<double> x, y;
  bool dashed = false;
  bool markers = false;
};

/// One set of axes. `shaded` are x intervals drawn as light bands (e.g. contact, holding).
struct Panel {
  std::string title;
  std::string y_label;
  std::vector<Series> series;
  std::vector<std::pair<double, double>> shaded;
};

/// Panels stacked vertically, sharing the x axis. The image is `width` wide and a fixed margin
/// (the title above, the shared x axis below) plus `panel_height` per panel high. `x_ticks`,
/// when given, replace the automatic x ticks by these labelled positions (categories such as the
/// stages of a waterfall), and the x axis then reaches every one of them.
struct Figure {
  std::string title;
  std::string x_label = "time (s)";
  std::vector<Panel> panels;
  std::vector<std::pair<double, std::string>> x_ticks;
  int width = 900;  // px (PNG) / pt (SVG)
  int panel_height = 220;
};

/// Writes `stem`.png and `stem`.svg. Throws std::runtime_error when a file cannot be written,
/// std::invalid_argument when the width or the panel height is not positive.
void write_figure(const Figure& figure, const std::filesystem::path& stem);

}  // namespace dyncc::plot
