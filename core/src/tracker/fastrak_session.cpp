// FastrakSession state machine. Every wait is a deadline checked in poll(); the only
// side effects are writes to and reads from the ByteStream port.
#include "twister/tracker/fastrak_session.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace twister::tracker {
namespace {

// Appends text to a fixed buffer; false when it does not fit.
bool append(std::array<char, 1024>& buf, std::size_t& len, const char* text) {
  const std::size_t n = std::strlen(text);
  if (len + n + 1 > buf.size()) return false;
  std::memcpy(buf.data() + len, text, n);
  len += n;
  return true;
}

bool append_int(std::array<char, 1024>& buf, std::size_t& len, int v) {
  char tmp[12];
  std::size_t n = 0;
  const bool neg = v < 0;
  unsigned u = neg ? static_cast<unsigned>(-v) : static_cast<unsigned>(v);
  do {
    tmp[n++] = static_cast<char>('0' + u % 10);
    u /= 10;
  } while (u != 0);
  if (neg) tmp[n++] = '-';
  if (len + n + 1 > buf.size()) return false;
  while (n > 0) buf[len++] = tmp[--n];
  return true;
}

// Appends a value 0..1 with three decimals ("0.200", "1.000").
bool append_unit3(std::array<char, 1024>& buf, std::size_t& len, float v) {
  const float c = v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v);
  const auto m = static_cast<unsigned>(std::lround(static_cast<double>(c) * 1000.0));
  if (len + 6 > buf.size()) return false;
  buf[len++] = static_cast<char>('0' + m / 1000);
  buf[len++] = '.';
  buf[len++] = static_cast<char>('0' + (m / 100) % 10);
  buf[len++] = static_cast<char>('0' + (m / 10) % 10);
  buf[len++] = static_cast<char>('0' + m % 10);
  return true;
}

}  // namespace

const char* session_state_name(SessionState s) {
  switch (s) {
    case SessionState::backoff:
      return "backoff";
    case SessionState::ladder:
      return "ladder";
    case SessionState::settle:
      return "settle";
    case SessionState::await_status:
      return "await_status";
    case SessionState::configuring:
      return "configuring";
    case SessionState::verify_status:
      return "verify_status";
    case SessionState::streaming:
      return "streaming";
  }
  return "unknown";
}

FastrakSession::FastrakSession(ports::ByteStream& stream, ports::Clock& clock,
                               const FastrakSessionConfig& config)
    : stream_(stream),
      clock_(clock),
      config_(config),
      continuity_(config.continuity, config.protocol.units, config.protocol.format) {
  config_ok_ = parser_.configure(config_.protocol).ok() && config_.reset_rung_limit >= 1;
  backoff_us_ = config_.backoff_initial_us;
  state_since_ = deadline_ = clock_.now_us();
  if (config_ok_) build_commands();
}

void FastrakSession::build_commands() {
  // One command per '\0'-terminated entry; sent one per command pause.
  std::size_t len = 0;
  auto end_cmd = [&] { commands_[len++] = '\0'; };
  bool ok = true;
  for (int s = 1; s <= kMaxStations; ++s) {
    const StationConfig& st = config_.protocol.stations[static_cast<std::size_t>(s - 1)];
    ok = ok && append(commands_, len, "l") && append_int(commands_, len, s) &&
         append(commands_, len, st.enabled ? ",1\r" : ",0\r");
    end_cmd();
    if (!st.enabled) continue;
    ok = ok && append(commands_, len, "O") && append_int(commands_, len, s);
    for (std::size_t i = 0; i < st.list.count; ++i) {
      ok = ok && append(commands_, len, ",") &&
           append_int(commands_, len, static_cast<int>(st.list.items[i]));
    }
    ok = ok && append(commands_, len, "\r");
    end_cmd();
    const auto& h = config_.hemisphere[static_cast<std::size_t>(s - 1)];
    ok = ok && append(commands_, len, "H") && append_int(commands_, len, s) &&
         append(commands_, len, ",") && append_int(commands_, len, h[0]) &&
         append(commands_, len, ",") && append_int(commands_, len, h[1]) &&
         append(commands_, len, ",") && append_int(commands_, len, h[2]) &&
         append(commands_, len, "\r");
    end_cmd();
  }
  ok = ok && append_filter('x', config_.position_filter, len);
  ok = ok && append_filter('v', config_.attitude_filter, len);
  // e1,0: the stylus must never toggle the stream off (docs/fastrak-protocol.md §6 pitfall 4).
  ok = ok && append(commands_, len, "e1,0\r");
  end_cmd();
  ok = ok && append(commands_, len, config_.protocol.units == Units::inches ? "U" : "u");
  end_cmd();
  // binary16 is selected with `f` as well: on a unit whose binary is the packed format.
  ok = ok && append(commands_, len, config_.protocol.format == Format::ascii ? "F" : "f");
  end_cmd();
  TWISTER_ASSERT(ok);  // 4 stations x 32 items always fit the buffer
  commands_len_ = len;
}

