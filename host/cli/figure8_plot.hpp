// Draws Figure 8 curves as a grid (one row per method, one column per angle), as
// SVG (by hand) or PNG (libpng). Host code. Returns false with a message on I/O errors.
#pragma once

#include <string>
#include <vector>

#include "figure8_experiment.hpp"

namespace twister::cli {

// `curves` holds every (method, angle) pair; rows follow first appearance of a
// method, columns of an angle. All cells share one scale so shapes compare.
bool write_figure8_svg(const std::string& path, const std::vector<Figure8Curve>& curves,
                       const std::string& title, std::string& error);
bool write_figure8_png(const std::string& path, const std::vector<Figure8Curve>& curves,
                       std::string& error);

}  // namespace twister::cli
