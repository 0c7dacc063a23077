// StationExhibit: the station's part of exhibit mode (issue 25). It owns the
// VisitorLifecycle, the raw levels of the button lines (for the new-sculpture chord),
// today's visitor number, the archive's trouble flags and the exhibit's counters; the
// Station feeds it each poll and does the archive and the rotation it asks for
// (station_exhibit.cpp). Exhibit mode off: it never acts. Plain data, no heap.
#pragma once

#include <cstdint>

#include "twister/ports/button_source.hpp"
#include "twister/ports/clock.hpp"
#include "twister/session/visitor_lifecycle.hpp"

namespace twister::station {

struct ExhibitConfig {
  session::VisitorConfig visitor{};
  // Button lines (bit i = line i) that, all held for visitor.chord_hold_us, end the
  // sculpture (and undo its end in the grace). 0: no chord (idle and the display's
  // command only). The config refuses lines of grab or move_object and existing chords.
  std::uint16_t chord_lines = 0;
};

// VisitorView::flags (the link's VisitorState flags carry the same bits).
inline constexpr std::uint8_t kVisitorFlagResetUndoable = 1u << 0;
inline constexpr std::uint8_t kVisitorFlagArchiveFailed = 1u << 1;
inline constexpr std::uint8_t kVisitorFlagDiskFull = 1u << 2;

// What the display shows about the visitor (Station::visitor_view()).
struct VisitorView {
  session::VisitorPhase phase = session::VisitorPhase::attract;
  std::uint8_t flags = 0;
  std::uint32_t visitor = 0;    // today's number of the current (or last) visitor
  std::uint32_t sculpture = 0;  // the current journal's identity
  std::uint32_t records = 0;    // its records so far
  float idle_left_s = 0.0F;
  float grace_left_s = 0.0F;
  friend bool operator==(const VisitorView&, const VisitorView&) = default;
};

struct ExhibitCounters {
  std::uint64_t visitors = 0;          // sculptures begun this run
  std::uint64_t archived = 0;          // archives written (journal rotated)
  std::uint64_t archive_failures = 0;  // archive attempts that failed
  std::uint64_t disk_full = 0;         // of them, on a full disk
  std::uint64_t rotate_failures = 0;   // new journals that could not be begun
  std::uint64_t undone = 0;            // ends undone in the grace
  std::uint64_t refused = 0;           // new / undo with nothing to act on
  // Sculptures ended today and archived (the journal rotated): at start-up the highest
  // visitor number of today's archives (the hal's count), plus each archived since
  // (the metrics' visitors today).
  std::uint64_t ended_today = 0;
};

class StationExhibit {
 public:
  explicit StationExhibit(const ExhibitConfig& config)
      : life_(config.visitor), chord_lines_(config.chord_lines) {}

  bool enabled() const { return life_.enabled(); }
  // Start-up: `visitors_today` archives were written today (the hal counts them);
  // a journal holding a sculpture is the next visitor's, still sculpting.
  void start(bool has_sculpture, std::uint32_t visitors_today, ports::TimestampUs now_us);
  void feed_edge(const ports::ButtonEdge& edge);
  bool chord_held() const { return chord_lines_ != 0 && (levels_ & chord_lines_) == chord_lines_; }

  session::VisitorLifecycle& life() { return life_; }
  const session::VisitorLifecycle& life() const { return life_; }
  ExhibitCounters& counters() { return counters_; }
  const ExhibitCounters& counters() const { return counters_; }
  std::uint32_t visitor() const { return visitor_; }
  void next_visitor(ports::TimestampUs now_us) {
    ++visitor_;
    began_us_ = now_us;
    ++counters_.visitors;
  }
  ports::TimestampUs began_us() const { return began_us_; }
  ports::TimestampUs ended_us() const { return ended_us_; }
  void set_ended(ports::TimestampUs now_us) { ended_us_ = now_us; }
  std::uint8_t& trouble() { return trouble_; }  // kVisitorFlagArchiveFailed / DiskFull
  std::uint8_t trouble() const { return trouble_; }
  ports::TimestampUs& journal_retry_us() { return journal_retry_us_; }
  // The time of the last poll (what visitor_view() counts the time left from).
  ports::TimestampUs& now_us() { return now_us_; }
  ports::TimestampUs now_us() const { return now_us_; }

 private:
  session::VisitorLifecycle life_;
  std::uint16_t chord_lines_ = 0;
  std::uint16_t levels_ = 0;  // raw levels of lines 0..15
  std::uint32_t visitor_ = 0;
  ports::TimestampUs began_us_ = 0;
  ports::TimestampUs ended_us_ = 0;
  ports::TimestampUs journal_retry_us_ = 0;  // next try to begin a new journal
  ports::TimestampUs now_us_ = 0;
  std::uint8_t trouble_ = 0;
  ExhibitCounters counters_{};
};

}  // namespace twister::station
