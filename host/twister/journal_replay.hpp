// Replaying a journal file onto a ModelSession, shared by `twister replay` and
// `twister export`: the journal is read whole into memory (read-only: a torn tail is
// reported, never cut), refused when corrupt (damage with valid records after it, or
// a refused record: replaying up to it would silently drop later strokes, and the
// station refuses the same journal), and applied record by record with a progress
// line per 10% of the file on stderr (notice) when asked or when the file is over
// 64 KiB.
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <memory>
#include <string>

#include "model_session.hpp"

namespace twister::cli {

// What a command needs to replay a journal as the station ran it (its undo history's
// sizes and refinement room), and how much it says; add_replay_options() gives each
// its flag (--undo-changes, --undo-entries, --spare-vertices, --progress, -q).
struct ReplaySettings {
  std::size_t undo_changes = session::kDefaultUndoChanges;
  std::size_t undo_entries = session::kDefaultUndoEntries;
  std::size_t spare_vertices = session::kDefaultSpareVertices;  // station.spare_vertices
  bool progress = false;
  bool quiet = false;
};
void add_replay_options(CLI::App& cmd, ReplaySettings& s);

struct JournalReplay {
  int exit_code = 0;        // kExitOk, or what the command returns (the error is logged)
  std::size_t applied = 0;  // records applied
};

JournalReplay replay_journal(const std::string& journal_path, ModelSession& model, bool progress);

// Opens the model at `model_path` as the station holds it (ModelSession::open with
// `s`) and replays the journal onto it; `model` is empty when exit_code is not kExitOk.
struct ReplayedModel {
  JournalReplay replay;
  std::unique_ptr<ModelSession> model;
};
ReplayedModel open_and_replay(const std::string& journal_path, const std::string& model_path,
                              const ReplaySettings& s);

}  // namespace twister::cli
