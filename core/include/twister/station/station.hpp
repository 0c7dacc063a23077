// Station: the sculpting station's core behind the ports. It owns the Fastrak
// session (tracker ByteStream) and the journal writer (Storage), feeds hand poses
// and button edges (ButtonSource, and the Fastrak stylus where configured) into the
// SculptSession (debounce, button map, interaction machine, warp, undo, journal),
// and is driven by poll() from the composition root's event loop; time comes from
// the Clock port.
// One poll(): drain tracker poses -> hand poses (metres, world frame) (TrackerHands);
// drain button edges; one session step; its events, and the station's own, are
// counted (EventCounters) and queued for the log (EventQueue) as they are: the
// station's events are the session's vocabulary (session_events.hpp). Checkpoints
// are written a chunk per poll (CheckpointSchedule).
// Hands are valid only while the tracker streams and their pose is fresh: on a loss
// the session holds the stroke (tracking_lost) and cancels it after lost_timeout, so
// an unplug never commits a stroke from stale or missing poses.
// start() checks the whole journal (JournalScanner), refuses a corrupt one (a damaged
// record with valid records after it: the file is left untouched), restores the last
// checkpoint when one fits, replays the records after it into the mesh (the same code
// path as live commits), cuts a torn tail (keeping its bytes through a FileSink) and
// opens the journal for appending. A composition root with more start-up steps that can
// fail calls recover() (which changes no file), then its steps, then begin_appending()
// (which cuts the torn tail and writes a new journal's header), so a start-up that
// fails leaves the journal byte-identical.
// No heap; all working memory is given at construction. Not thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>

#include "twister/base/result.hpp"
#include "twister/checkpoint/session_checkpoint.hpp"
#include "twister/journal/journal_scanner.hpp"
#include "twister/journal/journal_writer.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/ports/button_source.hpp"
#include "twister/ports/byte_stream.hpp"
#include "twister/ports/clock.hpp"
#include "twister/ports/file_sink.hpp"
#include "twister/ports/storage.hpp"
#include "twister/session/sculpt_session.hpp"
#include "twister/session/session_events.hpp"
#include "twister/station/checkpoint_schedule.hpp"
#include "twister/station/event_queue.hpp"
#include "twister/station/sculpture_archive.hpp"
#include "twister/station/station_config.hpp"
#include "twister/station/station_counters.hpp"
#include "twister/station/station_exhibit.hpp"
#include "twister/station/station_status.hpp"
#include "twister/station/tracker_hands.hpp"
#include "twister/tracker/fastrak_session.hpp"

