// Replaying a journal file onto a ModelSession, shared by `twister replay` and
// `twister export`: the journal is read whole into memory (read-only: a torn tail is
// reported, never cut), refused when corrupt (damage with valid records after it, or
// a refused record: replaying up to it would silently drop later strokes, and the
// station refuses the same journal), and applied record by record with a progress
// line per 10% of the file on stderr (notice) when asked or when the file is over
// 64 KiB.
#pragma once

#include <cstddef>
#include <string>

#include "model_session.hpp"

namespace twister::cli {

struct JournalReplay {
  int exit_code = 0;        // kExitOk, or what the command returns (the error is logged)
  std::size_t applied = 0;  // records applied
};

JournalReplay replay_journal(const std::string& journal_path, ModelSession& model, bool progress);

}  // namespace twister::cli
