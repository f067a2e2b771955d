// Line plots in the style of the paper's figures, drawn once with cairo and written both as PNG
// and as SVG (the same drawing code on two cairo surfaces).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace dyncc::sim {

/// A line. Samples are (x[i], y[i]) for i below the shorter length; a NaN or infinite sample
/// breaks the line. An empty label leaves the series out of the legend.
struct Series {
  std::string label;
  std::vector<double> x, y;
  bool dashed = false;
};

/// One set of axes. `shaded` are x intervals drawn as light bands (e.g. contact, holding).
struct Panel {
  std::string title;
  std::string y_label;
  std::vector<Series> series;
  std::vector<std::pair<double, double>> shaded;
};

/// Panels stacked vertically, sharing the x axis. The image is `width` wide and a fixed margin
/// (the title above, the shared x axis below) plus `panel_height` per panel high.
struct Figure {
  std::string title;
  std::string x_label = "time (s)";
  std::vector<Panel> panels;
  int width = 900;  // px (PNG) / pt (SVG)
  int panel_height = 220;
};

/// Writes `stem`.png and `stem`.svg. Throws std::runtime_error when a file cannot be written,
/// std::invalid_argument when the width or the panel height is not positive.
void write_figure(const Figure& figure, const std::filesystem::path& stem);

}  // namespace dyncc::sim
