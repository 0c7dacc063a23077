// The Figure 8 picture (cairo): size from the grid, the same picture in SVG and PNG,
// labels present, grab points and curves drawn, I/O errors reported.
#include "figure8_plot.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "cli_test_support.hpp"
#include "figure8_test_image.hpp"

namespace twister::cli {
namespace {

using test::load_png;
using test::read_file;

constexpr std::uint32_t kTwisterRed = 0xc0392b, kRottranBlue = 0x2471a3, kInk = 0x212121;

// Two methods x four angles of the paper-like set-up, with fewer points (four
// columns: the legend needs the width; cairo drops glyphs outside the picture).
Figure8Picture small_picture() {
  const Figure8Setup setup{401, 0.5, 0.6};
  Figure8Picture pic{"Test title", "Test subtitle", {}};
  pic.panels.push_back(Figure8Panel{"Panel heading", setup, {}});
  for (const int angle : {-90, 0, 45, 90}) {
    for (const auto m : {math::WarpMethod::twister, math::WarpMethod::rottran}) {
      Figure8Curve c;
      EXPECT_TRUE(run_figure8_curve(setup, angle, m, c).ok());
      pic.panels[0].curves.push_back(std::move(c));
    }
  }
  return pic;
}

class Figure8Plot : public ::testing::Test {
 protected:
  std::string path(const char* name) const { return (dir_ / name).string(); }
  host_test::ScratchDir dir_{"twister_figure8_plot"};
};

TEST(Figure8PictureSize, GrowsByWholeCells) {
  const Figure8Size one = figure8_picture_size(1, 3, 8);
  const Figure8Size more_cols = figure8_picture_size(1, 3, 9);
  const Figure8Size more_rows = figure8_picture_size(1, 4, 8);
  const Figure8Size two = figure8_picture_size(2, 3, 8);
  EXPECT_GT(more_cols.width - one.width, 100);
  EXPECT_EQ(more_cols.height, one.height);
  EXPECT_GT(more_rows.height - one.height, 100);
  EXPECT_EQ(more_rows.width, one.width);
  // A second panel adds at least its rows of cells (plus heading and gap).
  EXPECT_GT(two.height - one.height, more_rows.height - one.height);
  EXPECT_EQ(two.width, one.width);
}

TEST_F(Figure8Plot, PngIsAnImageOfTheGridSizeWithCurvesAndText) {
  const hal::Expected<void> written = write_figure8_png(path("f.png"), small_picture());
  ASSERT_TRUE(written) << written.error().message;
  const auto png = load_png(path("f.png"));
  ASSERT_EQ(png.status, CAIRO_STATUS_SUCCESS);
  const Figure8Size size = figure8_picture_size(1, 2, 4);
  EXPECT_EQ(png.width, size.width);
  EXPECT_EQ(png.height, size.height);
  // Each method's curves in its colour (antialiased: the line core is exact).
  EXPECT_GT(png.count(kTwisterRed, 12), 200);
  EXPECT_GT(png.count(kRottranBlue, 12), 200);
  // Title text is dark ink in the top band; the background is white.
  EXPECT_GT(png.count(kInk, 40, 0, 0, png.width, 50), 100);
  EXPECT_EQ(png.pixel(1, 1), 0xffffffu);
}

TEST_F(Figure8Plot, SvgHasTheSizeAndCarriesEveryLabel) {
  const hal::Expected<void> written = write_figure8_svg(path("f.svg"), small_picture());
  ASSERT_TRUE(written) << written.error().message;
  const std::string svg = read_file(path("f.svg"));
  const Figure8Size size = figure8_picture_size(1, 2, 4);
  EXPECT_NE(svg.find("width=\"" + std::to_string(size.width) + "px\""), std::string::npos);
  EXPECT_NE(svg.find("height=\"" + std::to_string(size.height) + "px\""), std::string::npos);
  EXPECT_NE(svg.find("<title>Test title</title>"), std::string::npos);
  const std::string desc = test::svg_desc(svg);
  for (const char* label : {"Test title", "Test subtitle", "Panel heading", "\u221290\u00b0",
                            "\n0\u00b0", "\n45\u00b0", "\n90\u00b0", "twister", "rottran"}) {
    EXPECT_NE(desc.find(label), std::string::npos) << label;
  }
  const Figure8Picture expected = small_picture();  // a temporary would die before the loop
  for (const auto& c : expected.panels[0].curves) {
    char cell[64];
    std::snprintf(cell, sizeof cell, "\n%zu crossings\n, turn %.1f\u00b0\n", c.intersections,
                  c.sharpest_turn_deg);
    EXPECT_NE(desc.find(cell), std::string::npos) << cell;
  }
  // The labels are drawn too, as glyphs: at least one per visible character.
  EXPECT_GE(test::svg_glyph_uses(svg), test::visible_chars(desc));
  EXPECT_GT(test::visible_chars(desc), 100u);
  // Curves in the method colours.
  EXPECT_NE(svg.find("rgb(75.294118%,22.352941%,16.862745%)"), std::string::npos);
}

TEST_F(Figure8Plot, CrossingsAndTurnsOfEachCellAreLabelled) {
  Figure8Picture pic = small_picture();
  pic.panels[0].curves[0].intersections = 1;
  pic.panels[0].curves[1].intersections = 12;
  pic.panels[0].curves[1].sharpest_turn_deg = 47.46;
  const hal::Expected<void> written = write_figure8_svg(path("f.svg"), pic);
  ASSERT_TRUE(written) << written.error().message;
  const std::string desc = test::svg_desc(read_file(path("f.svg")));
  EXPECT_NE(desc.find("1 crossing\n"), std::string::npos);
  EXPECT_NE(desc.find("12 crossings\n, turn 47.5\u00b0"), std::string::npos);
}

TEST_F(Figure8Plot, EmptyPictureIsStillAValidImage) {
  const hal::Expected<void> written = write_figure8_png(path("e.png"), Figure8Picture{});
  ASSERT_TRUE(written) << written.error().message;
  const auto png = load_png(path("e.png"));
  ASSERT_EQ(png.status, CAIRO_STATUS_SUCCESS);
  EXPECT_EQ(png.width, figure8_picture_size(0, 0, 0).width);
  const hal::Expected<void> svg = write_figure8_svg(path("e.svg"), Figure8Picture{});
  ASSERT_TRUE(svg) << svg.error().message;
}

TEST_F(Figure8Plot, UnwritablePathIsAnErrorNamingIt) {
  const std::string bad = path("no/such/dir/f.png");
  const hal::Expected<void> png = write_figure8_png(bad, small_picture());
  ASSERT_FALSE(png);
  EXPECT_NE(png.error().message.find(bad), std::string::npos) << png.error().message;
  const std::string bad_svg = path("no/such/dir/f.svg");
  const hal::Expected<void> svg = write_figure8_svg(bad_svg, small_picture());
  ASSERT_FALSE(svg);
  EXPECT_NE(svg.error().message.find(bad_svg), std::string::npos) << svg.error().message;
}

}  // namespace
}  // namespace twister::cli
