// StationEvent: what the station reports to the composition root's log (tracker
// up/down, strokes committed or cancelled, refusals, journal and button failures).
// Plain data; the station never formats text.
#pragma once

#include <cstdint>

#include "twister/base/status.hpp"
#include "twister/ports/clock.hpp"

namespace twister::station {

enum class StationEventKind : std::uint8_t {
  journal_recovered,    // start(): `sequence` good records; `value` torn-tail bytes cut
  tracker_streaming,    // the Fastrak session reached streaming (value = start-ups so far)
  tracker_lost,         // streaming stopped (unplug, silence, garbage); re-init follows
  stroke_begin,         // hand grabbed
  stroke_committed,     // journal record `sequence` appended and synced
  stroke_cancelled,     // dropped (tracking lost too long); model unchanged
  refused,              // a press was refused; value = input::Reason
  journal_error,        // a journal operation failed; status says how
  button_source_error,  // the button device failed; status says how
  stroke_not_saved,     // a commit (stroke segment or object move; `hand`) was NOT made:
                        // its record could not be made durable (status, e.g. io_error
                        // for a full disk); the model is back at the last saved record.
                        // value: input::Reason (released: the hand's grab ended)
  checkpoint_written,   // a checkpoint holding the first `sequence` records; value: bytes
  checkpoint_failed,    // writing a checkpoint failed (status); the previous one stays
};

const char* station_event_kind_name(StationEventKind kind);

struct StationEvent {
  StationEventKind kind = StationEventKind::tracker_lost;
  std::uint8_t hand = 0;
  std::uint32_t sequence = 0;
  std::uint64_t value = 0;  // kind-specific (see above; committed/cancelled/refused: input::Reason)
  Status status{};
  ports::TimestampUs time_us = 0;
};

}  // namespace twister::station
