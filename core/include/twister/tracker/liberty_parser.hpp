// LibertyParser: incremental byte-in, event-out parser of Liberty / Patriot / Latus binary
// frames (docs/liberty-protocol.md §4). It produces the Fastrak parser's event type, so the
// station consumes either. Pure: no I/O, clock or log; any split of the stream (one byte at a
// time included) yields the same events. Fixed storage (one pending candidate of at most
// kLibertyMaxFrameBytes), no heap, no exceptions. Not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/result.hpp"
#include "twister/tracker/fastrak_event.hpp"
#include "twister/tracker/frame_scanner.hpp"
#include "twister/tracker/liberty_wire.hpp"

namespace twister::tracker {

struct LibertyParserCounters {
  std::uint64_t bytes = 0;          // bytes consumed
  std::uint64_t poses = 0;          // pose events
  std::uint64_t errors = 0;         // plausibility-error events
  std::uint64_t resyncs = 0;        // resync events (runs of dropped bytes)
  std::uint64_t dropped_bytes = 0;  // bytes that belonged to no accepted frame
  std::uint64_t bad_frames = 0;     // candidates with the model's tag that were rejected
  std::uint64_t oversize = 0;       // of those: announced a size beyond the bound
};

class LibertyParser {
 public:
  // The configuration must pass validate(); otherwise every byte counts as dropped.
  explicit LibertyParser(const LibertyConfig& config = {});

  // Replaces the configuration and clears pending bytes (counters are kept).
  // invalid_argument: the configuration is invalid (see validate()).
  Status configure(const LibertyConfig& config);
  const LibertyConfig& config() const { return config_; }

  // Pulls the next event, consuming bytes from the front of `input` (advanced past
  // them). Events: pose, error (implausible values in a well-framed frame), resync (a
  // run of dropped bytes, reported before the frame that ends it).
  // unavailable: `input` is used up and no event is complete.
  Result<FastrakEvent> next(std::span<const std::byte>& input);

  // End of the stream: pending partial bytes count as dropped and the run is reported.
  // unavailable: nothing pending.
  Result<FastrakEvent> finish();

  // Drops pending bytes without reporting them (e.g. after a device reset).
  void reset();

  template <typename Sink>
  void feed(std::span<const std::byte> input, Sink&& sink) {
    for (;;) {
      auto ev = next(input);
      if (!ev.ok()) return;
      sink(*ev);
    }
  }

  const LibertyParserCounters& counters() const { return counters_; }

 private:
  template <std::size_t>
  friend class FrameScanner;  // the byte loop, with this parser as its codec
  using Verdict = FrameVerdict;
  struct Candidate {
    Verdict verdict = Verdict::drop;
    std::size_t length = 0;  // need_more: total bytes needed; accept: bytes consumed
    bool tagged = false;     // drop: the candidate began with the model's tag
    bool oversize = false;   // drop: its size field exceeded the bound
  };

  Candidate examine(const std::byte* p, std::size_t avail, FastrakEvent& out) const;
  Candidate decode_body(const std::byte* frame, std::size_t station, std::size_t len,
                        FastrakEvent& out) const;
  bool can_start(std::byte b) const;
  Candidate at_end(const Candidate& waiting, const std::byte* p, std::size_t n) const;
  void reject(const Candidate& c);
  void count(const FastrakEvent& ev);

  LibertyConfig config_{};
  bool config_ok_ = false;
  std::array<std::uint16_t, kLibertyMaxStations> body_len_{};  // 0 = station disabled
  FrameScanner<kLibertyMaxFrameBytes> scan_;
  LibertyParserCounters counters_{};
};

}  // namespace twister::tracker
