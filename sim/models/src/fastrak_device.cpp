// The device model: power-up, the 120 Hz cycle, records and the line (the command side
// is fastrak_device_commands.cpp). Records are built with the core encoder, so the
// simulator and the parser share one definition of the wire layout.
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
#include "twister/tracker/liberty_encoder.hpp"
#include "twister/tracker/pose_conversion.hpp"

namespace twister::sim {

const char* device_model_name(DeviceModel model) {
  switch (model) {
    case DeviceModel::fastrak:
      return "fastrak";
    case DeviceModel::liberty:
      return "liberty";
    case DeviceModel::patriot:
      return "patriot";
  }
  return "unknown";
}

namespace {

using tracker::Format;
using tracker::ModeCommand;
using tracker::Units;

// Cycle k starts at k * 1e6 / 120 us (8333.33 us).
ports::TimestampUs cycle_time(std::int64_t k) { return (k * 25'000) / 3; }

}  // namespace

FastrakDevice::FastrakDevice(const FastrakDeviceConfig& config, Scenario scenario,
                             ports::TimestampUs start_us)
    : config_(config),
      scenario_(std::move(scenario)),
      start_us_(start_us),
      scenario_origin_(config.scenario_clock == ScenarioClock::power_up ? start_us : kNotYet),
      rng_(scenario_.seed) {
  settings_.baud = config.baud;
  power_up(start_us);
}

ports::TimestampUs FastrakDevice::scenario_time_us(ports::TimestampUs now) const {
  return now <= scenario_origin_ ? 0 : now - scenario_origin_;
}

double FastrakDevice::scenario_time_s(ports::TimestampUs now) const {
  return static_cast<double>(scenario_time_us(now)) / 1e6;
}

void FastrakDevice::power_up(ports::TimestampUs now) {
  ++counters_.resets;
  settings_.power_up({config_.baud, config_.start_continuous, config_.start_format,
                      scenario_.receivers, config_.start_position_filter,
                      config_.start_attitude_filter});
  // A Liberty's stylus leaves the stream alone (assumed, docs/liberty-protocol.md §9: no
  // public driver sets its mode, and VRPN's reads it as a button while streaming).
  if (config_.model != DeviceModel::fastrak) settings_.stylus_mode = 0;
  solver_.reset();
  // A line hit's budget belongs to the stream it hit, not to the next one.
  counters_.drop_expired += faults_.expire_drop();
  busy_until_ = now + config_.reset_time_us;
  line_.clear(now);
  counters_.input_lost += input_.reset();  // the UART is reinitialised
  cycle_.next = 0;
  while (start_us_ + cycle_time(cycle_.next) < busy_until_) ++cycle_.next;
}

bool FastrakDevice::hung_up(ports::TimestampUs now) {
  apply_faults(now);
  // The line is down (a USB-serial adapter pulled, a cable out); the unit behind it keeps
  // its power, its configuration and its mode, and streams on into nothing.
  return faults_.in_window(now, FaultKind::hangup);
}

void FastrakDevice::apply_faults(ports::TimestampUs now) {
  faults_.apply(now, settings_.baud, counters_.faults,
                [this](std::uint64_t bytes, ports::TimestampUs at) { queue_noise(bytes, at); });
}

void FastrakDevice::queue_noise(std::uint64_t count, ports::TimestampUs now) {
  // Random bytes, straight into the line (what does not fit is lost and counted
  // without being made: an absurd amount must not spin the caller's loop).
  const std::uint64_t room = line_.queue().room();
  if (count > room) {
    counters_.line_overflow += count - room;
    count = room;
  }
  std::array<std::byte, 256> block{};
  while (count > 0) {
    const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(count, block.size()));
    for (std::size_t i = 0; i < n; ++i) block[i] = static_cast<std::byte>(rng_() & 0xFFu);
    count -= n;
    queue(std::span<const std::byte>(block.data(), n), now);
  }
}

void FastrakDevice::solve(int station, ports::TimestampUs at) {
  solver_.solve(station, sample(scenario_, station, scenario_time_s(at)), settings_);
}

char FastrakDevice::status_code(int station, ports::TimestampUs at,
                                const std::array<float, 3>& euler) const {
  const double t = scenario_time_s(at);
  for (const StatusEvent& e : scenario_.status) {
    if (e.station == station && t >= e.t_s && t < e.t_s + e.duration_s) return e.code;
  }
  // Outside the `Q` angular envelope the record is flagged 'y' (docs/fastrak-protocol.md §2).
  const auto& q = settings_.envelope[static_cast<std::size_t>(station - 1)];
  for (std::size_t k = 0; k < 3; ++k) {
    if (euler[k] > q[k] || euler[k] < q[k + 3]) return 'y';
  }
  return ' ';
}

void FastrakDevice::queue_record(int station, ports::TimestampUs at) {
  if (!solver_.solution(station).valid) solve(station, at);
  const StationSolver::Solution& s = solver_.solution(station);
  tracker::FastrakPose pose;
  pose.station = static_cast<std::uint8_t>(station);
  const double scale = settings_.protocol.units == Units::centimetres ? 2.54 : 1.0;
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
  std::array<std::byte, std::max(tracker::kMaxRecordBytes, tracker::kLibertyMaxFrameBytes)> buf{};
  std::size_t size = encode_pose(pose, buf);
  if (size == 0) return;
  if (size > 2 && faults_.take_truncate()) size = 1 + rng_() % (size - 2);
  ++counters_.output.records;
  queue(std::span<const std::byte>(buf.data(), size), at);
}

std::size_t FastrakDevice::encode_pose(const tracker::FastrakPose& pose, std::span<std::byte> buf) {
  const tracker::FastrakConfig& protocol = settings_.protocol;
  if (config_.model == DeviceModel::fastrak || protocol.format != Format::binary) {
    auto n = tracker::encode_record(pose, protocol, buf);
    if (!n.ok()) return 0;
    if (faults_.take_corrupt()) {
      counters_.corrupted_records += corrupt_record(buf.first(*n), pose.station, protocol, rng_);
    }
    return *n;
  }
  tracker::LibertyConfig liberty;
  const auto model = config_.model == DeviceModel::patriot ? tracker::LibertyModel::patriot
                                                           : tracker::LibertyModel::liberty;
  if (!tracker::to_liberty_config(protocol, model, liberty).ok()) return 0;
  auto n = tracker::encode_liberty_frame(pose, liberty, buf);
  if (!n.ok()) return 0;
  // A line hit inside a frame: one bit of a position float (framing cannot see it).
  const auto& list = liberty.stations[pose.station - 1u].list;
  if (faults_.take_corrupt() && list.count > 0 && list.items[0] == tracker::LibertyItem::position) {
    buf[tracker::kLibertyHeaderBytes + rng_() % 12] ^= std::byte{1} << (rng_() % 8);
    ++counters_.corrupted_records;
  }
  return *n;
}

void FastrakDevice::generate(ports::TimestampUs now, bool stalled) {
  // One station per 120 Hz cycle, in ascending order of the active stations: its
  // solution (and filter) is updated every cycle, and sent in continuous mode. A
  // cycle waits (is not lost) while the line queue has no room for a record: it runs
  // at the next call, once the reader has taken bytes.
  for (ports::TimestampUs t = start_us_ + cycle_time(cycle_.next); t <= now;
       t = start_us_ + cycle_time(++cycle_.next)) {
    if (line_.queue().room() < tracker::kMaxRecordBytes) return;
    if (t < busy_until_ || stalled || faults_.in_window(t, FaultKind::stall)) continue;
    const HandSample s1 = sample(scenario_, 1, scenario_time_s(t));
    const bool press = s1.button && !cycle_.last_button && settings_.stylus_mode == 1;
    cycle_.last_button = s1.button;
    // Point/track mode (`e1,1`, the default): a press toggles continuous output, and in
    // polled mode acts as `P` (manual, `e` command; docs/fastrak-protocol.md §2).
    if (press && settings_.continuous) settings_.output_on = !settings_.output_on;
    const ActiveStations act = active_stations();
    if (act.empty()) continue;
    if (press && !settings_.continuous) {
      ++counters_.output.stylus_polls;
      for (const int station : act) queue_record(station, t);  // as `P`
    }
    if (!settings_.continuous || !settings_.output_on) {  // polled: solutions still run
      solve(act[cycle_.polled_station++ % act.size()], t);
      continue;
    }
    const int station = act[cycle_.next_station++ % act.size()];
    solve(station, t);
    if (line_.busy_at(t)) {
      ++counters_.dropped_solutions;  // the previous record is still on the wire
      continue;
    }
    queue_record(station, t);
  }
}

bool FastrakDevice::misclocked(ports::TimestampUs t) const {
  return (host_baud_ != 0 && host_baud_ != settings_.baud) ||
         faults_.in_window(t, FaultKind::wrong_baud);
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
  LineQueue& line = line_.queue();
  while (!line.empty() && line.front_ready() <= now) {
    if (faults_.in_window(line.front_ready(), FaultKind::hangup)) {
      counters_.output.hangup_lost += line.front_left();  // sent while the line was down
      line.pop_front();
      continue;
    }
    const bool misclock = misclocked(line.front_ready());
    counters_.drop_expired += faults_.expire_drop_before(line.front_ready());  // hit long over
    while (line.front_left() > 0 && n < out.size()) {
      std::byte b = line.take();
      if (faults_.dropping()) {
        faults_.spend_drop();
        ++counters_.dropped_bytes;
        continue;
      }
      if (misclock && !misclock_byte(b)) continue;
      out[n++] = b;
      ++counters_.output.bytes_out;
    }
    if (line.front_left() > 0) break;  // `out` is full
    line.pop_front();
  }
  return n;
}

std::size_t FastrakDevice::advance(ports::TimestampUs now, std::span<std::byte> out) {
  if (hung_up(now)) {  // applies the faults due by now
    // The unit runs on; what it has sent by now reached nobody (nor does what the
    // pulled adapter held).
    generate(now, false);
    LineQueue& line = line_.queue();
    while (!line.empty() && line.front_ready() <= now) {
      counters_.output.hangup_lost += line.front_left();
      line.pop_front();
    }
    return 0;
  }
  const bool stalled = faults_.in_window(now, FaultKind::stall);
  if (!stalled) read_buffered(now);
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
