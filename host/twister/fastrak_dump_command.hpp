// `twister fastrak-dump`: configure a Fastrak (real or simulated) and print decoded
// records and error counters live, or decode a recorded stream (--file PATH|-).
#pragma once

#include <CLI/CLI.hpp>

namespace twister::cli {

void add_fastrak_dump_command(CLI::App& app, int& exit_code);

}  // namespace twister::cli
