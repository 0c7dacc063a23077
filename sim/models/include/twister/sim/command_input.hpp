// CommandInput: the simulated Fastrak's ear. Frames the host's bytes into commands with
// the shared codec (tracker/fastrak_command.hpp): a mode byte acts at once, a parameter
// letter collects its fields up to CR (stray LF and CR ignored, over 80 bytes: error
// -5), any other byte is an unknown command (error -99). Each command takes its
// processing time (CommandTimes); bytes that arrive meanwhile are lost. Not thread-safe.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "twister/ports/clock.hpp"
#include "twister/tracker/fastrak_command.hpp"

namespace twister::sim {

// Processing time of each command (index: its letter or control byte), microseconds:
// from the command's last byte until the unit listens again; bytes sent meanwhile are
// lost, and a reply leaves when the command is done.
using CommandTimes = std::array<std::int32_t, 128>;
// Defaults (docs/fastrak.md): 40 ms for parameter commands (VRPN waits 50 ms after
// `O`), 500 ms for the filters `x`, `v` (VRPN waits 1 s), 3 s for ^K (manual: "several
// seconds"), 1 s for W, 0 for the single-letter modes; ^Y is reset_time_us. Assumed
// except ^K's order of magnitude.
CommandTimes default_command_times();
// Every command done at once (tests of behaviour other than timing).
CommandTimes instant_commands();

class CommandInput {
 public:
  enum class Heard : std::uint8_t { nothing, lost, command, error };

  explicit CommandInput(const CommandTimes& times) : times_(times) {
    pending_.reserve(96);
    echo_.reserve(96);
  }

  // One byte at `now`. lost: the unit was busy with a command; command: command() is
  // complete and done at done(); error: error_code() for the input echo().
  Heard take(char byte, ports::TimestampUs now);
  const tracker::FastrakCommand& command() const { return command_; }
  ports::TimestampUs done() const { return done_; }
  // The command, or the bad input, as received (for error records).
  std::string_view echo() const { return echo_; }
  int error_code() const { return error_code_; }
  // Power-up: nothing pending, listening at once.
  void reset();
  // Deaf until `t` at least (a command that reset the input still takes its time).
  void hold_until(ports::TimestampUs t) { deaf_until_ = deaf_until_ > t ? deaf_until_ : t; }

 private:
  Heard take_first(char byte, ports::TimestampUs now);
  Heard finish(const tracker::FastrakCommand& command, ports::TimestampUs now);
  Heard fail(int code);
  std::int64_t command_time(char letter) const;

  const CommandTimes& times_;
  std::string pending_;
  bool in_parameter_ = false;
  ports::TimestampUs deaf_until_ = 0;
  tracker::FastrakCommand command_{};
  ports::TimestampUs done_ = 0;
  std::string echo_;
  int error_code_ = 0;
};

}  // namespace twister::sim
