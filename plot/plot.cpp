// The figures are drawn by one function on two cairo surfaces (image for PNG, SVG), so the quick
// look and the vector figure in the report cannot drift apart. All sizes are in px for the PNG,
// which cairo's SVG surface takes as pt, so both files have the same layout.
#include "plot.hpp"

#include <cairo-svg.h>
#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

// LeakSanitizer reads its built-in suppressions from this hook (sanitized builds only; elsewhere
// nothing calls it). It lives here, with the drawing that causes the allocations, so every
// program that plots (dyncc, dyncc-sim, the tests) carries it: write_figure pulls this object
// out of the static library. cairo's font cache and fontconfig's configuration are allocated
// on the first text drawn and live until exit, and fontconfig links the parts of a pattern by
// offsets rather than pointers, so LeakSanitizer cannot see they are still reachable.
extern "C" const char* __lsan_default_suppressions();   // NOLINT(bugprone-reserved-identifier)
extern "C" const char* __lsan_default_suppressions() {  // NOLINT(bugprone-reserved-identifier)
  return "leak:libfontconfig.so\n";
}

namespace dyncc::plot {
namespace {

// The image is  width  x  kTitleHeight + panels * panel_height + kXAxisHeight : each panel owns
// one slot of panel_height (its title above the frame, a gap below it), the figure title sits
// above the first slot, and the shared x tick labels and x label below the last one.
constexpr double kTitleHeight = 40;
constexpr double kXAxisHeight = 50;
constexpr double kLeftMargin = 84;  // room for the y tick labels and the rotated y label
constexpr double kRightMargin = 20;
constexpr double kPanelTitleHeight = 22;
constexpr double kPanelGap = 10;  // frames of neighbouring panels must not touch

constexpr double kLineWidth = 1.3;
constexpr double kMarkerRadius = 1.6;
constexpr double kMarkerOpacity = 0.55;
constexpr double kTickLength = 4;
// Beyond this many ticks the labels would overlap anyway; it also bounds the tick loop for
// degenerate ranges (a span of a few ulp).
constexpr long long kMaxTicks = 40;
// Data beyond this magnitude is clamped out of the axis range so that hi - lo and the padding
// stay finite; such points still get drawn, at the edge.
constexpr double kLargestAxisValue = 1e300;
// cairo stores coordinates as 24.8 fixed point; a far-off point must not wrap around.
constexpr double kLargestCoordinate = 1e5;

struct Rgb {
  double r = 0, g = 0, b = 0;
};

// Colour-blind-safe and distinguishable in greyscale print (Okabe-Ito, black left out since the
// frame and text are black). A series keeps its colour by index, so the same quantity has the
// same colour in every panel.
constexpr std::array<Rgb, 7> kPalette{{
    {0.000, 0.447, 0.698},  // blue
    {0.835, 0.369, 0.000},  // vermillion
    {0.000, 0.620, 0.451},  // bluish green
    {0.800, 0.475, 0.655},  // reddish purple
    {0.902, 0.624, 0.000},  // orange
    {0.337, 0.706, 0.914},  // sky blue
    {0.941, 0.894, 0.259},  // yellow
}};
constexpr Rgb kText{0.10, 0.10, 0.10};
constexpr Rgb kFrame{0.15, 0.15, 0.15};
constexpr Rgb kGrid{0.86, 0.86, 0.86};
constexpr Rgb kBand{0.91, 0.91, 0.91};

struct Range {
  double lo = 0, hi = 1;
};

/// Extent of the finite values seen; NaN and inf are gaps in a signal, not data.
class Extent {
 public:
  void add(double v) {
    if (!std::isfinite(v)) return;
    v = std::clamp(v, -kLargestAxisValue, kLargestAxisValue);
    lo_ = std::min(lo_, v);
    hi_ = std::max(hi_, v);
  }
  [[nodiscard]] bool empty() const { return lo_ > hi_; }
  [[nodiscard]] Range range() const { return {lo_, hi_}; }

