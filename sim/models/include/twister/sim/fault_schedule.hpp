// FaultSchedule: the scenario's line faults as they fall due (docs/fastrak.md, scenario
// format): noise bursts (handed to the caller), the drop budget and its expiry, records
// to truncate or corrupt, and the stall / hang-up / wrong-baud windows. One job: when a
// fault applies. The window list is reserved for every scenario fault at construction,
// so applying faults never allocates. Not thread-safe.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "twister/ports/clock.hpp"
#include "twister/sim/scenario.hpp"

namespace twister::sim {

class FaultSchedule {
 public:
  // `faults` must outlive the schedule; times are seconds after `start_us`.
  FaultSchedule(const std::vector<Fault>& faults, ports::TimestampUs start_us);

  // Applies the faults due by `now`: counts each in injected[kind] and hands each noise
  // burst to noise(bytes, at). `baud`: the line rate (a drop budget expires a second
  // after its bytes' transmission time).
  template <typename Noise>
  void apply(ports::TimestampUs now, int baud, std::array<std::uint64_t, kFaultKindCount>& injected,
             Noise&& noise) {
    while (const Fault* f = next_due(now)) {
      ++injected[static_cast<std::size_t>(f->kind)];
      if (f->kind == FaultKind::noise) {
        noise(static_cast<std::uint64_t>(f->amount), due_time(*f));
      } else {
        take(*f, baud);
      }
    }
  }
  bool in_window(ports::TimestampUs t, FaultKind kind) const;
  // Moves the scenario's t = 0 (before any fault has fallen due).
  void start_at(ports::TimestampUs start_us) { start_us_ = start_us; }

  // Drop budget: bytes of the line still to lose. expire_drop() ends it (stream stopped,
  // power-up) and returns what was left; expire_drop_before(t) the same once `t` is past
  // the budget's deadline.
  bool dropping() const { return drop_left_ > 0; }
  void spend_drop() { --drop_left_; }
  std::uint64_t expire_drop();
  std::uint64_t expire_drop_before(ports::TimestampUs t);
  // True (and one spent) when the next record is to be truncated / corrupted.
  bool take_truncate();
  bool take_corrupt();

 private:
  const Fault* next_due(ports::TimestampUs now);
  ports::TimestampUs due_time(const Fault& f) const;
  void take(const Fault& f, int baud);

  struct Window {
    FaultKind kind;
    ports::TimestampUs from, to;
  };
  const std::vector<Fault>& faults_;
  ports::TimestampUs start_us_;
  std::size_t next_ = 0;
  std::uint64_t drop_left_ = 0;
  ports::TimestampUs drop_until_ = 0;  // the drop budget expires then
  std::uint64_t truncate_left_ = 0;
  std::uint64_t corrupt_left_ = 0;
  std::vector<Window> windows_;
};

}  // namespace twister::sim
