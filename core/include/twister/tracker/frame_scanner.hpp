// FrameScanner: the byte loop the tracker parsers share (the Fastrak's records and
// replies, the Liberty/Patriot frames). It keeps the bytes of a candidate that is
// not complete yet, drops what cannot start anything in one step, reports each run
// of dropped bytes as a resync event before the item that ends it, and counts bytes.
// What a candidate is, is the codec's: a parser passes itself as the codec with
//   Candidate examine(const std::byte* p, std::size_t avail, FastrakEvent& out) const
//       (Candidate: .verdict (FrameVerdict) and .length: need_more: total bytes
//       needed; accept: bytes consumed),
//   bool can_start(std::byte b) const,
//   Candidate at_end(const Candidate& waiting, const std::byte* p, std::size_t n) const
//       (a candidate that can never complete: what it counts as, a drop),
//   void reject(const Candidate& dropped), void count(const FastrakEvent& emitted),
// and its counters with .bytes, .dropped_bytes and .resyncs.
// Memory: kMaxFrame bytes inline; no allocation.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

#include "twister/base/result.hpp"
#include "twister/tracker/fastrak_event.hpp"

namespace twister::tracker {

enum class FrameVerdict : std::uint8_t { need_more, drop, accept };

template <std::size_t kMaxFrame>
class FrameScanner {
 public:
  template <typename Codec, typename Counters>
  Result<FastrakEvent> next(Codec& codec, Counters& counters, std::span<const std::byte>& input) {
    if (held_) {
      held_ = false;
      return emit(codec, counters, held_event_);
    }
    FastrakEvent ev;
    for (;;) {
      if (pending_len_ > 0) {
        const auto c = codec.examine(pending_.data(), pending_len_, ev);
        if (c.verdict == FrameVerdict::need_more) {
          if (input.empty()) return StatusCode::unavailable;
          const std::size_t n = std::min(c.length - pending_len_, input.size());
          std::memcpy(pending_.data() + pending_len_, input.data(), n);
          pending_len_ += n;
          input = input.subspan(n);
          counters.bytes += n;
          continue;
        }
        // A dropped candidate takes with it every following byte that cannot start
        // anything (examine would drop them one by one), so one shift per resync.
        const std::size_t used = c.verdict == FrameVerdict::drop
                                     ? skip_to_start(codec, pending_.data(), pending_len_)
                                     : c.length;
        std::memmove(pending_.data(), pending_.data() + used, pending_len_ - used);
        pending_len_ -= used;
        if (c.verdict == FrameVerdict::drop) {
          codec.reject(c);
          drop(counters, used);
          continue;
        }
        return emit(codec, counters, ev);
      }
      if (input.empty()) return StatusCode::unavailable;
      if (!codec.can_start(input[0])) {  // fast skip of bytes that cannot start anything
        const std::size_t k = skip_to_start(codec, input.data(), input.size());
        drop(counters, k);
        counters.bytes += k;
        input = input.subspan(k);
        continue;
      }
      const auto c = codec.examine(input.data(), input.size(), ev);
      if (c.verdict == FrameVerdict::need_more) {
        // The codec asks for at most kMaxFrame bytes (its size checks come first).
        std::memcpy(pending_.data(), input.data(), input.size());
        pending_len_ = input.size();
        counters.bytes += input.size();
        input = input.subspan(input.size());
        return StatusCode::unavailable;
      }
      const std::size_t used = c.verdict == FrameVerdict::drop ? 1 : c.length;
      counters.bytes += used;
      input = input.subspan(used);
      if (c.verdict == FrameVerdict::drop) {
        codec.reject(c);
        drop(counters, 1);
        continue;
      }
      return emit(codec, counters, ev);
    }
  }

  // End of the stream: a candidate still waiting can never complete, but a shorter
  // item may start inside it; then the last dropped run.
  template <typename Codec, typename Counters>
  Result<FastrakEvent> finish(Codec& codec, Counters& counters) {
    if (held_) {
      held_ = false;
      return emit(codec, counters, held_event_);
    }
    FastrakEvent ev;
    while (pending_len_ > 0) {
      auto c = codec.examine(pending_.data(), pending_len_, ev);
      if (c.verdict == FrameVerdict::need_more) c = codec.at_end(c, pending_.data(), pending_len_);
      const std::size_t used = c.verdict == FrameVerdict::accept ? c.length : 1;
      std::memmove(pending_.data(), pending_.data() + used, pending_len_ - used);
      pending_len_ -= used;
      if (c.verdict == FrameVerdict::accept) return emit(codec, counters, ev);
      codec.reject(c);
      drop(counters, 1);
    }
    if (dropped_run_ == 0) return StatusCode::unavailable;
    return resync(counters);
  }

  // Forgets the pending bytes and a held item (a new configuration); the dropped run
  // is kept and still reported.
  void forget_pending() {
    pending_len_ = 0;
    held_ = false;
  }

  // Forgets pending bytes and the dropped run without reporting them.
  void reset() {
    pending_len_ = 0;
    dropped_run_ = 0;
    held_ = false;
  }

  // A parser without a valid configuration: every byte of `input` is dropped.
  template <typename Counters>
  Result<FastrakEvent> drop_all(Counters& counters, std::span<const std::byte>& input) {
    drop(counters, input.size());
    counters.bytes += input.size();
    input = input.subspan(input.size());
    return StatusCode::unavailable;
  }

 private:
  template <typename Counters>
  void drop(Counters& counters, std::size_t n) {
    dropped_run_ += static_cast<std::uint32_t>(n);
    counters.dropped_bytes += n;
  }

  // Bytes from p[0] up to the next one that could start an item (at least 1).
  template <typename Codec>
  static std::size_t skip_to_start(const Codec& codec, const std::byte* p, std::size_t n) {
    std::size_t k = 1;
    while (k < n && !codec.can_start(p[k])) ++k;
    return k;
  }

  template <typename Counters>
  Result<FastrakEvent> resync(Counters& counters) {
    FastrakEvent r{};
    r.kind = EventKind::resync;
    r.dropped = dropped_run_;
    dropped_run_ = 0;
    ++counters.resyncs;
    return r;
  }

  // The dropped run first; the accepted item follows on the next call.
  template <typename Codec, typename Counters>
  Result<FastrakEvent> emit(Codec& codec, Counters& counters, const FastrakEvent& ev) {
    if (dropped_run_ > 0) {
      held_ = true;
      held_event_ = ev;
      return resync(counters);
    }
    codec.count(ev);
    return ev;
  }

  std::array<std::byte, kMaxFrame> pending_{};
  std::size_t pending_len_ = 0;
  std::uint32_t dropped_run_ = 0;
  bool held_ = false;  // an accepted event waits behind its resync report
  FastrakEvent held_event_{};
};

}  // namespace twister::tracker