 private:
  double lo_ = std::numeric_limits<double>::infinity();
  double hi_ = -std::numeric_limits<double>::infinity();
};

/// A constant signal (a joint at rest, a saturated torque) would give a zero-height axis and a
/// division by zero in the mapping, so it is widened around its value; a real span gets
/// `pad` of it on either side so the extremes do not lie on the frame.
Range axis_range(const Extent& extent, double pad) {
  if (extent.empty()) return {};
  Range r = extent.range();
  const double span = r.hi - r.lo;
  if (span > 0) return {r.lo - pad * span, r.hi + pad * span};
  const double half = r.lo == 0 ? 1.0 : 0.1 * std::abs(r.lo);
  return {r.lo - half, r.hi + half};
}

void set_colour(cairo_t* cr, const Rgb& c) { cairo_set_source_rgb(cr, c.r, c.g, c.b); }

/// 1-2-5 steps: tick values a reader can interpolate between at a glance.
double nice_step(double span, double target_ticks) {
  const double raw = span / std::max(target_ticks, 1.0);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / magnitude;
  const double mantissa = f < 1.5 ? 1 : f < 3.5 ? 2 : f < 7.5 ? 5 : 10;
  return mantissa * magnitude;
}

struct Ticks {
  std::vector<double> values;
  std::vector<std::string> labels;
};

/// Labels with as many decimals as the step needs, so that 0.25 0.50 0.75 line up and no tick
/// reads "0.30000000000000004"; very large or very fine scales switch to exponent notation.
std::string tick_label(double value, double step, double largest_magnitude) {
  const int step_exponent = static_cast<int>(std::floor(std::log10(step)));
  const int decimals = std::max(0, -step_exponent);
  if (decimals <= 6 && largest_magnitude < 1e6) return fmt::format("{:.{}f}", value, decimals);
  const int value_exponent = largest_magnitude > 0 ? static_cast<int>(std::floor(std::log10(largest_magnitude))) : 0;
  const int digits = std::clamp(value_exponent - step_exponent + 1, 1, 17);
  return fmt::format("{:.{}g}", value, digits);
}

Ticks make_ticks(const Range& range, double target_ticks) {
  Ticks ticks;
  const double step = nice_step(range.hi - range.lo, target_ticks);
  if (!std::isfinite(step) || step <= 0) return ticks;
  // Tolerance so that a range ending exactly on a tick (0 to 10) keeps the end ticks despite
  // rounding in lo/step.
  const double first = std::ceil(range.lo / step - 1e-9);
  const double last = std::floor(range.hi / step + 1e-9);
  if (!(last - first < static_cast<double>(kMaxTicks))) return ticks;
  const auto k0 = static_cast<long long>(first);
  const auto k1 = static_cast<long long>(last);
  const double largest = std::max(std::abs(range.lo), std::abs(range.hi));
  for (long long k = k0; k <= k1; ++k) {
    // k * step rather than accumulating: no drift, and k = 0 gives 0, never "-0".
    const double value = static_cast<double>(k) * step;
    ticks.values.push_back(value);
    ticks.labels.push_back(tick_label(value, step, largest));
  }
  return ticks;
}

/// Labelled positions given by the caller, in place of numbers; non-finite ones are dropped.
Ticks given_ticks(const std::vector<std::pair<double, std::string>>& given) {
  Ticks ticks;
  for (const auto& [value, label] : given) {
    if (!std::isfinite(value)) continue;
    ticks.values.push_back(std::clamp(value, -kLargestAxisValue, kLargestAxisValue));
    ticks.labels.push_back(label);
  }
  return ticks;
}

/// Where a panel's frame is and which data rectangle it shows.
struct Axes {
  double left = 0, top = 0, width = 1, height = 1;
  Range x, y;

