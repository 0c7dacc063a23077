// `twister warp CASE|-`: warps the points of a case file with the station's kernel
// and prints them (docs/math.md §10).
#pragma once

#include <CLI/CLI.hpp>

namespace twister::cli {

void add_warp_command(CLI::App& app, int& exit_code);

}  // namespace twister::cli
