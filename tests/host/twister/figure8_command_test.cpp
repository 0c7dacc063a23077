// `twister figure8 --svg --png` end to end: the table is the committed one
// (docs/figure8.txt), the PNG is a valid image of the expected size showing every
// method's curves and text, the SVG carries every label of both panels, and a bad
// output path is a clear failure.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_support.hpp"
#include "figure8_plot.hpp"
#include "figure8_test_image.hpp"

namespace twister::cli {
namespace {

namespace fs = std::filesystem;
using test::read_file;

struct CliRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

CliRun run(const std::string& args, const fs::path& err_file) {
  const host_test::CommandRun r =
      host_test::run_command(std::string(TWISTER_CLI) + " " + args + " 2>" + err_file.string());
  return {r.exit_code, r.out, read_file(err_file.string())};
}

// The cell labels the picture must carry, in table order: "N crossing(s)", ", turn T°".
std::vector<std::string> cell_labels(const std::string& table) {
  std::vector<std::string> labels;
  std::istringstream lines(table);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream in(line);
    int angle = 0;
    if (line.empty() || line[0] == '#' || !(in >> angle)) continue;
    std::size_t n = 0;
    std::string slash, turn;
    while (in >> n >> slash >> turn) {
      labels.push_back(std::to_string(n) + (n == 1 ? " crossing" : " crossings"));
      labels.push_back(", turn " + turn + "\u00b0");
    }
  }
  return labels;
}

class Figure8Command : public ::testing::Test {
 protected:
  host_test::ScratchDir dir_{"twister_figure8_cmd"};
};

TEST_F(Figure8Command, PrintsTheTableAndWritesBothPictures) {
  const fs::path svg = dir_ / "f.svg", png = dir_ / "f.png";
  const CliRun r =
      run("figure8 --svg " + svg.string() + " --png " + png.string(), dir_ / "stderr.txt");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  // The table output is unchanged: it is the committed docs/figure8.txt.
  EXPECT_EQ(r.out, read_file(std::string(TWISTER_SOURCE_DIR) + "/docs/figure8.txt"));

  // PNG: valid, two panels of 3 methods x 8 angles, every method's colour, text.
  const auto image = test::load_png(png.string());
  ASSERT_EQ(image.status, CAIRO_STATUS_SUCCESS);
  const Figure8Size size = figure8_picture_size(2, 3, 8);
  EXPECT_EQ(image.width, size.width);
  EXPECT_EQ(image.height, size.height);
  for (const std::uint32_t method_colour : {0xc0392bu, 0x2471a3u, 0x1e8449u}) {
    EXPECT_GT(image.count(method_colour, 12), 2000) << std::hex << method_colour;
  }
  EXPECT_GT(image.count(0x212121u, 40), 5000);  // dark text: title, headings, labels

  // SVG: same size, every label as text and as glyphs.
  const std::string doc = read_file(svg.string());
  EXPECT_NE(doc.find("width=\"" + std::to_string(size.width) + "px\""), std::string::npos);
  EXPECT_NE(doc.find("height=\"" + std::to_string(size.height) + "px\""), std::string::npos);
  EXPECT_NE(doc.find("<title>Figure 8: "), std::string::npos);
  const std::string desc = test::svg_desc(doc);
  for (const char* label :
       {"A. Large displacement, the balls touch: r = 0.5, both hands move by (0, 0.6, 0)",
        "B. Small displacement: r = 1, both hands move by (0, 0.3, 0)", "\u2212180\u00b0",
        "\u2212135\u00b0", "\u221290\u00b0", "\u221245\u00b0", "\n0\u00b0", "\n45\u00b0",
        "\n90\u00b0", "\n135\u00b0", "\ntwister\n", "\nrottran\n", "\nscodef\n",
        "line before the warp", "grab point held by the hand"}) {
    EXPECT_NE(desc.find(label), std::string::npos) << label;
  }
  // Each cell's numbers, in table order (panel A then B), match the printed table.
  const std::vector<std::string> cells = cell_labels(r.out);
  ASSERT_EQ(cells.size(), 2u * 2u * 8u * 3u);
  std::size_t at = 0;
  for (const auto& label : cells) {
    at = desc.find("\n" + label + "\n", at);
    ASSERT_NE(at, std::string::npos) << label;
    ++at;
  }
  EXPECT_GE(test::svg_glyph_uses(doc), test::visible_chars(desc));
}

TEST_F(Figure8Command, UnwritablePictureFailsWithAMessage) {
  const fs::path bad = dir_ / "missing" / "f.png";
  const CliRun r = run("figure8 --png " + bad.string(), dir_ / "stderr.txt");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("twister figure8: cannot write " + bad.string()), std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace twister::cli