  [[nodiscard]] double right() const { return left + width; }
  [[nodiscard]] double bottom() const { return top + height; }
  [[nodiscard]] double px(double v) const {
    return std::clamp(left + (v - x.lo) / (x.hi - x.lo) * width, -kLargestCoordinate, kLargestCoordinate);
  }
  [[nodiscard]] double py(double v) const {
    return std::clamp(bottom() - (v - y.lo) / (y.hi - y.lo) * height, -kLargestCoordinate, kLargestCoordinate);
  }
};

enum class Weight { Normal, Bold };

void set_font(cairo_t* cr, double size, Weight weight = Weight::Normal) {
  cairo_select_font_face(cr, "sans", CAIRO_FONT_SLANT_NORMAL,
                         weight == Weight::Bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

double text_width(cairo_t* cr, const std::string& text) {
  cairo_text_extents_t extents{};
  cairo_text_extents(cr, text.c_str(), &extents);
  return extents.x_advance;
}

/// Draws `text` with the point (x, y) at fraction `align_x` of its advance (0 left, 0.5 centre,
/// 1 right) and on its baseline, or, with `centre_y`, at the middle of its ink so that numbers
/// sit level with the tick they label.
void show_text(cairo_t* cr, const std::string& text, double x, double y, double align_x, bool centre_y = false) {
  if (text.empty()) return;
  cairo_text_extents_t extents{};
  cairo_text_extents(cr, text.c_str(), &extents);
  const double baseline = centre_y ? y - (extents.y_bearing + extents.height / 2) : y;
  cairo_move_to(cr, x - align_x * extents.x_advance, baseline);
  cairo_show_text(cr, text.c_str());
}

/// The series as one path: a non-finite sample ends the current piece and the next finite one
/// starts a new piece, so a gap in the data is a gap in the line, not a jump across it. An
/// isolated finite sample becomes a zero-length piece, which the round cap draws as a dot.
void trace_series(cairo_t* cr, const Series& series, const Axes& axes) {
  const std::size_t n = std::min(series.x.size(), series.y.size());
  bool in_piece = false;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = series.x[i], y = series.y[i];
    if (!std::isfinite(x) || !std::isfinite(y)) {
      in_piece = false;
      continue;
    }
    const double px = axes.px(x), py = axes.py(y);
    if (!in_piece) {
      cairo_move_to(cr, px, py);
      in_piece = true;
    }
    cairo_line_to(cr, px, py);
  }
}

/// A scatter: one dot per finite sample, as sub-paths of one path filled at once.
void trace_markers(cairo_t* cr, const Series& series, const Axes& axes) {
  const std::size_t n = std::min(series.x.size(), series.y.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(series.x[i]) || !std::isfinite(series.y[i])) continue;
    cairo_new_sub_path(cr);
    cairo_arc(cr, axes.px(series.x[i]), axes.py(series.y[i]), kMarkerRadius, 0, 2 * std::numbers::pi);
  }
}

void set_series_style(cairo_t* cr, const Series& series, std::size_t index) {
  const Rgb& c = kPalette[index % kPalette.size()];
  // Dots of a dense scatter overlap: translucent ones show where the samples crowd.
  cairo_set_source_rgba(cr, c.r, c.g, c.b, series.markers ? kMarkerOpacity : 1.0);
  cairo_set_line_width(cr, kLineWidth);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  // The round caps lengthen each dash by a line width, hence the long gap.
  const std::array<double, 2> dash{5.0, 4.0};
  cairo_set_dash(cr, dash.data(), series.dashed ? static_cast<int>(dash.size()) : 0, 0);
}

void draw_bands(cairo_t* cr, const Panel& panel, const Axes& axes) {
  set_colour(cr, kBand);
  for (auto [a, b] : panel.shaded) {
    if (std::isnan(a) || std::isnan(b)) continue;
    if (a > b) std::swap(a, b);
    // Clamped to the axis so that an interval open to one side (-inf, t) still shows.
    a = std::clamp(a, axes.x.lo, axes.x.hi);
    b = std::clamp(b, axes.x.lo, axes.x.hi);
    if (b <= a) continue;
    const double left = axes.px(a);
    cairo_rectangle(cr, left, axes.top, axes.px(b) - left, axes.height);
  }
  cairo_fill(cr);
}

void draw_grid(cairo_t* cr, const Axes& axes, const Ticks& x_ticks, const Ticks& y_ticks) {
  set_colour(cr, kGrid);
  cairo_set_line_width(cr, 0.6);
  for (const double v : x_ticks.values) {
    cairo_move_to(cr, axes.px(v), axes.top);
    cairo_line_to(cr, axes.px(v), axes.bottom());
  }
  for (const double v : y_ticks.values) {
    cairo_move_to(cr, axes.left, axes.py(v));
    cairo_line_to(cr, axes.right(), axes.py(v));
  }
  cairo_stroke(cr);
}

void draw_legend(cairo_t* cr, const Panel& panel, const Axes& axes) {
  std::vector<std::size_t> entries;
  for (std::size_t i = 0; i < panel.series.size(); ++i) {
    if (!panel.series[i].label.empty()) entries.push_back(i);
  }
  if (entries.empty()) return;

  constexpr double kPad = 6, kRow = 15, kSample = 24, kSampleGap = 6, kInset = 8;
  set_font(cr, 10);
  double text = 0;
  for (const std::size_t i : entries) text = std::max(text, text_width(cr, panel.series[i].label));
  const double box_width = kPad + kSample + kSampleGap + text + kPad;
  const double box_height = 2 * kPad + kRow * static_cast<double>(entries.size()) - 3;
  const double box_left = axes.right() - kInset - box_width;
  const double box_top = axes.top + kInset;

  // Opaque enough to read over the lines, translucent enough to show what it covers.
  cairo_rectangle(cr, box_left, box_top, box_width, box_height);
  cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
  cairo_fill_preserve(cr);
  cairo_set_source_rgb(cr, 0.7, 0.7, 0.7);
  cairo_set_line_width(cr, 0.8);
  cairo_stroke(cr);

  double row_middle = box_top + kPad + kRow / 2 - 1.5;
  for (const std::size_t i : entries) {
    const Series& series = panel.series[i];
    set_series_style(cr, series, i);
    if (series.markers) {
      cairo_arc(cr, box_left + kPad + kSample / 2, row_middle, 2 * kMarkerRadius, 0, 2 * std::numbers::pi);
      cairo_fill(cr);
    } else {
      cairo_move_to(cr, box_left + kPad, row_middle);
      cairo_line_to(cr, box_left + kPad + kSample, row_middle);
      cairo_stroke(cr);
    }
    cairo_set_dash(cr, nullptr, 0, 0);
    set_colour(cr, kText);
    show_text(cr, series.label, box_left + kPad + kSample + kSampleGap, row_middle, 0, true);
    row_middle += kRow;
  }
}

void draw_panel(cairo_t* cr, const Panel& panel, const Axes& axes, const Ticks& x_ticks, bool last) {
  Extent y_extent;
  for (const Series& series : panel.series) {
    const std::size_t n = std::min(series.x.size(), series.y.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (std::isfinite(series.x[i])) y_extent.add(series.y[i]);
    }
  }
  Axes a = axes;
  a.y = axis_range(y_extent, 0.05);
  const Ticks y_ticks = make_ticks(a.y, a.height / 40);

  cairo_save(cr);
  cairo_rectangle(cr, a.left, a.top, a.width, a.height);
  cairo_clip(cr);
  draw_bands(cr, panel, a);
  draw_grid(cr, a, x_ticks, y_ticks);
  for (std::size_t i = 0; i < panel.series.size(); ++i) {
    const Series& series = panel.series[i];
    set_series_style(cr, series, i);
    if (series.markers) {
      trace_markers(cr, series, a);
      cairo_fill(cr);
    } else {
      trace_series(cr, series, a);
      cairo_stroke(cr);
    }
  }
  cairo_set_dash(cr, nullptr, 0, 0);
  draw_legend(cr, panel, a);
  cairo_restore(cr);

  set_colour(cr, kFrame);
  cairo_set_line_width(cr, 1.0);
  cairo_rectangle(cr, a.left, a.top, a.width, a.height);
  for (const double v : x_ticks.values) {
    cairo_move_to(cr, a.px(v), a.bottom());
    cairo_line_to(cr, a.px(v), a.bottom() + kTickLength);
  }
  for (const double v : y_ticks.values) {
    cairo_move_to(cr, a.left, a.py(v));
    cairo_line_to(cr, a.left - kTickLength, a.py(v));
  }
  cairo_stroke(cr);

  set_colour(cr, kText);
  set_font(cr, 10);
  for (std::size_t i = 0; i < y_ticks.values.size(); ++i) {
    show_text(cr, y_ticks.labels[i], a.left - kTickLength - 3, a.py(y_ticks.values[i]), 1, true);
  }
  // The x axis is shared: its numbers only under the last panel.
  if (last) {
    for (std::size_t i = 0; i < x_ticks.values.size(); ++i) {
      show_text(cr, x_ticks.labels[i], a.px(x_ticks.values[i]), a.bottom() + kTickLength + 13, 0.5);
    }
  }
  set_font(cr, 12, Weight::Bold);
  show_text(cr, panel.title, a.left, a.top - 7, 0);
  if (!panel.y_label.empty()) {
    set_font(cr, 11);
    cairo_save(cr);
    cairo_translate(cr, 18, a.top + a.height / 2);
    cairo_rotate(cr, -std::numbers::pi / 2);
    show_text(cr, panel.y_label, 0, 0, 0.5);
    cairo_restore(cr);
  }
}

void draw_figure(cairo_t* cr, const Figure& figure, double height) {
  // Grey antialiasing: colour fringes of subpixel text are wrong once the image is scaled in a
  // document. Unhinted metrics: text then measures the same on both surfaces.
  cairo_font_options_t* options = cairo_font_options_create();
  cairo_font_options_set_antialias(options, CAIRO_ANTIALIAS_GRAY);
  cairo_font_options_set_hint_metrics(options, CAIRO_HINT_METRICS_OFF);
  cairo_set_font_options(cr, options);
  cairo_font_options_destroy(options);

  const auto width = static_cast<double>(figure.width);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_rectangle(cr, 0, 0, width, height);
  cairo_fill(cr);

  set_colour(cr, kText);
  set_font(cr, 15, Weight::Bold);
  show_text(cr, figure.title, width / 2, 26, 0.5);
  if (figure.panels.empty()) return;

  Extent x_extent;
  for (const Panel& panel : figure.panels) {
    for (const Series& series : panel.series) {
      const std::size_t n = std::min(series.x.size(), series.y.size());
      for (std::size_t i = 0; i < n; ++i) {
        if (std::isfinite(series.y[i])) x_extent.add(series.x[i]);
      }
    }
  }
  for (const auto& tick : figure.x_ticks) x_extent.add(tick.first);
  // Only bands and no data: show the bands rather than an arbitrary [0, 1].
  if (x_extent.empty()) {
    for (const Panel& panel : figure.panels) {
      for (const auto& [a, b] : panel.shaded) {
        x_extent.add(a);
        x_extent.add(b);
      }
    }
  }

  const auto panel_height = static_cast<double>(figure.panel_height);
  Axes axes;
  // Frames on half pixels: 1 px lines then cover one pixel row instead of blurring over two.
  axes.left = std::round(kLeftMargin) + 0.5;
  axes.width = std::max(1.0, std::round(width - kLeftMargin - kRightMargin));
  axes.height = std::max(1.0, std::round(panel_height - kPanelTitleHeight - kPanelGap));
  // Time axes are tight: the run starts and ends at the frame.
  axes.x = axis_range(x_extent, 0);
  const Ticks x_ticks = figure.x_ticks.empty() ? make_ticks(axes.x, axes.width / 90) : given_ticks(figure.x_ticks);

  for (std::size_t p = 0; p < figure.panels.size(); ++p) {
    const double slot_top = kTitleHeight + panel_height * static_cast<double>(p);
    axes.top = std::round(slot_top + kPanelTitleHeight) + 0.5;
    draw_panel(cr, figure.panels[p], axes, x_ticks, p + 1 == figure.panels.size());
  }

  set_colour(cr, kText);
  set_font(cr, 11);
  const double last_bottom = axes.top + axes.height;
  show_text(cr, figure.x_label, axes.left + axes.width / 2, last_bottom + kTickLength + 34, 0.5);
}

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};
using SurfacePtr = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using ContextPtr = std::unique_ptr<cairo_t, ContextDeleter>;

void check(cairo_status_t status, const std::filesystem::path& file) {
  if (status != CAIRO_STATUS_SUCCESS) {
    throw std::runtime_error(fmt::format("cannot write {}: {}", file.string(), cairo_status_to_string(status)));
  }
}

// cairo records the first error on the surface or the context and then ignores further calls,
// so checking once after drawing catches any failure during it.
void render(cairo_surface_t* surface, const Figure& figure, double height, const std::filesystem::path& file) {
  check(cairo_surface_status(surface), file);
  const ContextPtr cr(cairo_create(surface));
  draw_figure(cr.get(), figure, height);
  check(cairo_status(cr.get()), file);
}

/// `stem` + suffix rather than replace_extension: a stem such as "run.v2" keeps its dot.
std::filesystem::path with_suffix(const std::filesystem::path& stem, const char* suffix) {
  std::filesystem::path file = stem;
  file += suffix;
  return file;
}

}  // namespace

void write_figure(const Figure& figure, const std::filesystem::path& stem) {
  if (figure.width <= 0 || figure.panel_height <= 0) {
    throw std::invalid_argument(fmt::format("figure {}: width and panel height must be positive", stem.string()));
  }
  const double height = kTitleHeight + static_cast<double>(figure.panels.size()) * figure.panel_height + kXAxisHeight;
  if (height > std::numeric_limits<int>::max()) {
    throw std::invalid_argument(fmt::format("figure {}: too many panels", stem.string()));
  }

  const std::filesystem::path png = with_suffix(stem, ".png");
  const SurfacePtr image(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, figure.width, static_cast<int>(height)));
  render(image.get(), figure, height, png);
  check(cairo_surface_write_to_png(image.get(), png.c_str()), png);

  const std::filesystem::path svg = with_suffix(stem, ".svg");
  const SurfacePtr vector(cairo_svg_surface_create(svg.c_str(), figure.width, height));
  render(vector.get(), figure, height, svg);
  // The SVG is only written out when the surface is finished; a full disk shows up here.
  cairo_surface_finish(vector.get());
  check(cairo_surface_status(vector.get()), svg);
}

}  // namespace dyncc::plot
