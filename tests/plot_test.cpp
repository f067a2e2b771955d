// plot/: write_figure checked by properties of the files it writes, not against stored images.
// The PNG reads back at the size the layout promises (the width, a fixed margin plus one
// panel_height per panel), a series shows up as coloured pixels (everything else in a figure is
// grey, so colour can only come from the data), a dashed or broken line colours fewer pixels
// than a solid one, a scatter colours only around its samples, labelled x ticks set the x range,
// a band is a light grey; the SVG is well-formed XML of the same size; bad data does not throw
// and an unwritable file does, naming it.
#include "plot.hpp"

#include <cairo.h>
#include <gtest/gtest.h>
#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "temp_path.hpp"

namespace dyncc::plot {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
using SurfacePtr = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;

struct Rgb {
  int r = 0, g = 0, b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

struct Image {
  int width = 0, height = 0;
  std::vector<Rgb> pixels;  // row by row
};

/// The PNG as cairo reads it back; an empty image (and a test failure) when it does not load.
Image read_png(const std::filesystem::path& file) {
  const SurfacePtr surface(cairo_image_surface_create_from_png(file.c_str()));
  Image image;
  const cairo_status_t status = cairo_surface_status(surface.get());
  if (status != CAIRO_STATUS_SUCCESS) {
    ADD_FAILURE() << file << " does not load: " << cairo_status_to_string(status);
    return image;
  }
  const cairo_format_t format = cairo_image_surface_get_format(surface.get());
  if (format != CAIRO_FORMAT_ARGB32 && format != CAIRO_FORMAT_RGB24) {
    ADD_FAILURE() << file << " loads in an unexpected pixel format " << format;
    return image;
  }
  cairo_surface_flush(surface.get());
  image.width = cairo_image_surface_get_width(surface.get());
  image.height = cairo_image_surface_get_height(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  const unsigned char* data = cairo_image_surface_get_data(surface.get());
  image.pixels.reserve(static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      std::uint32_t word = 0;  // native-endian 0xAARRGGBB; the figure is opaque, so no unpremultiplying
      std::memcpy(&word, data + static_cast<std::ptrdiff_t>(y) * stride + static_cast<std::ptrdiff_t>(x) * 4, 4);
      image.pixels.push_back({static_cast<int>((word >> 16) & 0xffU), static_cast<int>((word >> 8) & 0xffU),
                              static_cast<int>(word & 0xffU)});
    }
  }
  return image;
}

/// Clearly not a grey: frame, grid, text and bands are all greys, the palette is not.
bool coloured(const Rgb& p) { return std::max({p.r, p.g, p.b}) - std::min({p.r, p.g, p.b}) > 60; }

long count_coloured(const Image& image) {
  return static_cast<long>(std::count_if(image.pixels.begin(), image.pixels.end(), coloured));
}

long count_differing(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height) {
    ADD_FAILURE() << "images of different sizes";
    return 0;
  }
  long n = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) n += a.pixels[i] == b.pixels[i] ? 0 : 1;
  return n;
}

Series sampled(const std::string& label, double (*f)(double), bool dashed = false) {
  Series s{label, {}, {}, dashed};
  for (int i = 0; i <= 200; ++i) {
    const double t = 0.05 * i;
    s.x.push_back(t);
    s.y.push_back(f(t));
  }
  return s;
}

Series horizontal(const std::string& label, double level, bool dashed = false) {
  Series s{label, {}, {}, dashed};
  for (int i = 0; i <= 200; ++i) {
    s.x.push_back(0.05 * i);
    s.y.push_back(level);
  }
  return s;
}

Figure two_panels() {
  Figure figure;
  figure.title = "Tele-operation, free motion";
  Panel angles{"joint 1", "q (rad)", {}, {{2.0, 3.5}}};
  angles.series.push_back(sampled("master", [](double t) { return std::sin(t); }));
  angles.series.push_back(sampled(
      "slave", [](double t) { return 0.9 * std::sin(t - 0.2); }, true));
  Panel torques{"torque", "tau (N m)", {}, {}};
  torques.series.push_back(sampled("tau 1", [](double t) { return 0.02 * std::cos(3 * t); }));
  figure.panels = {angles, torques};
  return figure;
}

