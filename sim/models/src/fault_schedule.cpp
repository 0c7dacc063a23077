#include "twister/sim/fault_schedule.hpp"

namespace twister::sim {

FaultSchedule::FaultSchedule(const std::vector<Fault>& faults, ports::TimestampUs start_us)
    : faults_(faults), start_us_(start_us) {
  windows_.reserve(faults.size());
}

ports::TimestampUs FaultSchedule::due_time(const Fault& f) const {
  return start_us_ + static_cast<ports::TimestampUs>(f.t_s * 1e6);
}

const Fault* FaultSchedule::next_due(ports::TimestampUs now) {
  if (next_ >= faults_.size() || due_time(faults_[next_]) > now) return nullptr;
  return &faults_[next_++];
}

void FaultSchedule::take(const Fault& f, int baud) {
  const auto at = due_time(f);
  const auto amount = static_cast<std::uint64_t>(f.amount);
  switch (f.kind) {
    case FaultKind::noise:
      break;
    case FaultKind::drop:
      // A line hit: the budget is spent on the bytes sent next, and expires a second
      // after their transmission time (assumed) or when the stream stops.
      drop_left_ += amount;
      drop_until_ = at + 1'000'000 +
                    static_cast<ports::TimestampUs>(static_cast<double>(amount) * 1e7 / baud);
      break;
    case FaultKind::corrupt:
      corrupt_left_ += amount;
      break;
    case FaultKind::truncate:
      truncate_left_ += amount;
      break;
    case FaultKind::stall:
    case FaultKind::hangup:
    case FaultKind::wrong_baud:
      windows_.push_back({f.kind, at, at + static_cast<ports::TimestampUs>(f.amount * 1e6)});
      break;
  }
}

bool FaultSchedule::in_window(ports::TimestampUs t, FaultKind kind) const {
  for (const Window& w : windows_) {
    if (w.kind == kind && t >= w.from && t < w.to) return true;
  }
  return false;
}

std::uint64_t FaultSchedule::expire_drop() {
  const std::uint64_t left = drop_left_;
  drop_left_ = 0;
  return left;
}

std::uint64_t FaultSchedule::expire_drop_before(ports::TimestampUs t) {
  return drop_left_ > 0 && t >= drop_until_ ? expire_drop() : 0;
}

bool FaultSchedule::take_truncate() {
  if (truncate_left_ == 0) return false;
  --truncate_left_;
  return true;
}

bool FaultSchedule::take_corrupt() {
  if (corrupt_left_ == 0) return false;
  --corrupt_left_;
  return true;
}

}  // namespace twister::sim