bool FastrakSession::append_filter(char command, const FilterSetting& setting, std::size_t& len) {
  if (setting.mode == FilterSetting::Mode::leave) return true;
  const char head[2] = {command, '\0'};
  bool ok = append(commands_, len, head);
  if (setting.mode == FilterSetting::Mode::off) {
    ok = ok && append(commands_, len, ",1\r");  // FLOW = 1.0 disables the filter
  } else {
    ok = ok && append_unit3(commands_, len, setting.f) && append(commands_, len, ",") &&
         append_unit3(commands_, len, setting.flow) && append(commands_, len, ",") &&
         append_unit3(commands_, len, setting.fhigh) && append(commands_, len, ",") &&
         append_unit3(commands_, len, setting.factor) && append(commands_, len, "\r");
  }
  if (ok) commands_[len++] = '\0';
  return ok;
}

void FastrakSession::enter(SessionState s, ports::TimestampUs now) {
  state_ = s;
  state_since_ = now;
}

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

bool FastrakSession::send_text(const char* text, ports::TimestampUs now) {
  return send(std::span<const char>(text, std::strlen(text)), now);
}

void FastrakSession::start_ladder(ports::TimestampUs now) {
  if (rung_ < 1) rung_ = 1;
  ++counters_.inits;
  ladder_len_ = 0;
  if (rung_ >= 2) ladder_[ladder_len_++] = '\r';    // ends a half-typed command
  ladder_[ladder_len_++] = 'c';                     // leave continuous mode
  if (rung_ >= 3) ladder_[ladder_len_++] = kCtrlY;  // full re-initialisation
  ladder_pos_ = 0;
  deadline_ = now;
  enter(SessionState::ladder, now);
}

void FastrakSession::fault(ports::TimestampUs now) {
  parser_.reset();
  rx_len_ = rx_pos_ = 0;
  port_open_ = false;  // the port is reopened (VRPN closes and reopens as well)
  deadline_ = now + backoff_us_;
  backoff_us_ = std::min(backoff_us_ * 2, config_.backoff_max_us);
  enter(SessionState::backoff, now);
}

void FastrakSession::reinitialise() {
  ++counters_.reinit_requests;
  const ports::TimestampUs now = clock_.now_us();
  parser_.reset();
  rx_len_ = rx_pos_ = 0;
  port_open_ = false;
  rung_ = 1;
  deadline_ = now;
  enter(SessionState::backoff, now);
}