class Plot : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = dyncc::test::temp_path("figures");
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }

  /// Writes the figure under `name` and reads its PNG back.
  Image written(const Figure& figure, const std::string& name) {
    write_figure(figure, dir_ / name);
    return read_png(dir_ / (name + ".png"));
  }

  std::filesystem::path dir_;
};

TEST_F(Plot, WritesBothFiles) {
  write_figure(two_panels(), dir_ / "figure");
  EXPECT_TRUE(std::filesystem::is_regular_file(dir_ / "figure.png"));
  EXPECT_TRUE(std::filesystem::is_regular_file(dir_ / "figure.svg"));
  EXPECT_GT(std::filesystem::file_size(dir_ / "figure.png"), 0U);
  EXPECT_GT(std::filesystem::file_size(dir_ / "figure.svg"), 0U);
}

TEST_F(Plot, StemKeepsItsDots) {
  write_figure(two_panels(), dir_ / "run.v2");
  EXPECT_TRUE(std::filesystem::is_regular_file(dir_ / "run.v2.png"));
  EXPECT_TRUE(std::filesystem::is_regular_file(dir_ / "run.v2.svg"));
}

TEST_F(Plot, PngHasTheLayoutSize) {
  const Figure two = two_panels();
  const Image image = written(two, "two");
  EXPECT_EQ(image.width, two.width);
  // Title above and x axis below take room of their own.
  EXPECT_GT(image.height, 2 * two.panel_height);

  Figure three = two;
  three.panels.push_back(two.panels.front());
  EXPECT_EQ(written(three, "three").height, image.height + two.panel_height);

  Figure none = two;
  none.panels.clear();
  EXPECT_EQ(written(none, "none").height, image.height - 2 * two.panel_height);

  Figure taller = two;
  taller.panel_height += 30;
  EXPECT_EQ(written(taller, "taller").height, image.height + 2 * 30);

  Figure narrow = two;
  narrow.width = 640;
  const Image narrow_image = written(narrow, "narrow");
  EXPECT_EQ(narrow_image.width, 640);
  EXPECT_EQ(narrow_image.height, image.height);
}

TEST_F(Plot, SvgIsXmlOfTheSameSize) {
  const Figure figure = two_panels();
  const Image png = written(figure, "figure");
  tinyxml2::XMLDocument svg;
  ASSERT_EQ(svg.LoadFile((dir_ / "figure.svg").c_str()), tinyxml2::XML_SUCCESS) << svg.ErrorStr();
  const tinyxml2::XMLElement* root = svg.RootElement();
  ASSERT_NE(root, nullptr);
  EXPECT_STREQ(root->Name(), "svg");
  EXPECT_NE(root->FirstChildElement(), nullptr);
  // cairo writes the size in pt ("900pt"); the number is the PNG's size in px.
  const char* width = root->Attribute("width");
  const char* height = root->Attribute("height");
  ASSERT_NE(width, nullptr);
  ASSERT_NE(height, nullptr);
  EXPECT_DOUBLE_EQ(std::stod(width), png.width);
  EXPECT_DOUBLE_EQ(std::stod(height), png.height);
}

TEST_F(Plot, FigureWithoutDataIsNotBlankAndHasNoColour) {
  Figure figure;
  figure.title = "empty";
  figure.panels = {Panel{"nothing yet", "q (rad)", {}, {}}};
  const Image image = written(figure, "empty");
  const long drawn = std::count_if(image.pixels.begin(), image.pixels.end(), [](const Rgb& p) {
    return p != Rgb{255, 255, 255};
  });
  EXPECT_GT(drawn, 0) << "frame, ticks and text";
  EXPECT_EQ(count_coloured(image), 0);
}

TEST_F(Plot, SeriesIsDrawnInColourAcrossThePanel) {
  Figure without;
  without.panels = {Panel{"panel", "y", {}, {}}};
  Figure with = without;
  // A constant series also checks that a zero-height range gets an axis the line lies in.
  with.panels[0].series.push_back(horizontal("level", 0.5));
  const Image a = written(without, "without");
  const Image b = written(with, "with");
  EXPECT_GT(count_differing(a, b), 0);
  // The line runs over the whole x range, which is most of the figure's width.
  EXPECT_GT(count_coloured(b), with.width / 2);
}

