// FastrakSession: owns the command side of a Fastrak over a ByteStream port and
// emits validated poses only. Start-up: reset ladder (docs/fastrak-protocol.md §1.2), status check,
// station enables, output lists, hemispheres, e1,0, units, format, status re-check
// of format/units, continuous mode. Faults (I/O error/unplug, silence, endless
// garbage, missing or wrong replies) lead to automatic re-initialisation with
// exponential back-off; a port that reports its device's arrival (hot-plug) is
// reopened at once, the back-off started afresh. Driven by poll() calls; time comes from the Clock
// port, so all waits (including the unit's 10-20 s reset) are state, never sleeps. No heap.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "twister/base/result.hpp"
#include "twister/ports/byte_stream.hpp"
#include "twister/ports/clock.hpp"
#include "twister/tracker/fastrak_command.hpp"
#include "twister/tracker/fastrak_event.hpp"
#include "twister/tracker/fastrak_parser.hpp"
#include "twister/tracker/fastrak_wire.hpp"
#include "twister/tracker/liberty_parser.hpp"
#include "twister/tracker/liberty_startup.hpp"
#include "twister/tracker/pose_continuity.hpp"

namespace twister::tracker {

// The unit on the line. A Liberty, Patriot or Latus (Liberty HS) is started as the public
// drivers start it (liberty_startup.hpp, docs/liberty-protocol.md §9): the reset ladder
// back to ASCII, WhoAmI in place of `S`, `O` lists in its own item codes
// (to_liberty_config(protocol)), `H`, its filters `X` / `Y`, (`@B0` on a Latus), `U0`/`U1`,
// `F1`, then `C`; in binary its records are Liberty-family frames, so once streaming the
// session reads them with LibertyParser configured the same way. Those models need
// Format::binary.
// A FASTRAK 3 is a fastrak here (the same records).
enum class TrackerModel : std::uint8_t { fastrak, liberty, patriot, latus };
// "FASTRAK", "Liberty", "Patriot", "Latus"
const char* tracker_model_name(TrackerModel model);

// Delay before each re-initialisation: the first, doubled per failure up to the cap.
struct SessionBackoff {
  std::int64_t initial_us = 250'000;  // first re-initialisation delay
  std::int64_t max_us = 8'000'000;    // back-off cap
};

struct FastrakSessionConfig {
  TrackerModel model = TrackerModel::fastrak;
  FastrakConfig protocol{};  // format, units, enabled stations and their output lists
  // `H` vector per station (index = station - 1); default +X ("forward").
  std::array<std::array<int, 3>, kMaxStations> hemisphere{
      {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}}};
  // All durations in microseconds. Defaults suit a real unit; the simulator and
  // tests shorten them.
  std::int64_t ladder_char_pause_us = 200'000;  // pause after each ladder byte
  std::int64_t reset_wait_us = 15'000'000;      // after ^Y (Vrui 15 s, VRPN 20 s)
  std::int64_t settle_us = 500'000;             // before `S`, input is discarded
  std::int64_t reply_timeout_us = 2'000'000;    // wait for the status reply
  std::int64_t command_pause_us = 100'000;      // between configuration commands
  std::int64_t filter_pause_us = 1'000'000;     // after `x` / `v` (VRPN waits 1 s)
  std::int64_t silence_timeout_us = 2'000'000;  // no valid pose -> fault (VRPN 2 s)
  SessionBackoff backoff{};                     // re-initialisation delays
  int reset_rung_limit = 3;                     // highest ladder rung: 1 `c`, 2 CR+`c`, 3 CR+`c`+^Y
  FilterSetting position_filter{};              // `x`, sent after the output lists
  FilterSetting attitude_filter{};              // `v`
  // Jumps between a station's successive poses beyond these limits are held back
  // (pose_continuity.hpp); max_speed_in_s = max_turn_rate_deg_s = 0 turns it off.
  ContinuityLimits continuity{};
};

enum class SessionState : std::uint8_t {
  backoff,        // waiting before (re)opening the port
  ladder,         // writing the reset ladder bytes with their pauses
  settle,         // waiting, then discarding stray input before `S`
  await_status,   // `S` sent, waiting for the 55-byte status reply
  configuring,    // sending the configuration commands one by one
  verify_status,  // `S` sent after configuring: format/units must match
  streaming,      // `C` sent; poses flow
};
const char* session_state_name(SessionState s);

struct FastrakSessionCounters {
  std::uint64_t poses = 0;            // poses handed to the caller
  std::uint64_t inits = 0;            // start-up sequences begun
  std::uint64_t streams_started = 0;  // start-ups that reached streaming
  std::uint64_t status_timeouts = 0;  // no status reply in time
  std::uint64_t status_mismatch = 0;  // status flags disagree with the configuration
  std::uint64_t command_errors = 0;   // command-error records received
  std::uint64_t io_errors = 0;        // read/write/reopen failures (unplug)
  std::uint64_t silence_faults = 0;   // no bytes at all for silence_timeout
  std::uint64_t garbage_faults = 0;   // bytes but no valid pose for silence_timeout
  std::uint64_t rejected_poses = 0;   // plausibility errors reported by the parser
  std::uint64_t jump_rejects = 0;     // poses held back by the continuity check
  std::uint64_t warning_poses = 0;    // poses used whose status byte was a letter (§3.1)
  char last_warning = ' ';            // that letter, most recent
  std::uint64_t reinit_requests = 0;  // reinitialise() calls
};

