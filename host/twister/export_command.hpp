// `twister export JOURNAL [--base MODEL] --out DIR [--glb] [--stl] [--thumbnail]`:
// replays a station's journal onto its base model and writes what a visitor can take
// home: binary glTF (metres, +Y up, with a material), binary STL (millimetres, +Z up,
// checked closed and manifold first) and a PNG thumbnail, all upright and centred
// (hal/meshio mesh_export.hpp, thumbnail.hpp).
#pragma once

#include <CLI/CLI.hpp>

namespace twister::cli {

void add_export_command(CLI::App& app, int& exit_code);

}  // namespace twister::cli
