// CommandInput: the simulated Fastrak's ear. Frames the host's bytes into commands with
// the shared codec (tracker/fastrak_command.hpp): a mode byte acts at once, a parameter
// letter collects its fields up to CR (stray LF and CR ignored, over 80 bytes: error
// -5), any other byte is an unknown command (error -99). Each command takes its
// processing time (CommandTimes); bytes that arrive meanwhile wait in the unit's input
// buffer (kInputBufferBytes, as a UART's receive interrupt fills a firmware ring) and are
// read when it is done; a byte arriving at a full buffer is lost (an overrun), as is
// everything buffered when the unit resets. A unit configured with no buffer
// (input_buffer 0) loses every byte sent while it is busy. A Liberty or Patriot frames
// every command up to CR but `P` (the Liberty dialect, tracker/liberty_startup.hpp,
// docs/liberty-protocol.md §9): `F0`/`F1`, `U0`/`U1`, `C`, ^Y and `X`/`Y` read as the
// Fastrak's `F`/`f`, `U`/`u`, `C`, ^Y and `x`/`v`, ^V is WhoAmI, `@B0` is taken without
// effect, `O` and `H` as the Fastrak's; letters in either case (read as upper case).
// Not thread-safe.
#pragma once

#include <array>
#include <cstddef>
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

// Bytes the unit's input buffer holds while a command is processed. The manuals give no
// size (error code -5 "buffer limit" exists); 256 is assumed, more than a host's whole
// configuration burst (VRPN's reset ladder, the station's commands) needs.
inline constexpr std::size_t kInputBufferBytes = 256;

class CommandInput {
 public:
  // who_am_i: a Liberty's ^V, done at done().
  enum class Heard : std::uint8_t { nothing, lost, command, error, who_am_i };

  explicit CommandInput(const CommandTimes& times, std::size_t buffer = kInputBufferBytes,
                        bool liberty = false)
      : times_(times),
        buffer_limit_(buffer < kInputBufferBytes ? buffer : kInputBufferBytes),
        liberty_(liberty) {
    pending_.reserve(96);
    echo_.reserve(96);
  }

  // One byte at `now`. While the unit is busy with a command (or bytes wait before this
  // one) the byte is buffered (nothing) or, the buffer being full, lost; otherwise
  // command: command() is complete and done at done(); error: error_code() for the input
  // echo().
  Heard take(char byte, ports::TimestampUs now);
  // True when a buffered byte can be read at `now` (the unit is done); ready_at() is
  // the time it is read at.
  bool buffered_ready(ports::TimestampUs now) const { return buffered_ > 0 && deaf_until_ <= now; }
  ports::TimestampUs ready_at() const { return deaf_until_; }
  // Reads the next buffered byte (only when buffered_ready()), as take() at ready_at().
  Heard take_buffered();
  std::size_t buffered() const { return buffered_; }
  const tracker::FastrakCommand& command() const { return command_; }
  ports::TimestampUs done() const { return done_; }
  // The command, or the bad input, as received (for error records).
  std::string_view echo() const { return echo_; }
  int error_code() const { return error_code_; }
  // Power-up: nothing pending, listening at once; the buffer is emptied. Returns the
  // buffered bytes lost.
  std::size_t reset();
  // Deaf until `t` at least (a command that reset the input still takes its time).
  void hold_until(ports::TimestampUs t) { deaf_until_ = deaf_until_ > t ? deaf_until_ : t; }

 private:
  Heard frame(char byte, ports::TimestampUs now);
  Heard take_first(char byte, ports::TimestampUs now);
  // A Liberty's command line (without its CR) as the shared command it means.
  Heard liberty_line(ports::TimestampUs now);
  Heard finish(const tracker::FastrakCommand& command, ports::TimestampUs now);
  Heard fail(int code);
  std::int64_t command_time(char letter) const;

  const CommandTimes& times_;
  std::size_t buffer_limit_;
  bool liberty_ = false;                          // the Liberty dialect
  std::array<char, kInputBufferBytes> buffer_{};  // ring of bytes waiting to be read
  std::size_t buffer_head_ = 0;
  std::size_t buffered_ = 0;
  std::string pending_;
  bool in_parameter_ = false;
  ports::TimestampUs deaf_until_ = 0;
  tracker::FastrakCommand command_{};
  ports::TimestampUs done_ = 0;
  std::string echo_;
  int error_code_ = 0;
};

}  // namespace twister::sim