namespace twister::station {

// The station's files besides the journal (all optional).
struct StationFiles {
  // Receives the bytes of a torn journal tail before start() cuts it (a new file,
  // never an existing one). Null: the tail is cut without a copy.
  ports::FileSink* tail_archive = nullptr;
  // The last checkpoint, read by start() (null: none). Ignored when it does not fit
  // the journal or the model (JournalRecovery::checkpoint says why).
  ports::Storage* checkpoint_in = nullptr;
  // Where checkpoints go (null: none are written).
  ports::FileSink* checkpoint_out = nullptr;
  // The identity a new journal gets (journal_format.hpp; the program picks a random one).
  std::uint32_t new_journal_id = 0;
  // Exhibit mode (config.exhibit.visitor.enabled; both required then): where finished
  // sculptures are archived, and the initial model the mesh is reset to after each
  // (the same model the mesh held at construction; it must outlive the station).
  SculptureArchive* archive = nullptr;
  const mesh::Mesh* base_model = nullptr;
  // Sculptures archived today before this run (the visitor numbers go on from it).
  std::uint32_t visitors_today = 0;
};

// What start() found in the journal (for the start-up log and its error messages).
struct JournalRecovery {
  enum class Outcome : std::uint8_t {
    not_started,
    recovered,      // recover() replayed it; begin_appending() has not run yet
    ok,             // replayed (a torn tail, if any, was cut: tail_cut bytes)
    not_a_journal,  // foreign file: left alone
    corrupt,        // damage followed by valid records, or a complete record that is
                    // refused (unknown version or type, invalid values, another
                    // journal's, out of order): refused, left untouched
    too_new,        // a journal of a newer format version: refused, left untouched
    does_not_fit,   // a record cannot be applied to this mesh (record_index, status)
    tail_not_kept,  // the torn tail could not be copied aside: refused, left untouched
    io_error,       // storage failed
  };
  Outcome outcome = Outcome::not_started;
  journal::JournalSurvey survey{};
  std::uint64_t replayed = 0;  // records applied by start()
  std::uint64_t tail_cut = 0;  // bytes of a torn tail cut (kept when tail_archive is set)
  bool tail_kept = false;      // they went to the tail archive
  enum class Checkpoint : std::uint8_t {
    none,           // no checkpoint file
    used,           // restored: checkpoint_records came from it, `replayed` after it
    damaged,        // ignored: not a checkpoint (or format version 1), or its checks fail
    other_model,    // ignored: made from another initial model, mesh capacity or history size
    other_journal,  // ignored: its anchor is not a record boundary of this journal
  };
  Checkpoint checkpoint = Checkpoint::none;
  std::uint64_t checkpoint_records = 0;
  std::uint64_t record_index = 0;  // does_not_fit: the record (0-based, in file order)
  std::uint32_t record_sequence = 0;
  Status record_status{};
};
const char* recovery_outcome_name(JournalRecovery::Outcome outcome);
const char* checkpoint_use_name(JournalRecovery::Checkpoint use);

class Station {
 public:
  // Ports, mesh and work memory must outlive the station. `mesh` holds the initial
  // model (object frame); the journal's strokes are replayed onto it by start().
  // Nothing happens until start().
  Station(ports::ByteStream& tracker, ports::ButtonSource& buttons, ports::Clock& clock,
          ports::Storage& storage, mesh::Mesh& mesh, session::SculptStorage work,
          const StationConfig& config, StationFiles files = {});

  // Checks and replays the journal onto the mesh, cuts a torn tail (after copying it
  // to files.tail_archive) and opens the journal for appending. recovery() says what
  // was found. data_loss: the file is not a journal, is corrupt (a damaged record with
  // valid records after it), or a record does not fit this mesh; in each case the file
  // is left byte-identical. invalid_argument / resource_exhausted: a record was refused
  // by the warp plan; io_error: storage failed or the torn tail could not be kept;
  // failed_precondition: hand_station out of 1..4 or both hands on one receiver.
  Status start();
  // start() in two steps. recover(): every check and the replay, nothing written (the
  // same errors as start(), except those of cutting and opening).
  // begin_appending(): keeps and cuts a torn tail and opens the journal for appending
  // (io_error: storage failed, e.g. a full disk for a new journal's header, or the
  // tail could not be kept; failed_precondition: recover() did not succeed).
  Status recover();
  Status begin_appending();
  const JournalRecovery& recovery() const { return recovery_; }

  // One loop iteration (never blocks). failed_precondition: start() did not succeed.
  Status poll();

  // Next event for the log (oldest first, time_us set). unavailable: none pending.
  Result<session::SessionEvent> next_event() { return events_.pop(); }

  // The stop policy (SIGTERM, SIGHUP, SIGINT, end of run): an open stroke is
  // cancelled, never committed (the model stays as after the last commit; the sculptor
  // did not release it), an open object move is cancelled (the object goes back).
  // Each cancelled hand counts in strokes_cancelled and is reported as cancelled
  // with reason input::Reason::stopped (a move: move_cancelled, stopped). Then a
  // checkpoint of the final model is written (when the journal grew since the last
  // one; checkpoint_written / checkpoint_failed). Afterwards poll() is not called again.
  void stop();

  // Makes the journal durable (shutdown path); appends already sync each record.
  Status flush();

