// Station: the sculpting station's core behind the ports. It owns the Fastrak
// session (tracker ByteStream), the button debouncer and map (ButtonSource), the
// interaction machine and the stroke journal (Storage), and is driven by poll()
// from the composition root's event loop; time comes from the Clock port.
// One poll(): drain tracker poses -> hand poses (metres, world frame); drain button
// edges -> debounced events -> per-hand levels; one interaction step; apply its
// actions: on commit / freeze the stroke (start and end pose of the hand, radius) is
// appended to the journal and synced before poll() returns.
// Strokes are only built from valid poses: while the tracker is lost the machine
// holds the stroke (dragging_lost) and cancels it after lost_timeout, so an unplug
// never commits a stroke from stale or missing poses.
// No heap; all storage is inside the object. Not thread-safe (one loop thread).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "twister/base/result.hpp"
#include "twister/input/button_debouncer.hpp"
#include "twister/input/button_map.hpp"
#include "twister/input/interaction_machine.hpp"
#include "twister/journal/journal_writer.hpp"
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
  input::ButtonDebouncerConfig debounce{};
  input::ButtonMap buttons = input::ButtonMap::paper_default();
  input::InteractionConfig interaction{};
  std::uint8_t warp_method = 0;  // math::WarpMethod as a number, stored in strokes
};

struct StationCounters {
  std::uint64_t poses = 0;             // converted poses used for a hand
  std::uint64_t pose_errors = 0;       // poses that failed conversion (skipped)
  std::uint64_t foreign_poses = 0;     // poses of receivers bound to no hand
  std::uint64_t button_edges = 0;     // from the ButtonSource and the stylus
  std::uint64_t button_errors = 0;     // ButtonSource io_error / out-of-range lines
  std::uint64_t strokes_committed = 0;
  std::uint64_t strokes_cancelled = 0;
  std::uint64_t refused = 0;
  std::uint64_t journal_errors = 0;
  std::uint64_t events_dropped = 0;    // event queue full (the log is behind)
};

class Station {
 public:
  // Ports must outlive the station. Nothing happens until start().
  Station(ports::ByteStream& tracker, ports::ButtonSource& buttons, ports::Clock& clock,
          ports::Storage& storage, const StationConfig& config);

  // Recovers the journal (reads it to the end, cuts a torn tail) and opens it for
  // appending. data_loss: the file is not a journal (refuse to run: it is left
  // alone); io_error: storage failed; invalid_argument: hand_station out of 1..4 or
  // both hands on one receiver.
  Status start();

  // One loop iteration (never blocks). failed_precondition: start() did not succeed.
  Status poll();

  // Next event for the log (oldest first). unavailable: none pending.
  Result<StationEvent> next_event();

  // Makes the journal durable (shutdown path); appends already sync each record.
  Status flush();

  const StationCounters& counters() const { return counters_; }
  const tracker::FastrakSession& tracker_session() const { return session_; }
  const input::InteractionMachine& interaction() const { return machine_; }
  std::uint32_t journal_records() const { return next_sequence_; }
  bool hand_valid(std::uint8_t hand, ports::TimestampUs now_us) const;

 private:
  struct Hand {
    tracker::TrackedFrame pose{};
    ports::TimestampUs pose_time_us = 0;
    bool has_pose = false;
    tracker::TrackedFrame stroke_start{};
    std::uint16_t chain_step = 0;
  };

  void drain_tracker(ports::TimestampUs now_us);
  void drain_buttons(ports::TimestampUs now_us);
  void apply(const input::Action& action, ports::TimestampUs now_us);
  void commit_stroke(std::uint8_t hand, ports::TimestampUs now_us);
  void push_event(const StationEvent& event);

  ports::ButtonSource& buttons_;
  ports::Clock& clock_;
  ports::Storage& storage_;
  StationConfig config_;
  tracker::FastrakSession session_;
  input::ButtonDebouncer debouncer_;
  input::InteractionMachine machine_;
  journal::JournalWriter writer_;
  std::array<Hand, input::kHandCount> hands_{};
  std::array<input::HandButtons, input::kHandCount> levels_{};
  std::array<bool, tracker::kMaxStations> stylus_down_{};
  bool started_ = false;
  bool buttons_failed_ = false;
  bool was_streaming_ = false;
  std::uint32_t next_sequence_ = 0;
  StationCounters counters_{};
  static constexpr std::size_t kEventCapacity = 64;
  std::array<StationEvent, kEventCapacity> events_{};
  std::size_t event_head_ = 0;
  std::size_t event_count_ = 0;
};

}  // namespace twister::station
