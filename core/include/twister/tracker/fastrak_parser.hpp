// FastrakParser: incremental byte-in, event-out parser of the Fastrak record stream
// (docs/fastrak-protocol.md §3.7/§3.8). Pure: no I/O, clock or log; fed any split of the stream
// (one byte at a time included) it yields the same events. Fixed storage (one pending candidate, at
// most kMaxReplyBytes/kMaxRecordBytes), no heap, no exceptions. Not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/result.hpp"
#include "twister/tracker/fastrak_event.hpp"
#include "twister/tracker/fastrak_wire.hpp"
#include "twister/tracker/frame_scanner.hpp"

namespace twister::tracker {

struct FastrakParserCounters {
  std::uint64_t bytes = 0;          // bytes consumed
  std::uint64_t poses = 0;          // pose events
  std::uint64_t errors = 0;         // plausibility-error events
  std::uint64_t resyncs = 0;        // resync events (runs of dropped bytes)
  std::uint64_t dropped_bytes = 0;  // bytes that belonged to no accepted item
  std::uint64_t replies = 0;        // status + other reply events
};

class FastrakParser {
 public:
  // The configuration must pass validate(); otherwise the parser accepts nothing
  // and every byte counts as dropped (configure() reports the error).
  explicit FastrakParser(const FastrakConfig& config = {});

  // Replaces the configuration and clears pending bytes (counters are kept).
  // invalid_argument: the configuration is invalid (see validate()).
  Status configure(const FastrakConfig& config);
  const FastrakConfig& config() const { return config_; }

  // Pulls the next event, consuming bytes from the front of `input` (which is
  // advanced past them). unavailable: `input` is used up and no event is complete
  // (a partial candidate is kept for the next call).
  Result<FastrakEvent> next(std::span<const std::byte>& input);

  // End of the stream: reports the pending run of dropped bytes (pending partial
  // bytes count as dropped) as a resync. unavailable: nothing pending.
  Result<FastrakEvent> finish();

  // Drops pending bytes without reporting them (e.g. after a device reset).
  void reset();

  // Feeds a whole span, calling sink(const FastrakEvent&) for each event.
  template <typename Sink>
  void feed(std::span<const std::byte> input, Sink&& sink) {
    for (;;) {
      auto ev = next(input);
      if (!ev.ok()) return;
      sink(*ev);
    }
  }

  const FastrakParserCounters& counters() const { return counters_; }

 private:
  template <std::size_t>
  friend class FrameScanner;  // the byte loop, with this parser as its codec
  using Verdict = FrameVerdict;
  struct Candidate {
    Verdict verdict = Verdict::drop;
    std::size_t length = 0;  // need_more: total bytes needed; accept: bytes consumed
  };

  Candidate examine(const std::byte* p, std::size_t avail, FastrakEvent& out) const;
  // True when `b` can begin a record (per format) or a reply.
  bool can_start(std::byte b) const;
  Candidate at_end(const Candidate& waiting, const std::byte* p, std::size_t n) const;
  void reject(const Candidate&) {}
  void count(const FastrakEvent& ev);
  // A data record at p: header checks, then (binary16) unpacking, then decode_record.
  Candidate examine_record(const std::byte* p, std::size_t avail, FastrakEvent& out) const;
  // Items and plausibility of a framed record `rec` (logical bytes) of `station`
  // (0-based); `consumed` wire bytes are accepted.
  Candidate decode_record(const std::byte* rec, std::size_t station, std::size_t consumed,
                          FastrakEvent& out) const;
  // Reads one output-list item at q into the pose (dcm_rows: bit per DCM row seen);
  // false when its bytes are not a valid item.
  bool read_item(Item item, const std::byte* q, FastrakPose& pose, unsigned& dcm_rows) const;
  Candidate examine_reply(const std::byte* p, std::size_t avail, FastrakEvent& out) const;

  FastrakConfig config_{};
  bool config_ok_ = false;
  std::array<std::size_t, kMaxStations> record_len_{};  // 0 = station disabled
  FrameScanner<kMaxReplyBytes + kMaxRecordBytes> scan_;
  FastrakParserCounters counters_{};
};

}  // namespace twister::tracker
