#include "journal_command.hpp"

#include <sys/stat.h>

#include <array>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "cli_exit_code.hpp"
#include "cli_log.hpp"
#include "model_session.hpp"
#include "twister/hal/posix_file_sink.hpp"
#include "twister/hal/posix_file_storage.hpp"
#include "twister/journal/journal_format.hpp"
#include "twister/journal/journal_salvage.hpp"
#include "twister/journal/journal_scanner.hpp"

namespace twister::cli {
namespace {

struct Options {
  std::string journal;
  std::string out;
  std::string mesh;  // optional: check that the records replay onto this model
};

// The journal, read only (no lock: a running station may hold it).
bool open_journal(hal::PosixFileStorage& storage, const std::string& path) {
  return storage.open({.path = path, .create_if_missing = false, .read_only = true}).ok();
}

// The model to replay onto (--mesh), or none without --mesh.
hal::Expected<std::unique_ptr<ModelSession>> open_model(const std::string& path) {
  if (path.empty()) return std::unique_ptr<ModelSession>();
  return ModelSession::open(path);
}

const char* type_name(journal::RecordType t) {
  switch (t) {
    case journal::RecordType::stroke:
      return "stroke";
    case journal::RecordType::object_move:
      return "object_move";
    case journal::RecordType::undo:
      return "undo";
    case journal::RecordType::redo:
      return "redo";
  }
  return "?";
}

// What `check` found, counted while scanning.
struct Findings {
  std::array<std::uint64_t, 5> by_type{};  // indexed by RecordType
  std::uint64_t records = 0;
  std::uint64_t damaged = 0;
  std::uint64_t gaps = 0;     // version 1: sequences out of order (not proven by the format)
  std::uint64_t refused = 0;  // complete records refused (version, type, values, order)
  std::optional<std::uint32_t> first_sequence, last_sequence;
  std::uint64_t not_applied = 0;  // with --mesh
};

void note_record(Findings& f, const journal::ScanItem& item, ModelSession* model) {
  const journal::JournalRecord& r = item.record;
  ++f.records;
  ++f.by_type[static_cast<std::size_t>(r.type)];
  if (f.last_sequence && r.sequence != *f.last_sequence + 1) {
    ++f.gaps;
    std::printf("sequence %s at offset %llu: %u follows %u\n",
                r.sequence > *f.last_sequence ? "gap" : "out of order",
                static_cast<unsigned long long>(item.offset), r.sequence, *f.last_sequence);
  }
  if (!f.first_sequence) f.first_sequence = r.sequence;
  f.last_sequence = r.sequence;
  if (model == nullptr) return;
  if (const Status s = model->session().apply_record(r); !s.ok()) {
    ++f.not_applied;
    std::printf("record at offset %llu (sequence %u, %s) cannot be applied to the model: %s\n",
                static_cast<unsigned long long>(item.offset), r.sequence, type_name(r.type),
                s.name());
  }
}

void print_damage(Findings& f, const journal::ScanItem& item) {
  if (journal::may_be_torn(item.problem)) {
    ++f.damaged;
    std::printf(
        "damage at offset %llu: %llu bytes (%s)\n", static_cast<unsigned long long>(item.offset),
        static_cast<unsigned long long>(item.bytes), journal::tail_problem_name(item.problem));
    return;
  }
  ++f.refused;
  std::printf("refused: record at offset %llu (%llu bytes",
              static_cast<unsigned long long>(item.offset),
              static_cast<unsigned long long>(item.bytes));
  if (journal::is_order_problem(item.problem)) {
    std::printf(", sequence %u, %s", item.record.sequence, type_name(item.record.type));
  }
  std::printf("): %s (%s)\n", journal::tail_problem_text(item.problem),
              journal::tail_problem_name(item.problem));
}

void print_verdict(const Findings& f, const journal::JournalSurvey& s) {
  std::printf(
      "%llu records (strokes %llu, moves %llu, undos %llu, redos %llu)",
      static_cast<unsigned long long>(f.records), static_cast<unsigned long long>(f.by_type[1]),
      static_cast<unsigned long long>(f.by_type[2]), static_cast<unsigned long long>(f.by_type[3]),
      static_cast<unsigned long long>(f.by_type[4]));
  if (f.first_sequence) std::printf(", sequences %u..%u", *f.first_sequence, *f.last_sequence);
  std::printf("\n");
  std::printf("format version %u%s\n", s.format.version,
              s.format.proves_order() ? " (identity and sequences checked)"
                                      : " (order not proven by the format)");
  if (s.clean() && f.gaps > 0) {
    std::printf(
        "verdict: suspect order: %llu sequence(s) out of order in a version 1 journal; "
        "twister-station replays it as it is\n",
        static_cast<unsigned long long>(f.gaps));
  } else if (s.clean()) {
    std::printf("verdict: clean\n");
  } else if (s.refused_records > 0 &&
             (s.later_records == 0 || s.first_refused_offset <= s.good_end)) {
    std::printf(
        "verdict: corrupt: record at offset %llu is %s (%s), %llu refused record(s) in all; "
        "twister-station refuses this journal; `twister journal salvage` writes a copy "
        "that keeps the longest ordered valid prefix\n",
        static_cast<unsigned long long>(s.first_refused_offset),
        journal::tail_problem_text(s.first_refused), journal::tail_problem_name(s.first_refused),
        static_cast<unsigned long long>(s.refused_records));
  } else if (s.torn_tail()) {
    std::printf(
        "verdict: torn tail of %llu bytes at offset %llu (%s): twister-station cuts it "
        "on start and keeps its bytes in JOURNAL.torn-tail\n",
        static_cast<unsigned long long>(s.file_size - s.good_end),
        static_cast<unsigned long long>(s.good_end), journal::tail_problem_name(s.problem));
  } else {
    std::printf(
        "verdict: corrupt: damage at offset %llu (%s) with %llu valid record(s) after "
        "it; twister-station refuses this journal; `twister journal salvage` writes a "
        "copy that keeps every valid record\n",
        static_cast<unsigned long long>(s.good_end), journal::tail_problem_name(s.problem),
        static_cast<unsigned long long>(s.later_records));
  }
}

int run_check(const Options& o) {
  hal::PosixFileStorage storage;
  if (!open_journal(storage, o.journal)) {
    return fail(kExitBadInput, "cannot open journal " + o.journal);
  }
  auto opened = open_model(o.mesh);
  if (!opened) return fail(kExitBadInput, opened.error().message);
  const std::unique_ptr<ModelSession> model = std::move(*opened);
  journal::JournalScanner scanner(storage);
  if (const Status scanned = scanner.open(); !scanned.ok()) {
    return fail(kExitBadInput,
                o.journal + (scanned.code() == StatusCode::not_supported
                                 ? " is a journal of a newer format than this twister reads"
                                 : " is not a Twister journal (or its header is damaged)"));
  }
  std::printf("journal %s: %llu bytes\n", o.journal.c_str(),
              static_cast<unsigned long long>(scanner.file_size()));
  Findings f;
  for (auto item = scanner.next(); item.ok(); item = scanner.next()) {
    if (item->kind == journal::ScanItem::Kind::damage) {
      print_damage(f, *item);
      continue;
    }
    note_record(f, *item, model.get());
  }
  const auto survey = journal::survey_journal(storage);
  if (!survey.ok()) {
    return fail(kExitFailure, std::string("reading the journal: ") + survey.status().name());
  }
  print_verdict(f, *survey);
  if (model) {
    std::printf("model %s: %s; mesh checksum %016llx\n", o.mesh.c_str(),
                f.not_applied == 0 ? "every record applies" : "some records do not apply",
                static_cast<unsigned long long>(model->mesh().checksum()));
  }
  return survey->clean() && f.gaps == 0 && f.not_applied == 0 ? kExitOk : kExitFailure;
}

const char* why_text(journal::SalvageObserver::Drop why) {
  using Drop = journal::SalvageObserver::Drop;
  switch (why) {
    case Drop::broken_chain:
      return "a freeze step whose earlier step was lost";
    case Drop::refused:
      return "it does not apply to the model";
    case Drop::out_of_order:
      return "a duplicate, or a sequence the copy already has";
    case Drop::after_gap:
      return "a record before it is missing (the copy ends at the gap)";
  }
  return "?";
}

// Prints what salvage skips.
class SalvageLog final : public journal::SalvageObserver {
 public:
  void damaged(std::uint64_t offset, std::uint64_t bytes, journal::TailProblem problem) override {
    std::printf("lost: %llu %s at offset %llu: %s (%s)\n", static_cast<unsigned long long>(bytes),
                journal::may_be_torn(problem) ? "damaged bytes" : "bytes of a refused record",
                static_cast<unsigned long long>(offset), journal::tail_problem_text(problem),
                journal::tail_problem_name(problem));
  }
  void dropped(const journal::ScanItem& item, Drop why) override {
    std::printf("dropped: record at offset %llu (sequence %u, %s): %s\n",
                static_cast<unsigned long long>(item.offset), item.record.sequence,
                type_name(item.record.type), why_text(why));
  }
};

// --mesh: a record is kept only when it applies to the model after the ones kept.
class AppliesToModel final : public journal::RecordFilter {
 public:
  explicit AppliesToModel(ModelSession& model) : model_(model) {}
  bool keep(const journal::JournalRecord& record) override {
    return model_.session().apply_record(record).ok();
  }

