// The device model. Records are built with the core encoder, so the simulator and
// the parser share one definition of the wire layout.
#include "twister/sim/fastrak_device.hpp"

// GCC 12 reports a false -Wrestrict inside std::string concatenation at -O3
// (GCC bug 105329); nothing here overlaps.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "record_corruption.hpp"
#include "twister/tracker/fastrak_encoder.hpp"
#include "twister/tracker/pose_conversion.hpp"

namespace twister::sim {
namespace {

using tracker::kCtrlK;
using tracker::kCtrlQ;
using tracker::kCtrlS;
using tracker::kCtrlY;
using tracker::Units;

// Cycle k starts at k * 1e6 / 120 us (8333.33 us).
ports::TimestampUs cycle_time(std::int64_t k) { return (k * 25'000) / 3; }

}  // namespace

FastrakDevice::FastrakDevice(const FastrakDeviceConfig& config, Scenario scenario,
                             ports::TimestampUs start_us)
    : config_(config),
      scenario_(std::move(scenario)),
      start_us_(start_us),
      rng_(scenario_.seed),
      baud_(config.baud) {
  windows_.reserve(scenario_.faults.size());
  pending_cmd_.reserve(96);
  power_up(start_us);
}

double FastrakDevice::scenario_time_s(ports::TimestampUs now) const {
  return static_cast<double>(now - start_us_) / 1e6;
}

void FastrakDevice::power_up(ports::TimestampUs now) {
  ++counters_.resets;
  proto_ = {};
  proto_.format = config_.start_format;
  for (int s = 0; s < 4; ++s) {
    proto_.stations[static_cast<std::size_t>(s)].enabled = s < scenario_.receivers;
  }
  continuous_ = config_.start_continuous;
  output_on_ = true;
  e_mode_ = 1;
  for (auto& h : hemisphere_) h = {1.0, 0.0, 0.0};
  for (auto& e : envelope_) e = {180.0, 90.0, 180.0, -180.0, -90.0, -180.0};
  filter_params_ = {config_.start_position_filter, config_.start_attitude_filter};
  for (auto& f : filter_) {
    for (auto& one : f) one.reset();
  }
  solution_ = {};
  baud_ = config_.baud;  // `o` is not saved: power-up uses the switches' rate
  // A line hit's budget belongs to the stream it hit, not to the next one.
  counters_.drop_expired += drop_left_;
  drop_left_ = 0;
  deaf_until_ = 0;
  busy_until_ = now + config_.reset_time_us;
  line_.clear();
  line_free_at_ = now;
  pending_cmd_.clear();
  in_param_cmd_ = false;
  next_cycle_ = 0;
  while (start_us_ + cycle_time(next_cycle_) < busy_until_) ++next_cycle_;
}

bool FastrakDevice::in_window(ports::TimestampUs now, FaultKind kind) const {
  for (const Window& w : windows_) {
    if (w.kind == kind && now >= w.from && now < w.to) return true;
  }
  return false;
}

bool FastrakDevice::hung_up(ports::TimestampUs now) {
  apply_faults(now);
  if (in_window(now, FaultKind::hangup)) {
    was_hung_up_ = true;
    return true;
  }
  if (was_hung_up_) {
    // Plugged back in: the unit powers up from its defaults.
    was_hung_up_ = false;
    power_up(now);
  }
  return false;
}

void FastrakDevice::apply_faults(ports::TimestampUs now) {
  while (next_fault_ < scenario_.faults.size()) {
    const Fault& f = scenario_.faults[next_fault_];
    const auto at = start_us_ + static_cast<ports::TimestampUs>(f.t_s * 1e6);
    if (at > now) break;
    ++next_fault_;
    ++counters_.faults[static_cast<std::size_t>(f.kind)];
    const auto amount = static_cast<std::uint64_t>(f.amount);
    switch (f.kind) {
      case FaultKind::noise:
        queue_noise(amount, at);
        break;
      case FaultKind::drop:
        // A line hit: the budget is spent on the bytes sent next, and expires a second
        // after their transmission time (assumed) or when the stream stops.
        drop_left_ += amount;
        drop_until_ = at + 1'000'000 +
                      static_cast<ports::TimestampUs>(static_cast<double>(amount) * 1e7 / baud_);
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
}

FastrakDevice::ActiveStations FastrakDevice::active_stations() const {
  ActiveStations out;
  for (int s = 1; s <= 4; ++s) {
    if (proto_.stations[static_cast<std::size_t>(s - 1)].enabled && s <= scenario_.receivers) {
      out.ids[out.count++] = s;
    }
  }
  return out;
}

void FastrakDevice::queue(std::span<const std::byte> bytes, ports::TimestampUs now) {
  const std::size_t n = std::min(bytes.size(), line_.room());
  counters_.line_overflow += bytes.size() - n;
  for (std::size_t i = 0; i < n; ++i) line_.push(bytes[i]);
  // The line sends one byte per 10 bit times (8N1); chunks queue behind each other.
  const ports::TimestampUs start = std::max(now, line_free_at_);
  const auto duration =
      static_cast<ports::TimestampUs>(static_cast<double>(n) * 10.0 * 1e6 / baud_);
  line_free_at_ = start + duration;
  line_.end_chunk(line_free_at_);
}

void FastrakDevice::queue(std::string_view text, ports::TimestampUs now) {
  queue(std::as_bytes(std::span<const char>(text.data(), text.size())), now);
}

void FastrakDevice::queue_noise(std::uint64_t count, ports::TimestampUs now) {
  // Random bytes, straight into the line (what does not fit is lost and counted).
  std::array<std::byte, 256> block{};
  while (count > 0) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(count, block.size()));
    for (std::size_t i = 0; i < n; ++i) block[i] = static_cast<std::byte>(rng_() & 0xFFu);
    count -= n;
    queue(std::span<const std::byte>(block.data(), n), now);
  }
}

void FastrakDevice::solve(int station, ports::TimestampUs at) {
  const HandSample h = sample(scenario_, station, scenario_time_s(at));
  const auto i = static_cast<std::size_t>(station - 1);
  glm::dvec3 p(h.position_in[0], h.position_in[1], h.position_in[2]);
  const auto& hem = hemisphere_[i];
  // The unit reports positions in the configured half-space.
  if (glm::dot(p, glm::dvec3(hem[0], hem[1], hem[2])) < 0.0) p = -p;
  const double el = std::clamp(h.euler_deg[1], -90.0, 90.0);
  const glm::dquat q =
      glm::quat_cast(tracker::rotation_from_euler_deg(h.euler_deg[0], el, h.euler_deg[2]));
  Solution& s = solution_[i];
  s.valid = true;
  s.position_in = filter_[i][0].position(p, filter_params_[0]);
  s.attitude = filter_[i][1].attitude(q, filter_params_[1]);
  s.button = station == 1 && h.button;  // the stylus works on station 1 only
}

char FastrakDevice::status_code(int station, ports::TimestampUs at,
                                const std::array<float, 3>& euler) const {
  const double t = scenario_time_s(at);
  for (const StatusEvent& e : scenario_.status) {
    if (e.station == station && t >= e.t_s && t < e.t_s + e.duration_s) return e.code;
  }
  // Outside the `Q` angular envelope the record is flagged 'y' (docs/fastrak-protocol.md §2).
  const auto& q = envelope_[static_cast<std::size_t>(station - 1)];
  for (std::size_t k = 0; k < 3; ++k) {
    if (euler[k] > q[k] || euler[k] < q[k + 3]) return 'y';
  }
  return ' ';
}

void FastrakDevice::queue_record(int station, ports::TimestampUs at) {
  const auto i = static_cast<std::size_t>(station - 1);
  if (!solution_[i].valid) solve(station, at);
  const Solution& s = solution_[i];
  tracker::FastrakPose pose;
  pose.station = static_cast<std::uint8_t>(station);
  const double scale = proto_.units == Units::centimetres ? 2.54 : 1.0;
  for (glm::length_t k = 0; k < 3; ++k) {
    pose.position[static_cast<std::size_t>(k)] = static_cast<float>(s.position_in[k] * scale);
  }
  const glm::dmat3 r = glm::mat3_cast(s.attitude);
  const glm::dvec3 e = tracker::euler_deg_from_rotation(r);
  pose.euler_deg = {static_cast<float>(e.x), static_cast<float>(e.y), static_cast<float>(e.z)};
  for (std::size_t row = 0; row < 3; ++row) {
    for (std::size_t col = 0; col < 3; ++col) {
      pose.dcm[row * 3 + col] =
          static_cast<float>(r[static_cast<glm::length_t>(col)][static_cast<glm::length_t>(row)]);
    }
  }
  const glm::dquat q = s.attitude.w < 0.0 ? -s.attitude : s.attitude;
  pose.quaternion = {static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y),
                     static_cast<float>(q.z)};
  pose.button = s.button;
  pose.status = status_code(station, at, pose.euler_deg);
  counters_.status_letters += pose.status != ' ';
  std::array<std::byte, tracker::kMaxRecordBytes> buf{};
  auto n = tracker::encode_record(pose, proto_, buf);
  if (!n.ok()) return;
  std::size_t size = *n;
  if (corrupt_left_ > 0) {
    --corrupt_left_;
    counters_.corrupted_records +=
        corrupt_record(std::span(buf.data(), size), station, proto_, rng_);
  }
  if (truncate_left_ > 0 && size > 2) {
    --truncate_left_;
    size = 1 + rng_() % (size - 2);
  }
  ++counters_.records;
  queue(std::span<const std::byte>(buf.data(), size), at);
}

void FastrakDevice::send_error(const std::string& input, int code, ports::TimestampUs now) {
  ++counters_.command_errors;
  queue("2 E*ERROR* " + input + " *ERROR* EC " + std::to_string(code) + " *PS 0 *FL 1 *ST 0\r\n",
        now);
}

void FastrakDevice::generate(ports::TimestampUs now, bool stalled) {
  // One station per 120 Hz cycle, in ascending order of the active stations: its
  // solution (and filter) is updated every cycle, and sent in continuous mode. A
  // cycle waits (is not lost) while the line queue has no room for a record: it runs
  // at the next call, once the reader has taken bytes.
  for (ports::TimestampUs t = start_us_ + cycle_time(next_cycle_); t <= now;
       t = start_us_ + cycle_time(++next_cycle_)) {
    if (line_.room() < tracker::kMaxRecordBytes) return;
    if (t < busy_until_ || stalled || in_window(t, FaultKind::stall)) continue;
    const HandSample s1 = sample(scenario_, 1, scenario_time_s(t));
    if (s1.button && !last_button_ && e_mode_ == 1 && continuous_) output_on_ = !output_on_;
    last_button_ = s1.button;
    const ActiveStations act = active_stations();
    if (act.empty()) continue;
    if (!continuous_ || !output_on_) {  // polled: solutions (and filters) still run
      solve(act[polled_station_++ % act.size()], t);
      continue;
    }
    const int station = act[next_station_++ % act.size()];
    solve(station, t);
    if (line_free_at_ > t) {
      ++counters_.dropped_solutions;  // the previous record is still on the wire
      continue;
    }
    queue_record(station, t);
  }
}

bool FastrakDevice::misclocked(ports::TimestampUs t) const {
  return (host_baud_ != 0 && host_baud_ != baud_) || in_window(t, FaultKind::wrong_baud);
}

bool FastrakDevice::misclock_byte(std::byte& b) {
  // Most frames fail the stop-bit check and are dropped; a few arrive as junk.
  const double u = static_cast<double>(rng_()) / 4294967296.0;
  if (u >= config_.misclock_junk) {
    ++counters_.misclock_lost;
    return false;
  }
  ++counters_.misclock_junk;
  b = static_cast<std::byte>(rng_() & 0xFFu);
  return true;
}

std::size_t FastrakDevice::deliver(ports::TimestampUs now, std::span<std::byte> out) {
  std::size_t n = 0;
  while (!line_.empty() && line_.front_ready() <= now) {
    const bool misclock = misclocked(line_.front_ready());
    if (drop_left_ > 0 && line_.front_ready() >= drop_until_) {
      counters_.drop_expired += drop_left_;  // the line hit is long over
      drop_left_ = 0;
    }
    while (line_.front_left() > 0 && n < out.size()) {
      std::byte b = line_.take();
      if (drop_left_ > 0) {
        --drop_left_;
        ++counters_.dropped_bytes;
        continue;
      }
      if (misclock && !misclock_byte(b)) continue;
      out[n++] = b;
      ++counters_.bytes_out;
    }
    if (line_.front_left() > 0) break;  // `out` is full
    line_.pop_front();
  }
  return n;
}

std::size_t FastrakDevice::advance(ports::TimestampUs now, std::span<std::byte> out) {
  if (hung_up(now)) {  // applies the faults due by now
    line_.clear();
    return 0;
  }
  const bool stalled = in_window(now, FaultKind::stall);
  generate(now, stalled);
  if (stalled) return 0;
  return deliver(now, out);
}

void FastrakDevice::advance(ports::TimestampUs now, std::vector<std::byte>& out) {
  std::array<std::byte, 1024> block{};
  for (;;) {
    const std::size_t n = advance(now, block);
    out.insert(out.end(), block.begin(), block.begin() + static_cast<std::ptrdiff_t>(n));
    if (n == 0) return;
  }
}

}  // namespace twister::sim
