// ExhibitArchive: the SculptureArchive port over a directory (issue 25, exhibit mode).
// One directory per sculpture, ARCHIVE/YYYYMMDDTHHMMSSZ-vNNNN-IIIIIIII (UTC time of
// the archive, today's visitor number, the journal's identity in hex), holding
//   journal.twj    the sculpture's journal, byte for byte
//   model.stl      the final model (ArchiveModelWriter)
//   model.glb      the final model, binary glTF (ArchiveModelWriter)
//   thumbnail.png  a picture of it (ArchiveModelWriter)
//   record.json    times, visitor, end, records, strokes, undos, counts, checksum
// Built in ARCHIVE/.tmp-IIIIIIII-PID, every file fsynced, the directory fsynced, then
// renamed to its name and ARCHIVE fsynced: a crash leaves no directory under a final
// name that is not complete. The retention budget (count, bytes) then removes the
// oldest archives (never the newest; only directories of this naming holding only
// these file names: anything else is left alone). recover() at start-up, with the
// journal's lock held, removes our temporaries and finishes a rotation that a crash
// interrupted (docs/reliability.md "Exhibit mode"). The hal may allocate here (one
// archive per visitor, never in a stroke); errors carry errno for the log.
#pragma once

#include <cstdint>
#include <ctime>
#include <functional>
#include <glm/vec3.hpp>
#include <memory>
#include <string>
#include <vector>

#include "twister/hal/expected.hpp"
#include "twister/station/sculpture_archive.hpp"

namespace twister::station_app {

// Writes the final model's files (the swappable part: hal/meshio's writers when they
// are there). Each writes a new file at `path` (O_EXCL) and returns errno on failure.
class ArchiveModelWriter {
 public:
  virtual ~ArchiveModelWriter() = default;
  virtual int write_stl(const std::string& path, const mesh::Mesh& mesh, const Pose& pose) = 0;
  virtual int write_glb(const std::string& path, const mesh::Mesh& mesh, const Pose& pose) = 0;
  virtual int write_thumbnail(const std::string& path, const mesh::Mesh& mesh,
                              const Pose& pose) = 0;
};
// hal/meshio's writers (exhibit_model_files.cpp): `up` is the model's up in its own
// frame (+Z with a calibrated work frame, -Z in the transmitter frame).
std::unique_ptr<ArchiveModelWriter> meshio_model_writer(glm::vec3 up);

// The steps of the on-disk protocol (docs/reliability.md "Exhibit mode"), for the
// crash tests' hook: each is reported once it is done.
enum class ArchiveStep : std::uint8_t {
  temporary_made,     // ARCHIVE/.tmp-ID-PID created
  journal_copied,     // journal.twj written and fsynced
  stl_written,        // model.stl
  glb_written,        // model.glb
  thumbnail_written,  // thumbnail.png
  record_written,     // record.json written and fsynced
  temporary_synced,   // the temporary directory fsynced
  renamed,            // renamed to its final name (ARCHIVE not yet fsynced)
  archive_synced,     // ARCHIVE fsynced: archive() is about to return ok
  prune_renamed,      // an old archive renamed to ARCHIVE/.tmp-prune-NAME (not emptied)
};

struct ExhibitArchiveConfig {
  std::string dir;                 // the archive directory (created when missing)
  std::string journal_path;        // the station's journal (recover())
  std::uint32_t keep_count = 500;  // archives kept (at least 1)
  std::uint64_t keep_bytes = 2ULL << 30;
  // Wall-clock seconds (UTC) for names and records; the day test's virtual day.
  std::function<std::time_t()> wall_clock;
  // The monotonic clock's now (the station's Clock) for the records' times.
  std::function<ports::TimestampUs()> mono_clock;
  // Tests only (crash injection): called after each step; empty in the station.
  std::function<void(ArchiveStep)> step_hook;
};

struct ArchiveRecovery {
  int temporaries_removed = 0;
  bool rotation_finished = false;  // the journal was archived: it was cut
  std::uint32_t visitors_today = 0;
  std::string archive_of_journal;  // rotation_finished: which archive holds it
};

struct ArchiveStats {
  std::uint64_t written = 0;
  std::uint64_t failed = 0;
  std::uint64_t disk_full = 0;
  std::uint64_t pruned = 0;
  std::uint32_t kept = 0;  // archives present after the last prune
  std::uint64_t kept_bytes = 0;
  int last_errno = 0;
  std::string last_error;    // what failed, for the log
  std::string last_archive;  // the directory of the last archive written
};

class ExhibitArchive final : public station::SculptureArchive {
 public:
  ExhibitArchive(ExhibitArchiveConfig config, std::unique_ptr<ArchiveModelWriter> writer);
  // Start-up (after the journal's lock is taken, before the station reads it).
  hal::Expected<ArchiveRecovery> recover();
  const ArchiveStats& stats() const { return stats_; }
  // Our archive directories, oldest first (names only).
  std::vector<std::string> list() const;

 private:
  station::ArchiveOutcome do_archive(const station::SculptureSummary& summary,
                                     ports::Storage& journal, std::uint64_t journal_bytes,
                                     const mesh::Mesh& mesh, const Pose& object_pose) override;
  std::uint32_t do_next_journal_id() override;
  station::ArchiveOutcome fail(int err, const std::string& what, const std::string& tmp);
  void prune(const std::string& keep);
  void step(ArchiveStep s) const {
    if (config_.step_hook) config_.step_hook(s);
  }

  ExhibitArchiveConfig config_;
  std::unique_ptr<ArchiveModelWriter> writer_;
  ArchiveStats stats_;
};

// Whether `name` is one of our archive directory names; its identity and visitor.
bool parse_archive_name(const std::string& name, std::uint32_t* id, std::uint32_t* visitor,
                        std::string* day);

}  // namespace twister::station_app
