// `twister journal check JOURNAL [--mesh OBJ]`: what a station journal holds (records
// by type, sequence gaps, each damaged range, and the verdict: clean, torn tail, or
// corrupt) and, with --mesh, whether every record applies to the model.
// Exit 0 clean, 1 damage found or a record does not apply, 2 not a journal / bad input.
// `twister journal salvage JOURNAL OUT [--mesh OBJ]`: a new journal OUT (never an
// existing file) with every valid record of JOURNAL, byte for byte, except freeze steps
// whose chain lost a step (and, with --mesh, records that do not apply), each loss
// printed. JOURNAL is only read. Exit 0 written, 1 cannot write, 2 bad input.
#pragma once

#include <CLI/CLI.hpp>

namespace twister::cli {

void add_journal_command(CLI::App& app, int& exit_code);

}  // namespace twister::cli