TEST_F(Plot, DashedAndBrokenLinesColourFewerPixels) {
  Figure solid;
  solid.panels = {Panel{"panel", "y", {horizontal("", 0.5)}, {}}};
  Figure dashed = solid;
  dashed.panels[0].series[0].dashed = true;
  Figure broken = solid;
  std::vector<double>& y = broken.panels[0].series[0].y;
  for (std::size_t i = 60; i < 140; ++i) y[i] = kNaN;  // x in [3, 7): 40 % of the line

  const long full = count_coloured(written(solid, "solid"));
  const long dashes = count_coloured(written(dashed, "dashed"));
  const long pieces = count_coloured(written(broken, "broken"));
  EXPECT_GT(dashes, full / 10);
  EXPECT_LT(dashes, full * 9 / 10);
  EXPECT_GT(pieces, full / 3);
  EXPECT_LT(pieces, full * 3 / 4);
}

/// The columns of the image that hold a coloured pixel: first and last.
std::pair<int, int> coloured_columns(const Image& image) {
  int first = image.width, last = -1;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (!coloured(image.pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
                                 static_cast<std::size_t>(x)])) {
        continue;
      }
      first = std::min(first, x);
      last = std::max(last, x);
    }
  }
  return {first, last};
}

TEST_F(Plot, ScatterColoursOnlyAroundItsSamples) {
  // Two samples far apart: as a line they are joined across the panel, as a scatter they are two
  // dots with white between them.
  Figure line;
  line.panels = {Panel{"panel", "y", {Series{"", {0.0, 10.0}, {0.0, 1.0}}}, {}}};
  Figure scatter = line;
  scatter.panels[0].series[0].markers = true;
  const long joined = count_coloured(written(line, "line"));
  const Image dots = written(scatter, "scatter");
  const long dotted = count_coloured(dots);
  EXPECT_GT(joined, line.width / 2);
  EXPECT_GT(dotted, 0) << "each sample is a visible dot";
  EXPECT_LT(dotted, 100) << "two dots of a few pixels, no line";
  // Many samples: each one a dot, more dots more colour.
  Figure cloud = scatter;
  Series& s = cloud.panels[0].series[0];
  s.x.clear();
  s.y.clear();
  for (int i = 0; i <= 40; ++i) {
    s.x.push_back(0.25 * i);
    s.y.push_back(i % 2 == 0 ? 0.0 : 1.0);
  }
  EXPECT_GT(count_coloured(written(cloud, "cloud")), 10 * dotted);
}

TEST_F(Plot, LabelledTicksSetTheXRange) {
  // A line over x in [0, 1]: alone it spans the frame; with labelled ticks at 0 and 4 it spans a
  // quarter of it.
  Figure automatic;
  automatic.panels = {Panel{"panel", "y", {Series{"", {0.0, 1.0}, {0.5, 0.5}}}, {}}};
  Figure categories = automatic;
  categories.x_ticks = {{0.0, "nominal"}, {4.0, "after"}};
  const auto [a0, a1] = coloured_columns(written(automatic, "automatic"));
  const auto [c0, c1] = coloured_columns(written(categories, "categories"));
  ASSERT_GT(a1, a0);
  ASSERT_GT(c1, c0);
  EXPECT_NEAR(c0, a0, 2) << "both start at the left of the frame";
  const double share = static_cast<double>(c1 - c0) / static_cast<double>(a1 - a0);
  EXPECT_NEAR(share, 0.25, 0.02);
}

