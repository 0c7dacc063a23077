#include "station_assembly.hpp"

#include <sys/random.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>

#include "station_log.hpp"
#include "station_setup.hpp"
#include "twister/base/checksum.hpp"
#include "twister/checkpoint/session_checkpoint.hpp"
#include "twister/hal/output_file.hpp"
#include "twister/hal/startup_signals.hpp"
#include "twister/meshio/obj_file.hpp"

namespace twister::station_app {
namespace {

hal::Expected<void> open_journal(hal::PosixFileStorage& journal, const std::string& path) {
  const Status s = journal.open({.path = path, .lock = true});
  if (s.code() == StatusCode::failed_precondition) {
    const int pid = journal.lock_holder_pid();
    return hal::Error{s, "journal " + path + " is in use by another twister-station (" +
                             (pid > 0 ? "PID " + std::to_string(pid) : "PID unknown") +
                             "); refusing to start (the file was not changed)"};
  }
  if (s.code() == StatusCode::invalid_argument) {
    return hal::Error{s, "journal " + path +
                             " is not a regular file (a FIFO, device, socket or directory); "
                             "refusing to start"};
  }
  if (!s.ok()) {
    return hal::Error{s, "cannot open journal " + path + ": " +
                             storage_error_text(journal.last_errno()) + " (" + s.name() +
                             ", errno " + std::to_string(journal.last_errno()) + ")"};
  }
  return {};
}

std::string corrupt_message(const station::JournalRecovery& r) {
  const journal::JournalSurvey& v = r.survey;
  const std::string advice =
      "; refusing to start; the file is left untouched. `twister journal check` lists the "
      "damage, `twister journal salvage` writes a copy that keeps the longest ordered valid "
      "prefix";
  // A complete, CRC-valid record that is refused comes first when it is the first trouble.
  if (v.refused_records > 0 && (v.later_records == 0 || v.first_refused_offset <= v.good_end)) {
    return "record at offset " + std::to_string(v.first_refused_offset) + " is " +
           journal::tail_problem_text(v.first_refused) + " (" +
           journal::tail_problem_name(v.first_refused) + "), so it is not a torn tail" +
           (v.refused_records > 1
                ? " (" + std::to_string(v.refused_records) + " such records in all)"
                : std::string()) +
           advice;
  }
  return "damaged record at offset " + std::to_string(v.good_end) + " (" +
         journal::tail_problem_name(v.problem) + "); " + std::to_string(v.later_records) +
         " valid record(s) follow it (the first at offset " + std::to_string(v.first_later_offset) +
         "), so it is not a torn tail" + advice;
}

hal::Error start_error(Status s, const station::JournalRecovery& r, const std::string& journal_path,
                       const hal::PosixFileStorage& journal, const hal::PosixFileSink& archive) {
  using O = station::JournalRecovery::Outcome;
  std::string why = s.name();
  if (r.outcome == O::corrupt) {
    why = corrupt_message(r);
  } else if (r.outcome == O::not_a_journal) {
    why =
        "is not a Twister journal, or does not fit this mesh (left untouched): not a journal "
        "(or its header is damaged)";
  } else if (r.outcome == O::too_new) {
    why =
        "is a journal of a newer format than this twister-station reads (left untouched); "
        "use the twister-station that wrote it";
  } else if (r.outcome == O::does_not_fit) {
    why = "is not a Twister journal, or does not fit this mesh (left untouched): record " +
          std::to_string(r.record_index) + " (sequence " + std::to_string(r.record_sequence) +
          ") cannot be applied to this mesh (" + r.record_status.name() + ")";
  } else if (r.outcome == O::tail_not_kept) {
    why = "a torn tail of " + std::to_string(r.survey.file_size - r.survey.good_end) +
          " bytes at offset " + std::to_string(r.survey.good_end) + " could not be kept in " +
          archive.path() + " (" + archive.last_error() +
          "); refusing to cut it (the file is left untouched)";
  } else if (r.outcome == O::io_error && s.code() == StatusCode::io_error) {
    why = std::string("cannot write it: ") + storage_error_text(journal.last_errno()) + " (" +
          s.name() + ")";
  }
  return hal::Error{s, "journal " + journal_path + ": " + why};
}

// A new journal's identity: random, so records of two journals never pass for each other.
std::uint32_t random_journal_id() {
  std::uint32_t id = 0;
  if (::getrandom(&id, sizeof id, GRND_NONBLOCK) == static_cast<ssize_t>(sizeof id)) return id;
  const auto now = std::chrono::system_clock::now().time_since_epoch().count();
  return static_cast<std::uint32_t>(now) ^ (static_cast<std::uint32_t>(::getpid()) << 16);
}

std::vector<StationParts::Note> recovery_notes(const station::JournalRecovery& r,
                                               const StationParts& parts) {
  std::vector<StationParts::Note> notes;
  if (r.tail_cut > 0) {
    notes.push_back({true, "cut a torn tail of " + std::to_string(r.tail_cut) + " bytes (" +
                               journal::tail_problem_name(r.survey.problem) + ") at offset " +
                               std::to_string(r.survey.good_end) + "; its bytes are kept in " +
                               parts.tail_archive->committed_path()});
  }
  using C = station::JournalRecovery::Checkpoint;
  if (r.checkpoint == C::used) {
    notes.push_back({false, "restored the checkpoint of " + std::to_string(r.checkpoint_records) +
                                " records; replayed " + std::to_string(r.replayed) + " after it"});
  } else if (r.checkpoint != C::none) {
    notes.push_back({true, "checkpoint " + parts.checkpoint_out->path() + " ignored (" +
                               station::checkpoint_use_name(r.checkpoint) + "); replayed all " +
                               std::to_string(r.replayed) + " records"});
  }
  return notes;
}

// JOURNAL.ckpt for reading, when there is one (a failure to open it only means a
// full replay), and the sink that writes new ones. Something other than a regular
// file there (a FIFO, a device) is refused without blocking: it is never a checkpoint.
hal::Expected<void> open_checkpoint_files(StationParts& parts, const std::string& journal) {
  hal::PosixFileSinkConfig out;
  out.path = journal + ".ckpt";
  out.replace = hal::PosixFileSinkConfig::Replace::own_magic;
  out.magic.assign(checkpoint::kCheckpointMagic.begin(), checkpoint::kCheckpointMagic.end());
  out.writeback_bytes = std::size_t{1} << 20;
  parts.checkpoint_out = std::make_unique<hal::PosixFileSink>(out);
  auto in = std::make_unique<hal::PosixFileStorage>();
  const Status opened = in->open({.path = out.path, .create_if_missing = false, .read_only = true});
  if (opened.ok()) {
    parts.checkpoint_in = std::move(in);
  } else if (opened.code() == StatusCode::invalid_argument) {
    return hal::Error{opened, "checkpoint " + out.path +
                                  " is not a regular file (a FIFO, device, socket or "
                                  "directory); refusing to start (nothing was written)"};
  }
  return {};
}

// Is the whole checkpoint file intact (its last 4 bytes are the CRC-32 of the rest)?
bool checkpoint_crc_ok(ports::Storage& file) {
  auto size = file.size();
  if (!size.ok() || *size < 4) return false;
  std::array<std::byte, 1 << 16> chunk{};
  std::uint32_t crc = 0;
  const std::uint64_t body = *size - 4;
  for (std::uint64_t at = 0; at < body;) {
    const auto want = static_cast<std::size_t>(std::min<std::uint64_t>(chunk.size(), body - at));
    auto n = file.read_at(at, std::span(chunk).first(want));
    if (!n.ok() || *n != want) return false;
    crc = crc32(std::span(chunk).first(want), crc);
    at += want;
  }
  std::array<std::byte, 4> stored{};
  auto n = file.read_at(body, stored);
  if (!n.ok() || *n != stored.size()) return false;
  std::uint32_t value = 0;
  for (std::size_t i = 0; i < 4; ++i) value |= static_cast<std::uint32_t>(stored[i]) << (8 * i);
  return value == crc;
}

// An intact checkpoint names the checksum of the model its journal was started on.
// Another checksum means station.mesh changed since (say a tool wrote the sculpted
// model over it): replaying the journal onto it would not give the sculpture, and
// the next checkpoint would replace the only good one. So start-up stops here,
// before anything is written. A damaged checkpoint is only ignored (full replay).
hal::Expected<void> check_checkpoint_base(const StationParts& parts) {
  if (!parts.checkpoint_in) return {};
  auto header = checkpoint::read_checkpoint_header(*parts.checkpoint_in);
  if (!header.ok() || !checkpoint_crc_ok(*parts.checkpoint_in)) return {};
  const std::uint64_t base = parts.model->mesh().checksum();
  if (header->base_checksum == base) return {};
  char sums[96];
  std::snprintf(sums, sizeof sums, "(checksum %016llx, this model %016llx)",
                static_cast<unsigned long long>(header->base_checksum),
                static_cast<unsigned long long>(base));
  return hal::Error{StatusCode::failed_precondition,
                    "checkpoint " + parts.checkpoint_out->path() +
                        " was made from another model than " + parts.mesh_path.string() + " " +
                        sums +
                        ": the model changed since this journal was started; refusing to start "
                        "before anything is written (replaying onto it would not give the "
                        "sculpture). Put the original model back, or move the journal and its "
                        "checkpoint aside to start a new sculpture"};
}

hal::Expected<void> stop_requested(const char* during) {
  if (const int sig = hal::startup_stop_signal(); sig != 0) {
    return hal::Error{StatusCode::unavailable, std::string("stopped by signal ") +
                                                   std::to_string(sig) + " during start-up (" +
                                                   during + ")"};
  }
  return {};
}

}  // namespace

// Exhibit mode: the archive (its start-up recovery finishes or rolls back a rotation a
// crash interrupted, before the station reads the journal) and the base model.
hal::Expected<void> open_exhibit(StationParts& parts, const StationFileConfig& config,
                                 station::StationFiles& files) {
  ExhibitArchiveConfig a;
  a.dir = config.exhibit.archive_dir;
  a.journal_path = config.station.journal;
  a.keep_count = config.exhibit.keep_archives;
  a.keep_bytes = config.exhibit.keep_archive_mb << 20;
  ports::Clock* clock = parts.backends.clock.get();
  a.mono_clock = [clock] { return clock->now_us(); };
  // The model's up: +Z in a calibrated work frame, else the transmitter's -Z.
  const glm::vec3 up = config.tracker.calibration.has_work_frame ? glm::vec3(0.0F, 0.0F, 1.0F)
                                                                 : glm::vec3(0.0F, 0.0F, -1.0F);
  parts.archive = std::make_unique<ExhibitArchive>(a, meshio_model_writer(up));
  auto recovered = parts.archive->recover();
  if (!recovered) return recovered.error();
  if (recovered->temporaries_removed > 0) {
    parts.recovery_notes.push_back(
        {true, "exhibit: removed " + std::to_string(recovered->temporaries_removed) +
                   " unfinished archive(s) (the journal still holds the sculpture)"});
  }
  if (recovered->rotation_finished) {
    parts.recovery_notes.push_back(
        {true, "exhibit: the journal was archived as " + recovered->archive_of_journal +
                   " before the stop; the rotation is finished (a new journal begins)"});
  }
  auto base = load_station_mesh(parts.mesh_path, 0);
  if (!base) return base.error();
  parts.base_model = std::move(*base);
  files.archive = parts.archive.get();
  files.base_model = &parts.base_model->mesh();
  files.visitors_today = recovered->visitors_today;
  return {};
}

hal::Expected<std::unique_ptr<meshio::MeshBuffer>> load_station_mesh(
    const std::filesystem::path& path, std::size_t spare_vertices) {
  meshio::ObjOptions options;
  options.spare_vertices = spare_vertices;
  options.spare_triangles = 2 * spare_vertices;  // what refinement of a closed mesh needs
  auto loaded = meshio::load_obj(path, options);
  if (!loaded) {
    return hal::Error{loaded.error().status,
                      "mesh " + path.string() + ": " + loaded.error().message};
  }
  return std::move(loaded->buffer);
}

hal::Expected<std::unique_ptr<StationParts>> assemble_station(const StationFileConfig& config,
                                                              const AssemblyOptions& options) {
  // The backends first: a USB tracker found at start decides the model the session is
  // set up for when tracker.model is not given (with_detected_model). A config error
  // is still reported before a backend's.
  auto backends = make_backends(config);
  auto setup = make_station_setup(backends ? with_detected_model(config, *backends) : config);
  if (!setup) return setup.error();
  if (!backends) return backends.error();
  auto parts = std::make_unique<StationParts>();
  parts->backends = std::move(*backends);
  if (auto opened = open_journal(parts->journal, config.station.journal); !opened) {
    return opened.error();
  }
  // Ours alone now (the lock): what a killed checkpoint or tail writer left goes.
  for (const char* suffix : {".ckpt", ".torn-tail"}) {
    parts->stale_temporaries +=
        hal::PosixFileSink::remove_stale_temporaries(config.station.journal + suffix);
  }
  parts->mesh_path = config.station.mesh;
  if (parts->mesh_path.is_relative()) parts->mesh_path = options.config_dir / parts->mesh_path;
  // Held while the station runs: the tools refuse to write over a locked file.
  auto base_lock = hal::FileReadLock::hold(parts->mesh_path.string());
  if (!base_lock) return hal::Error{base_lock.error().status, "mesh " + base_lock.error().message};
  parts->base_lock = std::move(*base_lock);
  if (auto stop = stop_requested("journal opened"); !stop) return stop.error();
  auto model = load_station_mesh(parts->mesh_path, config.station.spare_vertices);
  if (!model) return model.error();
  parts->model = std::move(*model);
  if (auto stop = stop_requested("model loaded"); !stop) return stop.error();
  mesh::Mesh& mesh = parts->model->mesh();
  parts->work = std::make_unique<WorkMemory>(mesh.vertex_capacity());
  session::SculptStorage storage = parts->work->storage();
  parts->symmetry = std::make_unique<meshio::SymmetryBuffer>(mesh.vertex_capacity());
  storage.plan.symmetry = parts->symmetry->plan_symmetry();
  if (config.sculpt.refine) {
    parts->refine =
        std::make_unique<RefineMemory>(mesh.vertex_capacity(), mesh.triangle_capacity());
    storage = parts->refine->attach(storage);
  }
  Backends& b = parts->backends;
  hal::PosixFileSinkConfig archive;
  archive.path = config.station.journal + ".torn-tail";
  archive.replace = hal::PosixFileSinkConfig::Replace::never;
  parts->tail_archive = std::make_unique<hal::PosixFileSink>(archive);
  if (auto opened = open_checkpoint_files(*parts, config.station.journal); !opened) {
    return opened.error();
  }
  if (auto base = check_checkpoint_base(*parts); !base) return base.error();
  station::StationFiles files;
  files.tail_archive = parts->tail_archive.get();
  files.checkpoint_in = parts->checkpoint_in.get();
  files.checkpoint_out = parts->checkpoint_out.get();
  files.new_journal_id = random_journal_id();
  if (config.exhibit.enabled) {
    if (auto opened = open_exhibit(*parts, config, files); !opened) return opened.error();
  }
  parts->core = std::make_unique<station::Station>(*b.tracker, *b.buttons, *b.clock, parts->journal,
                                                   mesh, storage, *setup, files);
  // Nothing is written to the journal (no torn tail cut, no new header) until every
  // other start-up step has succeeded: a start-up that fails leaves it byte-identical.
  station::Station& core = *parts->core;
  if (const Status s = core.recover(); !s.ok()) {
    return start_error(s, core.recovery(), config.station.journal, parts->journal,
                       *parts->tail_archive);
  }
  if (auto stop = stop_requested("journal replayed"); !stop) return stop.error();
  LinkSection link = config.link;
  if (!options.link_address.empty()) link.address = options.link_address;  // --link wins
  if (!link.address.empty()) {
    if (auto opened = parts->display.open(
            link, core.sculpt(), workspace_of(config.tracker.calibration), hal::process_log());
        !opened) {
      return opened.error();
    }
  }
  if (const Status s = core.begin_appending(); !s.ok()) {
    return start_error(s, core.recovery(), config.station.journal, parts->journal,
                       *parts->tail_archive);
  }
  for (const StationParts::Note& n : recovery_notes(core.recovery(), *parts)) {
    parts->recovery_notes.push_back(n);
  }
  if (parts->stale_temporaries > 0) {
    parts->recovery_notes.push_back(
        {false, "removed " + std::to_string(parts->stale_temporaries) +
                    " temporary file(s) a stopped checkpoint or tail writer left"});
  }
  parts->checkpoint_in.reset();  // read: the next checkpoint replaces it
  return parts;
}

}  // namespace twister::station_app
