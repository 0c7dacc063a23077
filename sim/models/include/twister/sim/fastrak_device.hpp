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
#pragma once

#include <array>
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
#include "twister/sim/line_queue.hpp"
#include "twister/sim/scenario.hpp"
#include "twister/tracker/fastrak_event.hpp"
#include "twister/tracker/fastrak_wire.hpp"

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

struct FastrakDeviceConfig {
  int baud = 115200;                     // line rate; 10 bits per byte (`o` changes it)
  std::int64_t reset_time_us = 500'000;  // ^Y and power-up (a real unit: 10-20 s)
  bool start_continuous = false;         // power-up mode (the real default is polled)
  tracker::Format start_format = tracker::Format::ascii;
  // The unit's binary format, chosen by `f`: IEEE floats (Fastrak), or the 16-bit
  // packed format of an Isotrak II / 3SPACE-style unit.
  bool packed16 = false;
  CommandTimes command_time_us = default_command_times();
  FilterParams start_position_filter = kFilterOff;  // power-up filters
  FilterParams start_attitude_filter = kFilterOff;
  // At a baud mismatch a byte survives as one junk byte with this probability; the
  // rest are framing errors the receiving UART drops (IGNPAR). Assumed.
  double misclock_junk = 1.0 / 16.0;
};

struct FastrakDeviceCounters {
  std::uint64_t records = 0;            // records queued for transmission
  std::uint64_t dropped_solutions = 0;  // cycles skipped because the line was busy
  std::uint64_t commands = 0;           // commands executed
  std::uint64_t command_errors = 0;     // error records sent
  std::uint64_t resets = 0;             // ^Y and power-ups
  std::uint64_t bytes_out = 0;          // bytes handed to the line
  std::uint64_t line_overflow = 0;      // bytes lost because the line queue was full
  std::uint64_t input_lost = 0;         // bytes received while a command was processed
  std::uint64_t corrupted_records = 0;  // records with a corrupted field (fault corrupt)
  std::uint64_t dropped_bytes = 0;      // output bytes eaten by a `drop` fault
  std::uint64_t drop_expired = 0;       // drop budget discarded (stream stopped, reset)
  std::uint64_t misclock_lost = 0;      // bytes (either way) lost to a baud mismatch
  std::uint64_t misclock_junk = 0;      // junk bytes (either way) from a baud mismatch
  std::uint64_t status_letters = 0;     // records sent with a status letter
  std::array<std::uint64_t, kFaultKindCount> faults{};  // injected, indexed by FaultKind
};

class FastrakDevice {
 public:
  FastrakDevice(const FastrakDeviceConfig& config, Scenario scenario, ports::TimestampUs start_us);

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
  bool continuous() const { return continuous_; }
  int baud() const { return baud_; }
  const tracker::FastrakConfig& protocol() const { return proto_; }
  const FilterParams& position_filter() const { return filter_params_[0]; }
  const FilterParams& attitude_filter() const { return filter_params_[1]; }
  // Scenario time in seconds at `now`.
  double scenario_time_s(ports::TimestampUs now) const;

