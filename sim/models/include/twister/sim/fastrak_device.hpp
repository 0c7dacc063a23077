// FastrakDevice: a model of a Polhemus FASTRAK as seen from its serial port
// (docs/fastrak-protocol.md; what is modelled and what is assumed:
// docs/fastrak.md). It answers the command set a host uses (§2), taking time to
// process each command (input meanwhile is lost), streams records at 120 Hz shared
// by the active stations (§1 cycle) through its adaptive position / attitude filters,
// in ASCII, binary or 16-bit packed via the core encoder, limited to baud/10 bytes
// per second (whole solutions are dropped when the line is busy), sets the header's
// status letter ('y' outside the `Q` envelope, scripted letters), models the stylus
// e-mode toggle (§6 pitfall 4), the slow ^Y reset and a host at the wrong baud, and
// injects the scenario's faults. Time is passed in by the caller (microseconds, any
// epoch fixed at construction), so it runs in virtual or real time. Steady state
// (record generation, filters, corruption, the line, advance) uses no heap: the line
// is a fixed LineQueue; command handling (start-up) may allocate. Not thread-safe.
// The device composes its parts, one job each: CommandInput (framing, processing time),
// ParameterCommands (the parameter commands), UnitSettings (what they set),
// StationSolver (solutions through the filters), FaultSchedule (the scenario's faults),
// PacedLine (the output line); it runs the 120 Hz cycle, the mode commands and records.
#pragma once

#include <array>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "twister/ports/clock.hpp"
#include "twister/sim/adaptive_filter.hpp"
#include "twister/sim/command_input.hpp"
#include "twister/sim/fault_schedule.hpp"
#include "twister/sim/paced_line.hpp"
#include "twister/sim/parameter_commands.hpp"
#include "twister/sim/scenario.hpp"
#include "twister/sim/station_solver.hpp"
#include "twister/sim/unit_settings.hpp"
#include "twister/tracker/fastrak_event.hpp"
#include "twister/tracker/fastrak_wire.hpp"
#include "twister/tracker/liberty_wire.hpp"

