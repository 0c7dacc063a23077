// Draws the Figure 8 picture with cairo: a title, a legend and one panel per
// experiment, each a grid with one row per method and one column per angle. One
// drawing routine renders to an SVG surface and to an image surface saved as PNG, so
// both files show the same picture. Units: pixels (SVG user units = PNG pixels).
// Host code. Writers return an Error with a message on I/O or cairo errors.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "figure8_experiment.hpp"
#include "twister/hal/expected.hpp"

namespace twister::cli {

// One experiment: its set-up (grab points and lift come from it), a heading, and
// every (method, angle) curve. Rows follow the first appearance of a method, columns
// of an angle.
struct Figure8Panel {
  std::string heading;
  Figure8Setup setup;
  std::vector<Figure8Curve> curves;
};

// All panels share one scale, so shapes compare across cells and panels.
struct Figure8Picture {
  std::string title;
  std::string subtitle;
  std::vector<Figure8Panel> panels;
};

struct Figure8Size {
  int width = 0;
  int height = 0;
};

// Size of a picture of `panels` panels, each laid out with `rows` methods and `cols`
// angles (the largest counts of any panel). Depends on the counts only.
Figure8Size figure8_picture_size(std::size_t panels, std::size_t rows, std::size_t cols);

// Writes the picture. The SVG draws the labels as glyph outlines (cairo) and also
// carries them as text in its <title> and <desc> elements, so it is searchable.
// Written atomically under the programs' output rule (twister/hal/output_file.hpp:
// an existing file only with `force` and only an SVG / PNG).
// Errors: io_error ("cannot write '<path>'"), failed_precondition (cairo could not
// draw; the output rule refused the path).
hal::Expected<void> write_figure8_svg(const std::string& path, const Figure8Picture& picture,
                                      bool force = false);
hal::Expected<void> write_figure8_png(const std::string& path, const Figure8Picture& picture,
                                      bool force = false);

}  // namespace twister::cli