 private:
  void power_up(ports::TimestampUs now);
  void apply_faults(ports::TimestampUs now);
  void execute(char command, const std::string& args, ports::TimestampUs now);
  // The commands without arguments (mode letters, status, resets); false when
  // `command` is not one of them.
  bool execute_mode(char command, ports::TimestampUs now);
  void send_status(ports::TimestampUs now);
  // The parameter commands, `fields` split at commas; `echo` is the command as
  // received, for the error record.
  void execute_output_list(int station, const std::vector<std::string>& fields,
                           const std::string& echo, ports::TimestampUs now);
  void execute_station_state(int station, const std::vector<std::string>& fields,
                             const std::string& echo, ports::TimestampUs now);
  void execute_hemisphere(int station, const std::vector<std::string>& fields,
                          const std::string& echo, ports::TimestampUs now);
  // `x` / `v` (no station): set, macro or read back the filter; `Q` envelope; `o` port.
  void execute_filter(char command, const std::vector<std::string>& fields, const std::string& echo,
                      ports::TimestampUs now);
  void execute_envelope(int station, const std::vector<std::string>& fields,
                        const std::string& echo, ports::TimestampUs now);
  void execute_serial_port(const std::vector<std::string>& fields, const std::string& echo,
                           ports::TimestampUs now);
  // The command's processing time; the unit is deaf until it has passed.
  std::int64_t command_time(char command) const;
  // One command byte outside a parameter command.
  void receive_command_byte(char c, ports::TimestampUs now);
  void queue(std::span<const std::byte> bytes, ports::TimestampUs now);
  void queue(std::string_view text, ports::TimestampUs now);
  void queue_noise(std::uint64_t count, ports::TimestampUs now);
  void queue_record(int station, ports::TimestampUs at);
  // The unit's solution for `station` at `at`: the scenario sample in the station's
  // hemisphere, through the filters (updates the filter state).
  void solve(int station, ports::TimestampUs at);
  // The header status byte of `station` for a record with these Euler angles.
  char status_code(int station, ports::TimestampUs at, const std::array<float, 3>& euler) const;
  // Applies the wrong-baud model to one byte; false: lost (framing error).
  bool misclock_byte(std::byte& b);
  void generate(ports::TimestampUs now, bool stalled);
  std::size_t deliver(ports::TimestampUs now, std::span<std::byte> out);
  void send_error(const std::string& input, int code, ports::TimestampUs now);
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
  bool in_window(ports::TimestampUs now, FaultKind kind) const;

  FastrakDeviceConfig config_;
  Scenario scenario_;
  ports::TimestampUs start_us_;
  std::mt19937 rng_;

  // Unit state.
  tracker::FastrakConfig proto_;
  bool continuous_ = false;
  bool output_on_ = true;  // stylus point/track toggle in continuous mode
  int e_mode_ = 1;
  bool last_button_ = false;
  std::array<std::array<double, 3>, 4> hemisphere_{};
  // `Q` angular envelope per station: az max, el max, roll max, az min, el min, roll min.
  std::array<std::array<double, 6>, 4> envelope_{};
  std::array<FilterParams, 2> filter_params_{};  // position (`x`), attitude (`v`)
  struct Solution {
    bool valid = false;
    glm::dvec3 position_in{0.0};
    glm::dquat attitude{1.0, 0.0, 0.0, 0.0};
    bool button = false;
  };
  std::array<Solution, 4> solution_{};
  std::array<std::array<AdaptiveFilter, 2>, 4> filter_{};  // [station][position, attitude]
  int baud_ = 115200;
  int host_baud_ = 0;
  ports::TimestampUs busy_until_ = 0;  // reset in progress until then (deaf and mute)
  ports::TimestampUs deaf_until_ = 0;  // a command is processed until then
  std::int64_t next_cycle_ = 0;
  std::size_t next_station_ = 0;    // next station to send (continuous mode)
  std::size_t polled_station_ = 0;  // next station to solve while nothing is sent

  // Command input.
  std::string pending_cmd_;
  bool in_param_cmd_ = false;

  // Line: chunks that finish transmitting at their ready time.
  LineQueue line_;
  ports::TimestampUs line_free_at_ = 0;

  // Faults.
  std::size_t next_fault_ = 0;
  std::uint64_t drop_left_ = 0;
  ports::TimestampUs drop_until_ = 0;  // the drop budget expires then
  std::uint64_t truncate_left_ = 0;
  std::uint64_t corrupt_left_ = 0;
  struct Window {
    FaultKind kind;
    ports::TimestampUs from, to;
  };
  std::vector<Window> windows_;  // reserved for every scenario fault: no growth later
  bool was_hung_up_ = false;
  FastrakDeviceCounters counters_{};
};

}  // namespace twister::sim