  const StationCounters& counters() const { return counters_; }
  const tracker::FastrakSession& tracker_session() const { return tracker_.session(); }
  const session::SculptSession& sculpt() const { return sculpt_; }
  // Queues a session command (undo, redo, method) for the next poll(): the path
  // of the hands' buttons, also used by the display's keys (StationLink commands).
  // Errors as SculptSession::submit().
  // Exhibit mode: new_sculpture / undo_new_sculpture act on the visitor lifecycle at
  // once (new_sculpture(), undo_new_sculpture()); with it off the session refuses them.
  Status submit(const session::SessionCommand& command);
  const mesh::Mesh& mesh() const { return sculpt_.mesh(); }
  // Records in the journal file: the ones found at start() plus every record
  // appended (and synced) since.
  std::uint32_t journal_records() const {
    return static_cast<std::uint32_t>(records_at_start_ + writer_.appended());
  }
  // Where a checkpoint of the model as it stands would be anchored in the journal.
  checkpoint::CheckpointAnchor checkpoint_anchor() const {
    return {writer_.size(), journal_records(), writer_.last_crc()};
  }
  // Vertex normals of mesh(), up to date after every poll() (empty without storage).
  mesh::NormalColumns normals() const { return sculpt_.normals(); }
  // Refinement: on, threshold, spare capacity, how the last refined commit ended
  // (what a display shows).
  session::RefineStatus refinement() const { return sculpt_.state().refine; }
  bool hand_valid(std::uint8_t hand, ports::TimestampUs now_us) const {
    return tracker_.hand_valid(hand, now_us);
  }
  // The frame last applied to `hand` (hand < kHandCount); see hand_valid().
  const Pose& hand_pose(std::uint8_t hand) const { return tracker_.hand_pose(hand); }
  // What the display link reports about the station (as of the last poll()).
  StationStatus status() const;

  // Exhibit mode (issue 25; docs/interaction.md "The visitor lifecycle"). The display's
  // new_sculpture / undo_new_sculpture commands: the sculpture ends (the grace
  // begins) / its end is undone in the grace. failed_precondition: nothing to act on
  // (also reported as a visitor event, note refused), or exhibit mode is off.
  Status new_sculpture();
  Status undo_new_sculpture();
  // The visitor's phase, number, time left (as of the last poll()).
  VisitorView visitor_view() const;
  bool visitor_view_enabled() const { return exhibit_.enabled(); }
  const ExhibitCounters& exhibit_counters() const { return exhibit_.counters(); }
  // What the display shows briefly: the notices of the events emitted so far (refused
  // undo / redo / commands / presses, the symmetry changed, the lifecycle's notes),
  // exhibit mode on or off; StationLink sends the ones its display has not had.
  const NoticeBoard& notices() const { return events_.notices(); }

 private:
  // start()'s steps (station_start.cpp).
  Status replay_journal(journal::JournalReader& reader);
  Status keep_torn_tail();
  // Restores files_.checkpoint_in when it fits the survey's journal and the model.
  Status use_checkpoint(const checkpoint::CheckpointHeader& header,
                        const journal::JournalSurvey& survey);
  void drain_buttons(ports::TimestampUs now_us);
  // Every event the station reports passes here: stamped, counted, queued.
  void emit(session::SessionEvent event, ports::TimestampUs now_us);
  void emit_all(const session::SessionEvents& events, ports::TimestampUs now_us);
  // Exhibit mode (station_exhibit.cpp): one lifecycle step, what its action asks
  // (archive, rotate, reset), and a new journal begun again after a failure.
  void step_exhibit(ports::TimestampUs now_us);
  void act(session::VisitorAction action, ports::TimestampUs now_us);
  void end_sculpture(ports::TimestampUs now_us);
  Status rotate_journal(ports::TimestampUs now_us);
  void note(session::VisitorNote what, ports::TimestampUs now_us, Status status = {});

  ports::ButtonSource& buttons_;
  ports::Clock& clock_;
  ports::Storage& storage_;
  StationFiles files_;
  JournalRecovery recovery_{};
  StationConfig config_;
  TrackerHands tracker_;           // after config_, which it reads
  journal::JournalWriter writer_;  // before sculpt_, which keeps a pointer to it
  session::SculptSession sculpt_;
  CheckpointSchedule checkpoints_;
  EventQueue events_;
  StationCounters counters_{};
  StationExhibit exhibit_;
  std::uint64_t records_at_start_ = 0;
  bool started_ = false;
};

}  // namespace twister::station
