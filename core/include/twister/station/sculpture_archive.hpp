// SculptureArchive port (issue 25, exhibit mode): where a finished sculpture goes
// before the journal rotates. archive() writes, atomically and durably, the archive of
// the sculpture that ends: a byte copy of its journal, the final model and a small
// record; it returns ok only once all of it is on disk under its final name, so the
// station may then cut the journal (JournalWriter::restart) and reset the model. The
// POSIX backend (hal/twister-station/exhibit) writes a directory per sculpture and
// applies the retention budget; the test fakes fail on demand. Not thread-safe.
#pragma once

#include <cstdint>

#include "twister/base/pose.hpp"
#include "twister/base/status.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/ports/clock.hpp"
#include "twister/ports/storage.hpp"
#include "twister/session/visitor_lifecycle.hpp"

namespace twister::station {

struct SculptureSummary {
  std::uint32_t sculpture = 0;  // the journal's identity
  std::uint32_t visitor = 0;    // today's number
  std::uint32_t records = 0;    // journal records
  std::uint64_t checksum = 0;   // the model's (mesh::Mesh::checksum)
  session::SculptureEnd end = session::SculptureEnd::none;
  ports::TimestampUs began_us = 0;  // the first grab (or the start of this run)
  ports::TimestampUs ended_us = 0;  // the end (before the grace)
  ports::TimestampUs now_us = 0;    // when the archive is written
};

struct ArchiveOutcome {
  Status status{};         // ok: durable under its final name
  bool disk_full = false;  // the failure was a full disk (ENOSPC, EDQUOT, EFBIG)
};

class SculptureArchive {
 public:
  virtual ~SculptureArchive() = default;
  // Copies `journal` (its first `journal_bytes`), writes `mesh` (placed by
  // `object_pose`) and the summary. Idempotent: an archive of the same sculpture
  // holding the same journal bytes is reused (ok).
  ArchiveOutcome archive(const SculptureSummary& summary, ports::Storage& journal,
                         std::uint64_t journal_bytes, const mesh::Mesh& mesh,
                         const Pose& object_pose) {
    return do_archive(summary, journal, journal_bytes, mesh, object_pose);
  }
  // The identity of the next journal (random, never 0).
  std::uint32_t next_journal_id() { return do_next_journal_id(); }

 private:
  virtual ArchiveOutcome do_archive(const SculptureSummary& summary, ports::Storage& journal,
                                    std::uint64_t journal_bytes, const mesh::Mesh& mesh,
                                    const Pose& object_pose) = 0;
  virtual std::uint32_t do_next_journal_id() = 0;
};

}  // namespace twister::station
