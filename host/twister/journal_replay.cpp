#include "journal_replay.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <vector>

#include "cli_exit_code.hpp"
#include "cli_log.hpp"
#include "twister/journal/journal_format.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/journal/journal_scanner.hpp"

namespace twister::cli {
namespace {

// The journal file held in memory, read-only: replay never changes the journal
// (a torn tail is reported, the station truncates it on its next start).
class ReadOnlyStorage final : public ports::Storage {
 public:
  explicit ReadOnlyStorage(std::vector<std::byte> bytes) : bytes_(std::move(bytes)) {}

 private:
  Result<std::uint64_t> do_size() override { return std::uint64_t{bytes_.size()}; }
  Result<std::size_t> do_read_at(std::uint64_t offset, std::span<std::byte> dest) override {
    if (offset >= bytes_.size()) return std::size_t{0};
    const std::size_t n = std::min<std::size_t>(dest.size(), bytes_.size() - offset);
    std::memcpy(dest.data(), bytes_.data() + offset, n);
    return n;
  }
  Status do_append(std::span<const std::byte>) override { return StatusCode::not_supported; }
  Status do_sync() override { return ok_status(); }
  Status do_truncate(std::uint64_t) override { return StatusCode::not_supported; }

  std::vector<std::byte> bytes_;
};

// The whole file, or nothing when it cannot be opened.
std::optional<std::vector<std::byte>> read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::vector<char> chars((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::byte> bytes(chars.size());
  std::memcpy(bytes.data(), chars.data(), chars.size());
  return bytes;
}

// A damaged record with valid records after it, or a complete record that is refused
// (unknown version or type, invalid values, another journal's, out of order), is
// corruption, not a torn tail: replaying up to it would silently drop later strokes,
// and twister-station refuses the same journal. "" when there is none.
std::string corruption(ports::Storage& storage) {
  const auto survey = journal::survey_journal(storage);
  if (!survey.ok() || !survey->corrupt()) return "";
  const bool refused =
      survey->refused_records > 0 &&
      (survey->later_records == 0 || survey->first_refused_offset <= survey->good_end);
  const std::uint64_t at = refused ? survey->first_refused_offset : survey->good_end;
  const journal::TailProblem what = refused ? survey->first_refused : survey->problem;
  return "record at offset " + std::to_string(at) + ": " + journal::tail_problem_text(what) + " (" +
         journal::tail_problem_name(what) + "); " + std::to_string(survey->later_records) +
         " valid record(s) after the first damage; nothing written (`twister journal salvage` "
         "makes a copy of what can be kept)";
}

}  // namespace

JournalReplay replay_journal(const std::string& journal_path, ModelSession& model, bool progress) {
  session::SculptSession& session = model.session();
  JournalReplay result;
  auto failed = [&result](int code) {
    result.exit_code = code;
    return result;
  };
  auto bytes = read_file(journal_path);
  if (!bytes) return failed(fail(kExitBadInput, "cannot open journal '" + journal_path + "'"));
  ReadOnlyStorage storage(std::move(*bytes));
  journal::JournalReader reader(storage);
  if (const Status opened = reader.open(); !opened.ok()) {
    return failed(
        fail(kExitBadInput, "'" + journal_path +
                                (opened.code() == StatusCode::not_supported
                                     ? "' is a journal of a newer format than this twister reads"
                                     : "' is not a Twister journal")));
  }
  const std::uint64_t total_bytes = storage.size().value_or(0);
  if (const std::string why = corruption(storage); !why.empty()) {
    return failed(fail(kExitBadInput, journal_path + ": " + why));
  }

  // Progress for long journals: a line per 10% of the file, on stderr (notice).
  const bool show_progress = progress || total_bytes > (std::uint64_t{1} << 16);
  int shown_decile = 0;
  std::size_t applied = 0;
  for (;;) {
    auto record = reader.next();
    if (!record.ok()) {
      if (record.status().code() == StatusCode::unavailable ||
          record.status().code() == StatusCode::data_loss)
        break;
      return failed(
          fail(kExitFailure, "reading '" + journal_path + "': " + record.status().name()));
    }
    const Status s = session.apply_record(*record);
    if (!s.ok()) {
      return failed(fail(kExitFailure, "record " + std::to_string(applied + 1) + " (sequence " +
                                           std::to_string(record->sequence) +
                                           ") cannot be applied: " + s.name()));
    }
    ++applied;
    if (show_progress && total_bytes > 0) {
      const int decile = static_cast<int>(10 * reader.good_end() / total_bytes);
      if (decile > shown_decile) {
        shown_decile = decile;
        cli_log().notice("", "%3d%% (%zu records)", 10 * decile, applied);
      }
    }
  }
  if (reader.problem() != journal::TailProblem::none) {
    cli_log().warning("", "%s: %s tail of %llu bytes at offset %llu not applied",
                      journal_path.c_str(), journal::tail_problem_name(reader.problem()),
                      reader.tail_bytes(), reader.good_end());
  }
  result.applied = applied;
  return result;
}

void add_replay_options(CLI::App& cmd, ReplaySettings& s) {
  cmd.add_option("--undo-changes", s.undo_changes,
                 "Undo history size in vertex changes (must match the station's)")
      ->check(CLI::PositiveNumber);
  cmd.add_option("--undo-entries", s.undo_entries,
                 "Undo history size in strokes (must match the station's)")
      ->check(CLI::PositiveNumber);
  cmd.add_option("--spare-vertices", s.spare_vertices,
                 "Room for refinement beyond the OBJ's vertices, and twice as many triangles "
                 "(the station's station.spare_vertices; default 100000, the station's)");
  cmd.add_flag("--progress", s.progress,
               "Always print replay progress (default: journals > 64 KiB)");
  cmd.add_flag("-q,--quiet", s.quiet, "Only warnings and errors on stderr (no progress)");
}

ReplayedModel open_and_replay(const std::string& journal_path, const std::string& model_path,
                              const ReplaySettings& s) {
  ReplayedModel out;
  auto model = ModelSession::open(model_path, s.spare_vertices, s.undo_changes, s.undo_entries);
  if (!model) {
    out.replay.exit_code = fail(kExitBadInput, model.error().message);
    return out;
  }
  out.replay = replay_journal(journal_path, **model, s.progress);
  if (out.replay.exit_code == kExitOk) out.model = std::move(*model);
  return out;
}

}  // namespace twister::cli