class FastrakSession {
 public:
  // The stream and clock must outlive the session. The stream is (re)opened by the
  // session itself. The configuration is checked at the first poll(); an invalid
  // one keeps the session in back-off and poll() returns invalid_argument.
  FastrakSession(ports::ByteStream& stream, ports::Clock& clock,
                 const FastrakSessionConfig& config);

  // Advances the state machine (non-blocking) and returns the next validated pose.
  // Call until it returns unavailable. unavailable: no pose now;
  // invalid_argument: the configuration is invalid (nothing is sent).
  Result<FastrakPose> poll();

  // Forces a new start-up (e.g. after the caller changed something on the unit).
  void reinitialise();

  SessionState state() const { return state_; }
  bool streaming() const { return state_ == SessionState::streaming; }
  const FastrakSessionCounters& counters() const { return counters_; }
  const FastrakParserCounters& parser_counters() const { return parsers_.fastrak.counters(); }
  // The frame parser's counters (model liberty / patriot; zero for a Fastrak).
  const LibertyParserCounters& liberty_parser_counters() const {
    return parsers_.liberty.counters();
  }
  const FastrakStatus& last_status() const { return last_status_; }
  const FastrakSessionConfig& config() const { return config_; }
  int ladder_rung() const { return recovery_.rung; }

 private:
  void enter(SessionState s);
  void fault(ports::TimestampUs now);
  void step_timers(ports::TimestampUs now);
  bool send(std::span<const char> text, ports::TimestampUs now);
  bool send_command(const FastrakCommand& command, ports::TimestampUs now);
  void start_ladder(ports::TimestampUs now);
  // `C` sent: the stream starts, the recovery state is reset.
  void start_streaming(ports::TimestampUs now);
  // A Liberty's WhoAmI reply, once it has stopped coming: configure, or a fault.
  void judge_whoami(ports::TimestampUs now);
  void build_commands();
  // The Liberty family's configuration commands (docs/liberty-protocol.md §9).
  bool build_liberty_commands();
  // Appends `text` as one configuration command.
  bool add_text(std::string_view text);
  // Appends one encoded command to the configuration commands.
  bool add_command(const FastrakCommand& command);
  // Appends a Liberty-family `O` command for `station` (its list from the frame parser).
  bool add_liberty_list(int station);
  // A validated pose while streaming: continuity and status bookkeeping. false: held back.
  bool take_pose(const FastrakPose& pose, ports::TimestampUs now);
  void handle_event(const FastrakEvent& ev, ports::TimestampUs now);
  // The next event from rx_: frames while a Liberty-family unit streams, else records
  // and replies.
  Result<FastrakEvent> next_event();

  // A fixed buffer and how far it is filled (len) and used (pos).
  template <typename T, std::size_t N>
  struct Buffer {
    std::array<T, N> data{};
    std::size_t len = 0;
    std::size_t pos = 0;
  };
  struct Timers {
    ports::TimestampUs deadline = 0;   // the current state's wait ends
    ports::TimestampUs last_pose = 0;  // a pose was last accepted
    ports::TimestampUs last_byte = 0;  // a byte was last read
  };
  // The Fastrak parser reads replies (and a Fastrak's records); the frame parser reads a
  // Liberty's or Patriot's records while streaming.
  struct Parsers {
    FastrakParser fastrak;
    LibertyParser liberty;
    void reset() {
      fastrak.reset();
      liberty.reset();
    }
  };
  struct Recovery {
    std::int64_t backoff_us = 0;  // the next re-initialisation delay
    int rung = 0;                 // the reset ladder's rung
  };

  ports::ByteStream& stream_;
  ports::Clock& clock_;
  FastrakSessionConfig config_;
  Parsers parsers_;
  PoseContinuity continuity_;
  struct Flags {
    bool config_ok = false;
    bool port_open = false;
    char whoami_first = 0;  // a Liberty's WhoAmI reply's first byte (0: none yet)
  };
  Flags flags_{};
  SessionState state_ = SessionState::backoff;
  Timers timers_{};
  Recovery recovery_{};
  FastrakStatus last_status_{};
  Buffer<char, 8> ladder_{};  // ladder bytes of the current attempt, sent one per pause
  // Configuration commands (fastrak_command.hpp, encoded), '\0'-separated, sent one
  // per command pause.
  Buffer<char, 1024> commands_{};
  Buffer<std::byte, 512> rx_{};  // bytes read but not yet parsed
  FastrakSessionCounters counters_{};
};

}  // namespace twister::tracker