void FastrakSession::step_timers(ports::TimestampUs now) {
  switch (state_) {
    case SessionState::backoff: {
      if (now < deadline_) return;
      const Status s = stream_.reopen();
      if (!s.ok()) {
        ++counters_.io_errors;
        fault(now);
        return;
      }
      port_open_ = true;
      start_ladder(now);
      return;
    }
    case SessionState::ladder: {
      if (now < deadline_) return;
      if (ladder_pos_ < ladder_len_) {
        const char c = ladder_[ladder_pos_++];
        if (!send(std::span<const char>(&c, 1), now)) return;
        deadline_ = now + (c == kCtrlY ? config_.reset_wait_us : config_.ladder_char_pause_us);
        return;
      }
      deadline_ = now + config_.settle_us;
      enter(SessionState::settle, now);
      return;
    }
    case SessionState::settle: {
      if (now < deadline_) return;
      // Whatever came during the ladder (records, power-up text) is stale.
      stream_.discard_input();
      parser_.reset();
      rx_len_ = rx_pos_ = 0;
      if (!send_text("S", now)) return;
      deadline_ = now + config_.reply_timeout_us;
      enter(SessionState::await_status, now);
      return;
    }
    case SessionState::await_status:
    case SessionState::verify_status: {
      if (now < deadline_) return;
      ++counters_.status_timeouts;
      if (rung_ < config_.reset_rung_limit) {
        ++rung_;  // escalate at once, as VRPN's ladder does
        start_ladder(now);
      } else {
        fault(now);
      }
      return;
    }
    case SessionState::configuring: {
      if (now < deadline_) return;
      if (command_pos_ < commands_len_) {
        const char* cmd = commands_.data() + command_pos_;
        const std::size_t n = std::strlen(cmd);
        command_pos_ += n + 1;
        if (!send(std::span<const char>(cmd, n), now)) return;
        // The unit is deaf while it processes a command (filters take longest).
        const bool filter = cmd[0] == 'x' || cmd[0] == 'v';
        deadline_ = now + (filter ? config_.filter_pause_us : config_.command_pause_us);
        return;
      }
      if (!send_text("S", now)) return;
      deadline_ = now + config_.reply_timeout_us;
      enter(SessionState::verify_status, now);
      return;
    }
    case SessionState::streaming: {
      if (now - last_pose_ <= config_.silence_timeout_us) return;
      if (now - last_byte_ > config_.silence_timeout_us) {
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
        command_pos_ = 0;
        deadline_ = now;
        enter(SessionState::configuring, now);
      } else if (state_ == SessionState::verify_status) {
        const bool want_bin = config_.protocol.format != Format::ascii;
        const bool want_cm = config_.protocol.units == Units::centimetres;
        if (ev.status.binary != want_bin || ev.status.centimetres != want_cm) {
          ++counters_.status_mismatch;
          if (rung_ < config_.reset_rung_limit) ++rung_;
          fault(now);
          return;
        }
        if (!send_text("C", now)) return;
        ++counters_.streams_started;
        rung_ = 0;
        backoff_us_ = config_.backoff_initial_us;
        last_pose_ = last_byte_ = now;
        continuity_.reset();
        enter(SessionState::streaming, now);
      }
      return;
  }
}

bool FastrakSession::take_pose(const FastrakPose& pose, ports::TimestampUs now) {
  if (!continuity_.accept(pose, now)) {
    ++counters_.jump_rejects;
    return false;
  }
  last_pose_ = now;
  ++counters_.poses;
  if (pose.status != ' ') {  // a warning letter: the pose is used, the code kept
    ++counters_.warning_poses;
    counters_.last_warning = pose.status;
  }
  return true;
}

Result<FastrakPose> FastrakSession::poll() {
  if (!config_ok_) return StatusCode::invalid_argument;
  const ports::TimestampUs now = clock_.now_us();
  // While streaming, silence is judged only once the input is drained: a host that
  // stalled (a slow fsync, a starved process) finds the records that came meanwhile
  // instead of calling a unit that kept sending "lost".
  if (state_ != SessionState::streaming) step_timers(now);
  for (;;) {
    // The parser may still hold an event (an accepted record queued behind its
    // resync report) even when no bytes are left, so ask it before reading.
    std::span<const std::byte> in(rx_.data() + rx_pos_, rx_len_ - rx_pos_);
    auto ev = parser_.next(in);
    rx_pos_ = rx_len_ - in.size();
    if (ev.ok()) {
      if (ev->kind == EventKind::pose && state_ == SessionState::streaming) {
        if (!take_pose(ev->pose, now)) continue;
        return ev->pose;
      }
      handle_event(*ev, now);
      continue;
    }
    if (!port_open_) return StatusCode::unavailable;
    auto n = stream_.read(rx_);
    if (!n.ok()) {
      ++counters_.io_errors;
      fault(now);
      return StatusCode::unavailable;
    }
    if (*n == 0) {
      if (state_ == SessionState::streaming) step_timers(now);
      return StatusCode::unavailable;
    }
    rx_len_ = *n;
    rx_pos_ = 0;
    last_byte_ = now;
  }
}

}  // namespace twister::tracker
