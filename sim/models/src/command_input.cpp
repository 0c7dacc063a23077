#include "twister/sim/command_input.hpp"

#include <algorithm>
#include <string_view>
#include <variant>

#include "twister/tracker/liberty_startup.hpp"

namespace twister::sim {

CommandTimes default_command_times() {
  CommandTimes t{};
  for (std::size_t c = 0; c < t.size(); ++c) {
    if (tracker::parameter_command(static_cast<char>(c))) t[c] = 40'000;
  }
  t[static_cast<std::size_t>(tracker::ParameterCommand::position_filter)] = 500'000;
  t[static_cast<std::size_t>(tracker::ParameterCommand::attitude_filter)] = 500'000;
  t[static_cast<std::size_t>(tracker::ModeCommand::save)] = 3'000'000;
  t[static_cast<std::size_t>(tracker::ModeCommand::factory_defaults)] = 1'000'000;
  return t;
}

CommandTimes instant_commands() { return CommandTimes{}; }

std::int64_t CommandInput::command_time(char letter) const {
  const auto i = static_cast<unsigned char>(letter);
  return i < times_.size() ? times_[i] : 0;
}

std::size_t CommandInput::reset() {
  pending_.clear();
  in_parameter_ = false;
  deaf_until_ = 0;
  const std::size_t lost = buffered_;
  buffer_head_ = buffered_ = 0;
  return lost;
}

CommandInput::Heard CommandInput::take(char byte, ports::TimestampUs now) {
  // Still processing the previous command, or earlier bytes wait: into the buffer.
  if (now < deaf_until_ || buffered_ > 0) {
    if (buffered_ >= buffer_limit_) return Heard::lost;  // overrun
    buffer_[(buffer_head_ + buffered_) % buffer_.size()] = byte;
    ++buffered_;
    return Heard::nothing;
  }
  return frame(byte, now);
}

CommandInput::Heard CommandInput::take_buffered() {
  const char byte = buffer_[buffer_head_];
  buffer_head_ = (buffer_head_ + 1) % buffer_.size();
  --buffered_;
  return frame(byte, deaf_until_);
}

CommandInput::Heard CommandInput::frame(char byte, ports::TimestampUs now) {
  // The Liberty dialect takes either case (polhemus_ros_driver sends `f1`, `c`, `h*`,
  // `p`; docs/liberty-protocol.md §9); found by liberty_command_fuzz.
  if (liberty_ && byte >= 'a' && byte <= 'z') byte = static_cast<char>(byte - 'a' + 'A');
  if (!in_parameter_) return take_first(byte, now);
  if (byte == tracker::kCr && liberty_) {
    in_parameter_ = false;
    return liberty_line(now);
  }
  if (byte == tracker::kCr) {
    in_parameter_ = false;
    pending_ += byte;
    const auto decoded = tracker::decode(std::span<const char>(pending_.data(), pending_.size()));
    pending_.pop_back();
    echo_ = pending_;
    pending_.clear();
    if (!decoded.ok()) return fail(-5);  // cannot happen: 80 bytes fit a command
    return finish(*decoded, now);
  }
  if (byte == tracker::kLf) return Heard::nothing;
  pending_ += byte;
  if (pending_.size() > 80) {
    in_parameter_ = false;
    echo_ = pending_;
    pending_.clear();
    return fail(-5);
  }
  return Heard::nothing;
}

CommandInput::Heard CommandInput::take_first(char byte, ports::TimestampUs now) {
  if (byte == tracker::kCr || byte == tracker::kLf) return Heard::nothing;
  if (liberty_ && byte != tracker::kLibertyPoll) {  // a line up to CR
    in_parameter_ = true;
    pending_.assign(1, byte);
    return Heard::nothing;
  }
  if (const auto mode = tracker::mode_command(byte)) {
    echo_.assign(1, byte);
    return finish(tracker::Mode{*mode}, now);
  }
  if (tracker::parameter_command(byte)) {
    in_parameter_ = true;
    pending_.assign(1, byte);
    return Heard::nothing;
  }
  echo_.assign(1, byte);
  return fail(-99);
}

CommandInput::Heard CommandInput::liberty_line(ports::TimestampUs now) {
  using tracker::ModeCommand;
  echo_ = pending_;
  const std::string line = pending_;
  pending_.clear();
  struct Word {
    std::string_view text;
    ModeCommand mode;
  };
  static constexpr Word kWords[] = {
      {tracker::kLibertyAscii, ModeCommand::ascii},
      {tracker::kLibertyBinary, ModeCommand::binary},
      {tracker::kLibertyInches, ModeCommand::inches},
      {tracker::kLibertyCentimetres, ModeCommand::centimetres},
      {tracker::kLibertyStartContinuous, ModeCommand::continuous},
  };
  for (const Word& w : kWords) {
    if (w.text.substr(0, w.text.size() - 1) == line) return finish(tracker::Mode{w.mode}, now);
  }
  if (line == std::string(1, tracker::kCtrlY)) {
    return finish(tracker::Mode{ModeCommand::reinitialise}, now);
  }
  if (line == std::string(1, tracker::kCtrlV)) {
    done_ = now + command_time(tracker::kCtrlV);
    deaf_until_ = std::max(deaf_until_, done_);
    return Heard::who_am_i;
  }
  if (line + tracker::kCr == tracker::kLatusUsbBufferingOff) return Heard::nothing;  // no effect
  std::string fastrak = line;
  if (line[0] == tracker::kLibertyPositionFilter || line[0] == tracker::kLibertyAttitudeFilter) {
    fastrak[0] = line[0] == tracker::kLibertyPositionFilter ? 'x' : 'v';
    // FLOW = 1 switches the filter off (VRPN's `X0,1,0,0`): the Fastrak's `x,1`.
    const std::size_t comma = line.find(',');
    if (comma != std::string::npos && line.compare(comma, 3, ",1,") == 0)
      fastrak = fastrak.substr(0, 1) + ",1";
  }
  fastrak += tracker::kCr;
  const auto decoded = tracker::decode(std::span<const char>(fastrak.data(), fastrak.size()));
  if (!decoded.ok() || !std::holds_alternative<tracker::Parameters>(*decoded)) return fail(-99);
  return finish(*decoded, now);
}

CommandInput::Heard CommandInput::finish(const tracker::FastrakCommand& command,
                                         ports::TimestampUs now) {
  command_ = command;
  // Replies leave when the command is done; until then the unit is deaf.
  done_ = now + command_time(tracker::letter(command));
  deaf_until_ = std::max(deaf_until_, done_);
  return Heard::command;
}

CommandInput::Heard CommandInput::fail(int code) {
  error_code_ = code;
  return Heard::error;
}

}  // namespace twister::sim
