// `twister figure8 [--svg FILE] [--png FILE]`: the Figure 8 experiment (docs/math.md §9):
// prints self-intersections and sharpest turns per angle and method, draws the grid.
#pragma once

#include <CLI/CLI.hpp>

namespace twister::cli {

void add_figure8_command(CLI::App& app, int& exit_code);

}  // namespace twister::cli