 private:
  ModelSession& model_;
};

int run_salvage(const Options& o) {
  struct stat st {};
  if (::lstat(o.out.c_str(), &st) == 0) {
    return fail(kExitBadInput, o.out + " exists; salvage writes a new file and never replaces one");
  }
  hal::PosixFileStorage storage;
  if (!open_journal(storage, o.journal)) {
    return fail(kExitBadInput, "cannot open journal " + o.journal);
  }
  auto opened = open_model(o.mesh);
  if (!opened) return fail(kExitBadInput, opened.error().message);
  const std::unique_ptr<ModelSession> model = std::move(*opened);
  std::unique_ptr<AppliesToModel> filter;
  if (model) filter = std::make_unique<AppliesToModel>(*model);
  hal::PosixFileSinkConfig config;
  config.path = o.out;
  config.replace = hal::PosixFileSinkConfig::Replace::never;
  hal::PosixFileSink sink(config);
  SalvageLog log;
  const auto report = journal::salvage_journal(storage, sink, &log, filter.get());
  if (!report.ok()) {
    if (report.status().code() == StatusCode::data_loss) {
      return fail(kExitBadInput,
                  o.journal + " is not a Twister journal (or its header is damaged)");
    }
    if (report.status().code() == StatusCode::not_supported) {
      return fail(kExitBadInput,
                  o.journal + " is a journal of a newer format than this twister reads");
    }
    return fail(kExitFailure, "cannot write " + o.out + ": " + sink.last_error());
  }
  const journal::SalvageReport& r = *report;
  std::printf(
      "salvaged %llu of %llu valid records into %s; lost %llu damaged range(s) (%llu "
      "bytes), dropped %llu broken-chain, %llu non-applying, %llu duplicate or out-of-order and "
      "%llu after-a-gap record(s)\n",
      static_cast<unsigned long long>(r.records_kept),
      static_cast<unsigned long long>(r.records_found), sink.committed_path(),
      static_cast<unsigned long long>(r.damaged_ranges),
      static_cast<unsigned long long>(r.damaged_bytes),
      static_cast<unsigned long long>(r.broken_chain), static_cast<unsigned long long>(r.refused),
      static_cast<unsigned long long>(r.out_of_order),
      static_cast<unsigned long long>(r.after_gap));
  return kExitOk;
}

}  // namespace

void add_journal_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("journal", "Inspect or repair a station's stroke journal");
  cmd->require_subcommand(1);
  CLI::App* check = cmd->add_subcommand(
      "check", "Report what a journal holds: records, damage, torn tail or corruption");
  check->add_option("journal", options->journal, "Journal file")->required();
  check->add_option("--mesh", options->mesh, "Also replay every record onto this model (OBJ)");
  check->callback([options, &exit_code] {
    start_command_log("journal check");
    exit_code = run_check(*options);
  });
  CLI::App* salvage = cmd->add_subcommand(
      "salvage", "Write a repaired copy that keeps every valid record, saying what was lost");
  salvage->add_option("journal", options->journal, "Damaged journal (read only)")->required();
  salvage->add_option("out", options->out, "New journal to write (must not exist)")->required();
  salvage->add_option("--mesh", options->mesh,
                      "Keep only records that apply to this model (so the copy replays)");
  salvage->callback([options, &exit_code] {
    start_command_log("journal salvage");
    exit_code = run_salvage(*options);
  });
}

}  // namespace twister::cli
