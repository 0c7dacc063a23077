// `twister replay JOURNAL --mesh IN --out OUT`: applies a station's stroke journal
// to a mesh (the same one, or a finer version of it) and writes the result.
#pragma once

#include <CLI/CLI.hpp>

namespace twister::cli {

void add_replay_command(CLI::App& app, int& exit_code);

}  // namespace twister::cli
