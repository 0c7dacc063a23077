// `twister mesh grid|sphere --out OUT`: writes a procedural test/demo mesh as OBJ.
#pragma once

#include <CLI/CLI.hpp>

namespace twister::cli {

void add_mesh_command(CLI::App& app, int& exit_code);

}  // namespace twister::cli