namespace twister::sim {

// Which unit the model plays. A Liberty or Patriot takes its own dialect of the commands
// (CommandInput: lines up to CR, `F1`, `U1`, `C`, `X`/`Y`, WhoAmI ^V answered with a line
// starting '0') and sends the Fastrak's ASCII records here; in binary it frames each
// record with the family's header (docs/liberty-protocol.md; the ASCII records and the
// WhoAmI text are assumptions, docs/fastrak.md).
enum class DeviceModel : std::uint8_t { fastrak, liberty, patriot };
const char* device_model_name(DeviceModel model);

// Where the scenario's clock starts (docs/fastrak.md, "Scenario clock"): when the unit
// powers up (the default; the in-process simulator's station starts with it), or at the
// first `C` after power-up: the moment the host starts continuous output, so that a
// scenario's motion, faults and presses do not race the host's start-up. Before that `C`
// the hands rest at their t = 0 pose and no fault falls due.
enum class ScenarioClock : std::uint8_t { power_up, first_continuous };

// A real unit's boot (power-up or ^Y) time. VRPN's Fastrak driver waits 20 s after ^Y
// and says 10 s is enough for an actual Fastrak (InterSense units need 20); Vrui waits
// 15 s (docs/fastrak-protocol.md §1.1). twister-sim's default; tests pass --reset-time.
inline constexpr std::int64_t kRealUnitBootUs = 10'000'000;

struct FastrakDeviceConfig {
  DeviceModel model = DeviceModel::fastrak;
  int baud = 115200;                     // line rate; 10 bits per byte (`o` changes it)
  std::int64_t reset_time_us = 500'000;  // ^Y and power-up (a real unit: kRealUnitBootUs)
  ScenarioClock scenario_clock = ScenarioClock::power_up;
  bool start_continuous = false;  // power-up mode (the real default is polled)
  tracker::Format start_format = tracker::Format::ascii;
  // The unit's binary format, chosen by `f`: IEEE floats (Fastrak), or the 16-bit
  // packed format of an Isotrak II / 3SPACE-style unit.
  bool packed16 = false;
  CommandTimes command_time_us = default_command_times();
  // Bytes the input buffer holds while a command is processed (0: bytes sent meanwhile
  // are lost, as this model did before issue 22; at most kInputBufferBytes).
  std::size_t input_buffer_bytes = kInputBufferBytes;
  FilterParams start_position_filter = kFilterOff;  // power-up filters
  FilterParams start_attitude_filter = kFilterOff;
  // At a baud mismatch a byte survives as one junk byte with this probability; the
  // rest are framing errors the receiving UART drops (IGNPAR). Assumed.
  double misclock_junk = 1.0 / 16.0;
};

// What the unit put on its line and what became of it there (one group of
// FastrakDeviceCounters).
struct FastrakOutputCounters {
  std::uint64_t records = 0;       // records queued for transmission
  std::uint64_t bytes_out = 0;     // bytes handed to the line
  std::uint64_t stylus_polls = 0;  // stylus presses in polled mode (each acts as `P`)
  std::uint64_t hangup_lost = 0;   // bytes sent while a hang-up held the line down
};

struct FastrakDeviceCounters {
  FastrakOutputCounters output;         // records, bytes, polled presses, hang-up losses
  std::uint64_t dropped_solutions = 0;  // cycles skipped because the line was busy
  std::uint64_t commands = 0;           // commands executed
  std::uint64_t command_errors = 0;     // error records sent
  std::uint64_t resets = 0;             // ^Y and power-ups
  std::uint64_t line_overflow = 0;      // bytes lost because the line queue was full
  std::uint64_t input_lost = 0;         // bytes lost: input buffer full, or buffered at a reset
  std::uint64_t corrupted_records = 0;  // records with a corrupted field (fault corrupt)
  std::uint64_t dropped_bytes = 0;      // output bytes eaten by a `drop` fault
  std::uint64_t drop_expired = 0;       // drop budget discarded (stream stopped, reset)
  std::uint64_t misclock_lost = 0;      // bytes (either way) lost to a baud mismatch
  std::uint64_t misclock_junk = 0;      // junk bytes (either way) from a baud mismatch
  std::uint64_t status_letters = 0;     // records sent with a status letter
  std::array<std::uint64_t, kFaultKindCount> faults{};  // injected, indexed by FaultKind
};

class FastrakDevice final : private ReplySink {
 public:
  FastrakDevice(const FastrakDeviceConfig& config, Scenario scenario, ports::TimestampUs start_us);
  // The parts refer to each other: neither copied nor moved.
  FastrakDevice(const FastrakDevice&) = delete;
  FastrakDevice& operator=(const FastrakDevice&) = delete;

  // Bytes from the host (commands). LF and stray CR around commands are ignored.
  void receive(const std::byte* data, std::size_t size, ports::TimestampUs now);
  // Runs the model up to `now` and copies up to out.size() of the bytes whose
  // transmission has completed by then into `out`; returns how many. Bytes that do
  // not fit stay queued for the next call. No heap.
  std::size_t advance(ports::TimestampUs now, std::span<std::byte> out);
  // The same, appending every byte ready by `now` to `out` (twister-sim, tests).
  void advance(ports::TimestampUs now, std::vector<std::byte>& out);
  // True while a hang-up fault holds the line down (the server closes the port).
  bool hung_up(ports::TimestampUs now);
  // The host's line rate as far as the server can tell (a PTY master reads the slave's
  // configured speed); 0 = unknown (taken as matching).
  void set_host_baud(int baud) { host_baud_ = baud; }
  // True when the line is mis-clocked at `t`: host and unit at different rates, or a
  // `wrongbaud` fault.
  bool misclocked(ports::TimestampUs t) const;

