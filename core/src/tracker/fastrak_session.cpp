// FastrakSession state machine. Every wait is a deadline checked in poll(); the only
// side effects are writes to and reads from the ByteStream port.
#include "twister/tracker/fastrak_session.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace twister::tracker {
namespace {
LibertyModel liberty_family(TrackerModel model) {
  return model == TrackerModel::patriot ? LibertyModel::patriot
         : model == TrackerModel::latus ? LibertyModel::latus
                                        : LibertyModel::liberty;
}

// A Liberty-family model needs binary output and lists with a Liberty equivalent.
bool configure_frames(const FastrakSessionConfig& config, LibertyParser& parser) {
  if (config.model == TrackerModel::fastrak) return true;
  if (config.protocol.format != Format::binary) return false;
  LibertyConfig frames;
  return to_liberty_config(config.protocol, liberty_family(config.model), frames).ok() &&
         parser.configure(frames).ok();
}
}  // namespace

FastrakSession::FastrakSession(ports::ByteStream& stream, ports::Clock& clock,
                               const FastrakSessionConfig& config)
    : stream_(stream),
      clock_(clock),
      config_(config),
      continuity_(config.continuity, config.protocol.units, config.protocol.format) {
  flags_.config_ok = parsers_.fastrak.configure(config_.protocol).ok() &&
                     configure_frames(config_, parsers_.liberty) && config_.reset_rung_limit >= 1;
  recovery_.backoff_us = config_.backoff.initial_us;
  timers_.deadline = clock_.now_us();
  if (flags_.config_ok) build_commands();
}

void FastrakSession::build_commands() {
  // One command per '\0'-terminated entry; sent one per command pause.
  commands_.len = 0;
  if (config_.model != TrackerModel::fastrak) {
    const bool ok = build_liberty_commands();
    TWISTER_ASSERT(ok);  // 16 commands of at most 128 bytes fit the buffer
    return;
  }
  bool ok = true;
  for (int s = 1; s <= kMaxStations; ++s) {
    const ReceiverConfig& st = config_.protocol.stations[static_cast<std::size_t>(s - 1)];
    ok = ok && add_command(station_state_command(s, st.enabled));
    if (!st.enabled) continue;
    ok = ok && add_command(output_list_command(s, st.list));
    ok = ok &&
         add_command(hemisphere_command(s, config_.hemisphere[static_cast<std::size_t>(s - 1)]));
  }
  const auto position = filter_command(ParameterCommand::position_filter, config_.position_filter);
  if (position) ok = ok && add_command(*position);
  const auto attitude = filter_command(ParameterCommand::attitude_filter, config_.attitude_filter);
  if (attitude) ok = ok && add_command(*attitude);
  // e1,0: the stylus must never toggle the stream off (docs/fastrak-protocol.md §6 pitfall 4).
  ok = ok && add_command(stylus_mode_command(1, 0));
  const bool inches = config_.protocol.units == Units::inches;
  ok = ok && add_command(Mode{inches ? ModeCommand::inches : ModeCommand::centimetres});
  // binary16 is selected with `f` as well: on a unit whose binary is the packed format.
  const bool ascii = config_.protocol.format == Format::ascii;
  ok = ok && add_command(Mode{ascii ? ModeCommand::ascii : ModeCommand::binary});
  TWISTER_ASSERT(ok);  // 4 stations x 32 items always fit the buffer
}

bool FastrakSession::add_command(const FastrakCommand& command) {
  const auto room = std::span<char>(commands_.data).subspan(commands_.len);
  const Result<std::size_t> n = encode(command, room);
  if (!n.ok() || *n >= room.size()) return false;
  commands_.len += *n;
  commands_.data[commands_.len++] = '\0';
  return true;
}

void FastrakSession::enter(SessionState s) { state_ = s; }

bool FastrakSession::send(std::span<const char> text, ports::TimestampUs now) {
  auto bytes = std::as_bytes(text);
  // A full output queue is retried a few times; a persistent refusal is a fault.
  for (int tries = 0; tries < 4 && !bytes.empty(); ++tries) {
    auto n = stream_.write(bytes);
    if (!n.ok()) {
      ++counters_.io_errors;
      fault(now);
      return false;
    }
    bytes = bytes.subspan(*n);
  }
  if (!bytes.empty()) {
    ++counters_.io_errors;
    fault(now);
    return false;
  }
  return true;
}

bool FastrakSession::send_command(const FastrakCommand& command, ports::TimestampUs now) {
  std::array<char, kMaxCommandBytes> buf{};
  const Result<std::size_t> n = encode(command, buf);
  TWISTER_ASSERT(n.ok());  // any command fits kMaxCommandBytes
  return send(std::span<const char>(buf.data(), *n), now);
}