TEST_F(Plot, ShadedIntervalIsALightGreyBand) {
  // The band goes in a panel without lines, so every pixel it changes is background or grid.
  Figure plain;
  plain.panels = {Panel{"signal", "y", {sampled("s", [](double t) { return std::sin(t); })}, {}},
                  Panel{"phases", "", {}, {}}};
  Figure banded = plain;
  banded.panels[1].shaded = {{4.0, 2.0}};  // reversed on purpose
  const Image a = written(plain, "plain");
  const Image b = written(banded, "banded");
  long changed = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    if (a.pixels[i] == b.pixels[i]) continue;
    ++changed;
    const Rgb& p = b.pixels[i];
    EXPECT_FALSE(coloured(p));
    EXPECT_GE(std::min({p.r, p.g, p.b}), 180) << "a band, not a line";
    if (::testing::Test::HasFailure()) break;
  }
  // 2 of the 10 time units over the panel's height: thousands of pixels.
  EXPECT_GT(changed, 1000);
}

TEST_F(Plot, BadDataAndEmptyPanelsDoNotThrow) {
  Figure figure;
  figure.title = "robustness";
  Panel odd{"odd data", "y", {}, {{kNaN, 1.0}, {-kInf, 0.5}, {8.0, kInf}, {3.0, 3.0}}};
  odd.series.push_back(Series{"empty", {}, {}});
  odd.series.push_back(Series{"nan and inf", {0, 1, 2, 3, 4, 5, 6}, {1, kNaN, 2, kInf, -kInf, 3, 4}});
  odd.series.push_back(Series{"inf x", {kNaN, 1, kInf, 3}, {0, 1, 2, 3}, true});
  odd.series.push_back(Series{"single point", {2.5}, {0.5}});
  odd.series.push_back(Series{"lengths differ", {0, 1, 2, 3, 4}, {1, 2}});
  odd.series.push_back(Series{"huge", {0, 10}, {-1e308, 1e308}});
  odd.series.push_back(Series{"scatter with gaps", {0, kNaN, 2, kInf, 4}, {1, 2, kNaN, 3, 1e308}, false, true});
  Panel all_nan{"all NaN", "y", {Series{"nan", {kNaN, kNaN}, {kNaN, kNaN}}}, {}};
  Panel constant{"constant", "y", {Series{"zero", {0, 10}, {0, 0}}, Series{"tiny", {0, 10}, {1e-300, 1e-300}}}, {}};
  Panel empty{"", "", {}, {}};
  figure.panels = {odd, all_nan, constant, empty};
  figure.x_ticks = {{kNaN, "not a number"}, {-kInf, "minus infinity"}, {1e308, "huge"}, {2.0, ""}};
  EXPECT_NO_THROW(write_figure(figure, dir_ / "odd"));
  const Image image = read_png(dir_ / "odd.png");
  EXPECT_EQ(image.width, figure.width);
  tinyxml2::XMLDocument svg;
  EXPECT_EQ(svg.LoadFile((dir_ / "odd.svg").c_str()), tinyxml2::XML_SUCCESS);

  // No finite data at all, and no panels at all.
  Figure nothing;
  nothing.panels = {all_nan, empty};
  EXPECT_NO_THROW(write_figure(nothing, dir_ / "nothing"));
  EXPECT_NO_THROW(write_figure(Figure{}, dir_ / "no_panels"));
}

TEST_F(Plot, UnwritablePathThrowsNamingTheFile) {
  EXPECT_THROW(write_figure(two_panels(), "/nonexistent-dir/x"), std::runtime_error);
  try {
    write_figure(two_panels(), "/nonexistent-dir/x");
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.png"), std::string::npos) << e.what();
  }
}

TEST_F(Plot, UnwritableSvgThrowsNamingIt) {
  // The PNG can be written, the SVG cannot: a directory is in its way.
  std::filesystem::create_directory(dir_ / "x.svg");
  try {
    write_figure(two_panels(), dir_ / "x");
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("x.svg"), std::string::npos) << e.what();
  }
}

TEST_F(Plot, NonPositiveSizeIsRejected) {
  Figure figure = two_panels();
  figure.width = 0;
  EXPECT_THROW(write_figure(figure, dir_ / "zero_width"), std::invalid_argument);
  figure = two_panels();
  figure.panel_height = -5;
  EXPECT_THROW(write_figure(figure, dir_ / "negative_height"), std::invalid_argument);
}

}  // namespace
}  // namespace dyncc::plot
