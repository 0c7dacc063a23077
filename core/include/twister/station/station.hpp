// Station: the sculpting station's core behind the ports. It owns the Fastrak
// session (tracker ByteStream) and the journal writer (Storage), feeds hand poses
// and button edges (ButtonSource, and the Fastrak stylus where configured) into the
// SculptSession (debounce, button map, interaction machine, warp, undo, journal),
// and is driven by poll() from the composition root's event loop; time comes from
// the Clock port.
// One poll(): drain tracker poses -> hand poses (metres, world frame); drain button
// edges; one session step; its events become StationEvents for the log.
// Hands are valid only while the tracker streams and their pose is fresh: on a loss
// the session holds the stroke (tracking_lost) and cancels it after lost_timeout, so
// an unplug never commits a stroke from stale or missing poses.
// start() replays the journal into the mesh (the same code path as live commits),
// cuts a torn tail, and opens the journal for appending.
// No heap; all working memory is given at construction. Not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "twister/base/result.hpp"
#include "twister/input/sculpt_session.hpp"
#include "twister/journal/journal_writer.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/ports/button_source.hpp"
#include "twister/ports/byte_stream.hpp"
#include "twister/ports/clock.hpp"
#include "twister/ports/storage.hpp"
#include "twister/station/station_event.hpp"
#include "twister/tracker/fastrak_session.hpp"
#include "twister/tracker/pose_conversion.hpp"

namespace twister::station {

struct StationConfig {
  tracker::FastrakSessionConfig session{};
  tracker::PoseConversion conversion{};
  // Fastrak receiver (1..4) held by hand 0 and hand 1.
  std::array<std::uint8_t, input::kHandCount> hand_station{1, 2};
  // A hand's pose older than this counts as not valid (tracker silent or lost).
  ports::TimestampUs pose_stale_us = 200'000;
  // Fastrak stylus switch (item 16) as a button: stylus_line[station - 1] is the
  // button line its state drives (-1 = none). The edge goes through the debouncer
  // like any ButtonSource edge, stamped with the poll time of the record.
  std::array<std::int8_t, tracker::kMaxStations> stylus_line{-1, -1, -1, -1};
  // Debounce, button map, interaction timing, warp method.
  input::SculptSessionConfig sculpt{};
};

struct StationCounters {
  std::uint64_t poses = 0;          // converted poses used for a hand
  std::uint64_t pose_errors = 0;    // poses that failed conversion (skipped)
  std::uint64_t foreign_poses = 0;  // poses of receivers bound to no hand
  std::uint64_t button_edges = 0;   // from the ButtonSource and the stylus
  std::uint64_t button_errors = 0;  // ButtonSource io_error / out-of-range lines
  // Committed warps (journal stroke records): one per release, freeze step or change
  // of the grabbing hands, however many hands took part.
  std::uint64_t strokes_committed = 0;
  std::uint64_t strokes_cancelled = 0;  // grabs dropped (per hand)
  std::uint64_t undos = 0;
  std::uint64_t redos = 0;
  std::uint64_t refined_commits = 0;  // commits that refined the mesh
  std::uint64_t refine_stops = 0;     // of them, stopped at the mesh's capacity
  std::uint64_t refused = 0;
  std::uint64_t session_events_dropped = 0;
  std::uint64_t journal_errors = 0;
  std::uint64_t events_dropped = 0;  // event queue full (the log is behind)
};

class Station {
 public:
  // Ports, mesh and work memory must outlive the station. `mesh` holds the initial
  // model (object frame); the journal's strokes are replayed onto it by start().
  // Nothing happens until start().
  Station(ports::ByteStream& tracker, ports::ButtonSource& buttons, ports::Clock& clock,
          ports::Storage& storage, mesh::Mesh& mesh, input::SculptStorage work,
          const StationConfig& config);

  // Replays the journal onto the mesh, cuts a torn tail and opens the journal for
  // appending. data_loss: the file is not a journal (it is left alone), or a record
  // does not fit this mesh (wrong initial mesh: nothing is written);
  // invalid_argument / resource_exhausted: a record was refused by the warp plan;
  // io_error: storage failed; failed_precondition: hand_station out of 1..4 or both
  // hands on one receiver.
  Status start();

  // One loop iteration (never blocks). failed_precondition: start() did not succeed.
  Status poll();

  // Next event for the log (oldest first). unavailable: none pending.
  Result<StationEvent> next_event();

  // Makes the journal durable (shutdown path); appends already sync each record.
  Status flush();

  const StationCounters& counters() const { return counters_; }
  const tracker::FastrakSession& tracker_session() const { return session_; }
  const input::SculptSession& sculpt() const { return sculpt_; }
  const mesh::Mesh& mesh() const { return sculpt_.mesh(); }
  // Vertex normals of mesh(), up to date after every poll() (empty without storage).
  mesh::NormalColumns normals() const { return sculpt_.normals(); }
  // Refinement: on, threshold, spare capacity, how the last refined commit ended
  // (what a display shows; the link does not carry it yet).
  input::RefineStatus refinement() const { return sculpt_.state().refine; }
  std::uint32_t journal_records() const { return sculpt_.next_sequence(); }
  bool hand_valid(std::uint8_t hand, ports::TimestampUs now_us) const;
  // The frame last applied to `hand` (hand < kHandCount); see hand_valid().
  const tracker::TrackedFrame& hand_pose(std::uint8_t hand) const { return hands_[hand].pose; }

 private:
  struct Hand {
    tracker::TrackedFrame pose{};
    ports::TimestampUs pose_time_us = 0;
    bool has_pose = false;
  };

  void drain_tracker(ports::TimestampUs now_us);
  void drain_buttons(ports::TimestampUs now_us);
  void report(const input::SessionEvent& event, ports::TimestampUs now_us);
  // The sculptor's other actions (radius, clutch, turn limit, undo/redo, method).
  void report_sculpt(const input::SessionEvent& event, ports::TimestampUs now_us);
  void push_event(const StationEvent& event);

  ports::ButtonSource& buttons_;
  ports::Clock& clock_;
  ports::Storage& storage_;
  StationConfig config_;
  tracker::FastrakSession session_;
  journal::JournalWriter writer_;  // before sculpt_, which keeps a pointer to it
  input::SculptSession sculpt_;
  std::array<Hand, input::kHandCount> hands_{};
  std::array<bool, tracker::kMaxStations> stylus_down_{};
  bool started_ = false;
  bool buttons_failed_ = false;
  bool was_streaming_ = false;
  StationCounters counters_{};
  static constexpr std::size_t kEventCapacity = 64;
  std::array<StationEvent, kEventCapacity> events_{};
  std::size_t event_head_ = 0;
  std::size_t event_count_ = 0;
};

}  // namespace twister::station