void FastrakSession::start_ladder(ports::TimestampUs now) {
  if (recovery_.rung < 1) recovery_.rung = 1;
  ++counters_.inits;
  ladder_.len = 0;
  if (config_.model != TrackerModel::fastrak) {  // docs/liberty-protocol.md §9
    ladder_.len = liberty_ladder(liberty_family(config_.model), recovery_.rung, ladder_.data);
    ladder_.pos = 0;
    timers_.deadline = now;
    enter(SessionState::ladder);
    return;
  }
  if (recovery_.rung >= 2) ladder_.data[ladder_.len++] = kCr;  // ends a half-typed command
  ladder_.data[ladder_.len++] = static_cast<char>(ModeCommand::polled);  // leave continuous mode
  if (recovery_.rung >= 3) {
    ladder_.data[ladder_.len++] = static_cast<char>(ModeCommand::reinitialise);  // power-up state
  }
  ladder_.pos = 0;
  timers_.deadline = now;
  enter(SessionState::ladder);
}

void FastrakSession::fault(ports::TimestampUs now) {
  parsers_.reset();
  rx_.len = rx_.pos = 0;
  flags_.port_open = false;  // the port is reopened (VRPN closes and reopens as well)
  timers_.deadline = now + recovery_.backoff_us;
  recovery_.backoff_us = std::min(recovery_.backoff_us * 2, config_.backoff.max_us);
  enter(SessionState::backoff);
}

void FastrakSession::reinitialise() {
  ++counters_.reinit_requests;
  const ports::TimestampUs now = clock_.now_us();
  parsers_.reset();
  rx_.len = rx_.pos = 0;
  flags_.port_open = false;
  recovery_.rung = 1;
  timers_.deadline = now;
  enter(SessionState::backoff);
}

void FastrakSession::step_timers(ports::TimestampUs now) {
  switch (state_) {
    case SessionState::backoff: {
      // A device that has just been plugged in is tried at once, with the back-off
      // started afresh (a replug is not one more failure).
      if (now < timers_.deadline) {
        if (!stream_.device_arrived()) return;
        recovery_.backoff_us = config_.backoff.initial_us;
      }
      const Status s = stream_.reopen();
      if (!s.ok()) {
        ++counters_.io_errors;
        fault(now);
        return;
      }
      flags_.port_open = true;
      start_ladder(now);
      return;
    }
    case SessionState::ladder: {
      if (now < timers_.deadline) return;
      if (ladder_.pos < ladder_.len) {
        // A byte at a time; a Liberty's ladder a line (up to its CR) at a time.
        const bool liberty = config_.model != TrackerModel::fastrak;
        const std::size_t from = ladder_.pos;
        while (ladder_.pos++ < ladder_.len - 1 && liberty && ladder_.data[ladder_.pos - 1] != kCr) {
        }
        const std::span<const char> chunk(ladder_.data.data() + from, ladder_.pos - from);
        if (!send(chunk, now)) return;
        // The unit re-initialises after ^Y (a Liberty: after the CR that ends it).
        const bool reset = std::find(chunk.begin(), chunk.end(), kCtrlY) != chunk.end();
        timers_.deadline = now + (reset ? config_.reset_wait_us : config_.ladder_char_pause_us);
        return;
      }
      timers_.deadline = now + config_.settle_us;
      enter(SessionState::settle);
      return;
    }
    case SessionState::settle: {
      if (now < timers_.deadline) return;
      // Whatever came during the ladder (records, power-up text) is stale.
      stream_.discard_input();
      parsers_.reset();
      rx_.len = rx_.pos = 0;
      // A Liberty has no `S`: WhoAmI (docs/liberty-protocol.md §9).
      flags_.whoami_first = 0;
      const bool sent = config_.model == TrackerModel::fastrak
                            ? send_command(Mode{ModeCommand::status}, now)
                            : send(std::span<const char>(kLibertyWhoAmI), now);
      if (!sent) return;
      timers_.deadline = now + config_.reply_timeout_us;
      enter(SessionState::await_status);
      return;
    }
    case SessionState::await_status:
    case SessionState::verify_status: {
      // A WhoAmI reply is complete when no byte came for a command pause.
      if (flags_.whoami_first != 0 && now - timers_.last_byte >= config_.command_pause_us) {
        judge_whoami(now);
        return;
      }
      if (now < timers_.deadline) return;
      ++counters_.status_timeouts;
      if (recovery_.rung < config_.reset_rung_limit) {
        ++recovery_.rung;  // escalate at once, as VRPN's ladder does
        start_ladder(now);
      } else {
        fault(now);
      }
      return;
    }
    case SessionState::configuring: {
      if (now < timers_.deadline) return;
      if (commands_.pos < commands_.len) {
        const char* cmd = commands_.data.data() + commands_.pos;
        const std::size_t n = std::strlen(cmd);
        commands_.pos += n + 1;
        if (!send(std::span<const char>(cmd, n), now)) return;
        // The unit is deaf while it processes a command (filters take longest).
        const bool filter = cmd[0] == static_cast<char>(ParameterCommand::position_filter) ||
                            cmd[0] == static_cast<char>(ParameterCommand::attitude_filter) ||
                            cmd[0] == kLibertyPositionFilter || cmd[0] == kLibertyAttitudeFilter;
        timers_.deadline = now + (filter ? config_.filter_pause_us : config_.command_pause_us);
        return;
      }
      if (config_.model != TrackerModel::fastrak) {
        // No status record to check format and units against: the frames show the
        // format; the units are taken as set (docs/liberty-protocol.md §9).
        if (send(std::span<const char>(kLibertyStartContinuous), now)) start_streaming(now);
        return;
      }
      if (!send_command(Mode{ModeCommand::status}, now)) return;
      timers_.deadline = now + config_.reply_timeout_us;
      enter(SessionState::verify_status);
      return;
    }
    case SessionState::streaming: {
      if (now - timers_.last_pose <= config_.silence_timeout_us) return;
      if (now - timers_.last_byte > config_.silence_timeout_us) {
        ++counters_.silence_faults;
      } else {
        ++counters_.garbage_faults;
      }
      fault(now);
      return;
    }
  }
}

