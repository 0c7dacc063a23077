// The device model's serial input: command framing (single letters and control
// bytes; parameter commands up to CR; stray LF and CR ignored), the processing time of
// each command during which the unit is deaf, and a host at the wrong baud.
#include "twister/sim/fastrak_device.hpp"

// GCC 12 reports a false -Wrestrict inside std::string concatenation at -O3
// (GCC bug 105329); nothing here overlaps.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace twister::sim {
namespace {

using tracker::kCtrlK;
using tracker::kCtrlQ;
using tracker::kCtrlS;
using tracker::kCtrlY;

constexpr char kModeCommands[] = {'P', 'C', 'c', 'F', 'f',    'U',    'u',    'S',
                                  'W', 'T', 'D', 'd', kCtrlY, kCtrlK, kCtrlS, kCtrlQ};
constexpr char kParameterCommands[] = {'O', 'l', 'H', 'A', 'R', 'B', 'b', 'G',
                                       'N', 'e', 'I', 'x', 'v', 'Q', 'X', 'o'};

bool is_one_of(char c, const char* set, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    if (set[i] == c) return true;
  }
  return false;
}

}  // namespace

CommandTimes default_command_times() {
  CommandTimes t{};
  for (const char c : kParameterCommands) t[static_cast<std::size_t>(c)] = 40'000;
  t['x'] = t['v'] = 500'000;
  t[static_cast<std::size_t>(kCtrlK)] = 3'000'000;
  t['W'] = 1'000'000;
  return t;
}

CommandTimes instant_commands() { return CommandTimes{}; }

std::int64_t FastrakDevice::command_time(char command) const {
  const auto i = static_cast<unsigned char>(command);
  return i < config_.command_time_us.size() ? config_.command_time_us[i] : 0;
}

void FastrakDevice::receive(const std::byte* data, std::size_t size, ports::TimestampUs now) {
  apply_faults(now);
  // A resetting, stalled or hung-up unit understands nothing.
  if (now < busy_until_ || in_window(now, FaultKind::stall) || in_window(now, FaultKind::hangup)) {
    return;
  }
  const bool misclock = misclocked(now);
  for (std::size_t i = 0; i < size; ++i) {
    std::byte b = data[i];
    if (misclock && !misclock_byte(b)) continue;
    if (now < busy_until_) return;  // a ^Y earlier in this chunk
    if (now < deaf_until_) {        // still processing the previous command
      ++counters_.input_lost;
      continue;
    }
    const char c = static_cast<char>(b);
    if (!in_param_cmd_) {
      receive_command_byte(c, now);
      continue;
    }
    if (c == '\r') {
      in_param_cmd_ = false;
      // Replies leave when the command is done; until then the unit is deaf.
      const char command = pending_cmd_[0];
      const ports::TimestampUs done = now + command_time(command);
      execute(command, pending_cmd_.substr(1), done);
      pending_cmd_.clear();
      deaf_until_ = std::max(deaf_until_, done);
    } else if (c != '\n') {
      pending_cmd_ += c;
      if (pending_cmd_.size() > 80) {
        in_param_cmd_ = false;
        send_error(pending_cmd_, -5, now);
        pending_cmd_.clear();
      }
    }
  }
}

void FastrakDevice::receive_command_byte(char c, ports::TimestampUs now) {
  if (c == '\r' || c == '\n') return;
  if (is_one_of(c, kModeCommands, sizeof kModeCommands)) {
    const ports::TimestampUs done = now + command_time(c);
    execute(c, {}, done);
    deaf_until_ = std::max(deaf_until_, done);
    return;
  }
  if (is_one_of(c, kParameterCommands, sizeof kParameterCommands)) {
    in_param_cmd_ = true;
    pending_cmd_.assign(1, c);
    return;
  }
  send_error(std::string(1, c), -99, now);
}

}  // namespace twister::sim
