#include "replay_command.hpp"

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <glm/mat3x3.hpp>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli_exit_code.hpp"
#include "cli_log.hpp"
#include "model_session.hpp"
#include "twister/session/commit_refinement.hpp"
#include "twister/hal/output_file.hpp"
#include "twister/journal/journal_format.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/journal/journal_scanner.hpp"
#include "twister/meshio/obj_file.hpp"
#include "twister/session/sculpt_session.hpp"

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

struct Options {
  std::string journal;
  std::string mesh_in;
  std::string mesh_out;
  std::size_t undo_changes = session::kDefaultUndoChanges;
  std::size_t undo_entries = session::kDefaultUndoEntries;
  // Refinement's room: the station's station.spare_vertices.
  std::size_t spare_vertices = session::kDefaultSpareVertices;
  bool world = false;
  bool quiet = false;
  bool progress = false;
  bool force = false;  // --force: replace an existing OBJ (never anything else)
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

// Object frame -> world: p_world = origin + [U V W] p.
void to_world(mesh::Mesh& m, const math::Frame& pose) {
  const glm::dmat3 r(pose.u, pose.v, pose.w);
  for (std::uint32_t i = 0; i < m.vertex_count(); ++i) {
    m.set_position(i, glm::vec3(pose.origin + r * glm::dvec3(m.position(i))));
  }
}

// Refined commits: what they added, and a warning when the capacity stopped one (the
// station's was larger, or the result differs from the station's).
void report_refinement(const session::RefineStatus& r, const Options& o) {
  if (r.refined_commits == 0) return;
  std::printf("refined %llu commits, %llu vertices added\n",
              static_cast<unsigned long long>(r.refined_commits),
              static_cast<unsigned long long>(r.vertices_added));
  if (r.capacity_stops > 0) {
    cli_log().warning(
        "",
        "refinement stopped at this mesh's capacity in %llu commits (--spare-vertices "
        "%zu); the station's result differs unless it had the same spare capacity",
        static_cast<unsigned long long>(r.capacity_stops), o.spare_vertices);
  }
}

// Before any work: the output may not be an input, and must pass the output rule
// (never a journal, checkpoint, locked file such as a running station's journal or
// base model; an existing OBJ only with --force). kExitOk when it may be written.
int check_output(const Options& o) {
  for (const std::string* input : {&o.journal, &o.mesh_in}) {
    if (hal::same_file(o.mesh_out, *input)) {
      return fail(kExitBadInput, o.mesh_out + " is the input " + *input + "; it is not replaced");
    }
  }
  if (auto free = hal::check_output_path(o.mesh_out, {hal::OutputKind::obj, o.force}); !free) {
    return fail(kExitBadInput, free.error().message);
  }
  return kExitOk;
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

int run_replay(const Options& o) {
  if (const int refused = check_output(o); refused != kExitOk) return refused;
  auto model = ModelSession::open(o.mesh_in, o.spare_vertices, o.undo_changes, o.undo_entries);
  if (!model) return fail(kExitBadInput, model.error().message);
  mesh::Mesh& mesh = (*model)->mesh();
  session::SculptSession& session = (*model)->session();

  auto bytes = read_file(o.journal);
  if (!bytes) return fail(kExitBadInput, "cannot open journal '" + o.journal + "'");
  ReadOnlyStorage storage(std::move(*bytes));
  journal::JournalReader reader(storage);
  if (const Status opened = reader.open(); !opened.ok()) {
    return fail(kExitBadInput, "'" + o.journal +
                                   (opened.code() == StatusCode::not_supported
                                        ? "' is a journal of a newer format than this twister reads"
                                        : "' is not a Twister journal"));
  }
  const std::uint64_t total_bytes = storage.size().value_or(0);
  if (const std::string why = corruption(storage); !why.empty()) {
    return fail(kExitBadInput, o.journal + ": " + why);
  }

  // Progress for long journals: a line per 10% of the file, on stderr (notice).
  const bool show_progress = o.progress || total_bytes > (std::uint64_t{1} << 16);
  int shown_decile = 0;
  std::size_t applied = 0;
  for (;;) {
    auto record = reader.next();
    if (!record.ok()) {
      if (record.status().code() == StatusCode::unavailable ||
          record.status().code() == StatusCode::data_loss)
        break;
      return fail(kExitFailure, "reading '" + o.journal + "': " + record.status().name());
    }
    const Status s = session.apply_record(*record);
    if (!s.ok()) {
      return fail(kExitFailure, "record " + std::to_string(applied + 1) + " (sequence " +
                                    std::to_string(record->sequence) +
                                    ") cannot be applied: " + s.name());
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
    cli_log().warning("", "%s: %s tail of %llu bytes at offset %llu not applied", o.journal.c_str(),
                      journal::tail_problem_name(reader.problem()), reader.tail_bytes(),
                      reader.good_end());
  }
  if (o.world) to_world(mesh, session.object_pose());
  if (auto saved = meshio::save_obj(o.mesh_out, mesh, o.force); !saved) {
    return fail(kExitFailure, saved.error().message);
  }
  const session::ReplayStats& st = session.replay_stats();
  const math::Frame& pose = session.object_pose();
  std::printf("replayed %zu records (strokes %zu, moves %zu, undos %zu, redos %zu)\n", applied,
              st.strokes, st.moves, st.undos, st.redos);
  report_refinement(session.state().refine, o);
  std::printf("mesh %zu vertices %zu triangles checksum %016" PRIx64 "\n", mesh.vertex_count(),
              mesh.triangle_count(), mesh.checksum());
  std::printf("object origin %.9g %.9g %.9g u %.9g %.9g %.9g v %.9g %.9g %.9g\n", pose.origin.x,
              pose.origin.y, pose.origin.z, pose.u.x, pose.u.y, pose.u.z, pose.v.x, pose.v.y,
              pose.v.z);
  return kExitOk;
}

}  // namespace

void add_replay_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "replay", "Apply a station's stroke journal to a mesh (same or finer) and write the result");
  cmd->add_option("journal", options->journal, "Journal file written by twister-station")
      ->required();
  cmd->add_option("--mesh", options->mesh_in, "Initial mesh (OBJ)")->required();
  cmd->add_option("--out", options->mesh_out, "Output mesh (OBJ)")->required();
  cmd->add_option("--undo-changes", options->undo_changes,
                  "Undo history size in vertex changes (must match the station's)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--undo-entries", options->undo_entries,
                  "Undo history size in strokes (must match the station's)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--spare-vertices", options->spare_vertices,
                  "Room for refinement beyond the OBJ's vertices, and twice as many triangles "
                  "(the station's station.spare_vertices; default 100000, the station's)");
  cmd->add_flag("--force", options->force,
                "Replace an existing OBJ at --out (never a journal, checkpoint, a file a "
                "running station holds, or another kind of file)");
  cmd->add_flag("--world", options->world, "Write world coordinates (apply the object pose)");
  cmd->add_flag("--progress", options->progress,
                "Always print progress (default: journals > 64 KiB)");
  cmd->add_flag("-q,--quiet", options->quiet, "Only warnings and errors on stderr (no progress)");
  cmd->callback([options, &exit_code] {
    start_command_log("replay", options->quiet ? hal::LogLevel::warning : hal::LogLevel::notice);
    exit_code = run_replay(*options);
  });
}

}  // namespace twister::cli