void FastrakSession::handle_event(const FastrakEvent& ev, ports::TimestampUs now) {
  switch (ev.kind) {
    case EventKind::pose:
    case EventKind::resync:
      return;
    case EventKind::error:
      ++counters_.rejected_poses;
      return;
    case EventKind::reply:
      if (!ev.reply.is_error) return;
      ++counters_.command_errors;
      // A refused configuration command leaves the unit in an unknown state.
      if (state_ == SessionState::configuring || state_ == SessionState::verify_status) {
        fault(now);
      }
      return;
    case EventKind::status:
      last_status_ = ev.status;
      if (state_ == SessionState::await_status) {
        commands_.pos = 0;
        timers_.deadline = now;
        enter(SessionState::configuring);
      } else if (state_ == SessionState::verify_status) {
        const bool want_bin = config_.protocol.format != Format::ascii;
        const bool want_cm = config_.protocol.units == Units::centimetres;
        if (ev.status.binary != want_bin || ev.status.centimetres != want_cm) {
          ++counters_.status_mismatch;
          if (recovery_.rung < config_.reset_rung_limit) ++recovery_.rung;
          fault(now);
          return;
        }
        if (send_command(Mode{ModeCommand::continuous}, now)) start_streaming(now);
      }
      return;
  }
}

void FastrakSession::start_streaming(ports::TimestampUs now) {
  ++counters_.streams_started;
  recovery_.rung = 0;
  recovery_.backoff_us = config_.backoff.initial_us;
  timers_.last_pose = timers_.last_byte = now;
  continuity_.reset();
  enter(SessionState::streaming);
}

bool FastrakSession::take_pose(const FastrakPose& pose, ports::TimestampUs now) {
  if (!continuity_.accept(pose, now)) {
    ++counters_.jump_rejects;
    return false;
  }
  timers_.last_pose = now;
  ++counters_.poses;
  if (pose.status != ' ') {  // a warning letter: the pose is used, the code kept
    ++counters_.warning_poses;
    counters_.last_warning = pose.status;
  }
  return true;
}

Result<FastrakEvent> FastrakSession::next_event() {
  std::span<const std::byte> in(rx_.data.data() + rx_.pos, rx_.len - rx_.pos);
  const bool frames = config_.model != TrackerModel::fastrak && state_ == SessionState::streaming;
  auto ev = frames ? parsers_.liberty.next(in) : parsers_.fastrak.next(in);
  rx_.pos = rx_.len - in.size();
  return ev;
}

Result<FastrakPose> FastrakSession::poll() {
  if (!flags_.config_ok) return StatusCode::invalid_argument;
  const ports::TimestampUs now = clock_.now_us();
  // While streaming, silence is judged only once the input is drained: a host that
  // stalled (a slow fsync, a starved process) finds the records that came meanwhile
  // instead of calling a unit that kept sending "lost".
  if (state_ != SessionState::streaming) step_timers(now);
  for (;;) {
    // The parser may still hold an event (an accepted record queued behind its
    // resync report) even when no bytes are left, so ask it before reading.
    auto ev = next_event();
    if (ev.ok()) {
      if (ev->kind == EventKind::pose && state_ == SessionState::streaming) {
        if (!take_pose(ev->pose, now)) continue;
        return ev->pose;
      }
      handle_event(*ev, now);
      continue;
    }
    if (!flags_.port_open) return StatusCode::unavailable;
    auto n = stream_.read(rx_.data);
    if (!n.ok()) {
      ++counters_.io_errors;
      fault(now);
      return StatusCode::unavailable;
    }
    if (*n == 0) {
      if (state_ == SessionState::streaming) step_timers(now);
      return StatusCode::unavailable;
    }
    rx_.len = *n;
    rx_.pos = 0;
    timers_.last_byte = now;
    if (config_.model != TrackerModel::fastrak && state_ == SessionState::await_status) {
      // A WhoAmI reply is text, not a record: only its first byte is judged.
      if (flags_.whoami_first == 0) flags_.whoami_first = static_cast<char>(rx_.data[0]);
      rx_.pos = rx_.len;
      if (flags_.whoami_first == 0) flags_.whoami_first = 1;  // a NUL: not '0' either
    }
  }
}

}  // namespace twister::tracker