  const FastrakDeviceCounters& counters() const { return counters_; }
  bool continuous() const { return settings_.continuous; }
  int baud() const { return settings_.baud; }
  const tracker::FastrakConfig& protocol() const { return settings_.protocol; }
  const FilterParams& position_filter() const { return settings_.filter[0]; }
  const FilterParams& attitude_filter() const { return settings_.filter[1]; }
  // Scenario time at `now` (0 before the scenario's clock has started).
  ports::TimestampUs scenario_time_us(ports::TimestampUs now) const;
  double scenario_time_s(ports::TimestampUs now) const;
  // True once the scenario's clock runs (at once with ScenarioClock::power_up).
  bool scenario_started() const { return scenario_origin_ != kNotYet; }

 private:
  // Where the 120 Hz cycle stands.
  struct Cycle {
    std::int64_t next = 0;           // the next cycle's number
    std::size_t next_station = 0;    // next station to send (continuous mode)
    std::size_t polled_station = 0;  // next station to solve while nothing is sent
    bool last_button = false;        // the stylus at the previous cycle (toggle edge)
  };

  void power_up(ports::TimestampUs now);
  void apply_faults(ports::TimestampUs now);
  // Reads the input buffer's bytes that the unit, done with its command, takes by `now`.
  void read_buffered(ports::TimestampUs now);
  void heard(CommandInput::Heard what, ports::TimestampUs at);
  void execute(const tracker::FastrakCommand& command, std::string_view echo,
               ports::TimestampUs now);
  // The single-byte commands (mode letters, status, resets).
  void execute_mode(tracker::ModeCommand command, ports::TimestampUs now);
  void send_status(ports::TimestampUs now);
  void reply(std::string_view text, ports::TimestampUs at) override;
  void error(std::string_view echo, int code, ports::TimestampUs at) override;
  void queue(std::span<const std::byte> bytes, ports::TimestampUs now);
  void queue_noise(std::uint64_t count, ports::TimestampUs now);
  void queue_record(int station, ports::TimestampUs at);
  // Encodes `pose` as the model frames it (Fastrak record or Liberty-family frame),
  // corrupting it when a corrupt fault is due; returns the bytes (0: not encodable).
  std::size_t encode_pose(const tracker::FastrakPose& pose, std::span<std::byte> buf);
  void solve(int station, ports::TimestampUs at);
  // The header status byte of `station` for a record with these Euler angles.
  char status_code(int station, ports::TimestampUs at, const std::array<float, 3>& euler) const;
  // Applies the wrong-baud model to one byte; false: lost (framing error).
  bool misclock_byte(std::byte& b);
  void generate(ports::TimestampUs now, bool stalled);
  std::size_t deliver(ports::TimestampUs now, std::span<std::byte> out);
  // Stations 1..4 that are enabled and plugged in, ascending.
  struct ActiveStations {
    std::array<int, 4> ids{};
    std::size_t count = 0;
    bool empty() const { return count == 0; }
    std::size_t size() const { return count; }
    int operator[](std::size_t i) const { return ids[i]; }
    const int* begin() const { return ids.data(); }
    const int* end() const { return ids.data() + count; }
  };
  ActiveStations active_stations() const;

  static constexpr ports::TimestampUs kNotYet = INT64_MAX / 4;  // the clock has not started

  FastrakDeviceConfig config_;
  Scenario scenario_;
  ports::TimestampUs start_us_;         // power-up: the 120 Hz cycle's origin
  ports::TimestampUs scenario_origin_;  // the scenario's t = 0 (kNotYet: not started)
  std::mt19937 rng_;
  UnitSettings settings_;
  ParameterCommands parameters_{settings_, *this, config_.model != DeviceModel::fastrak};
  CommandInput input_{config_.command_time_us, config_.input_buffer_bytes,
                      config_.model != DeviceModel::fastrak};
  FaultSchedule faults_{scenario_.faults, scenario_origin_};
  StationSolver solver_;
  PacedLine line_;
  Cycle cycle_;
  int host_baud_ = 0;
  ports::TimestampUs busy_until_ = 0;  // reset in progress until then (deaf and mute)
  FastrakDeviceCounters counters_{};
};

}  // namespace twister::sim
