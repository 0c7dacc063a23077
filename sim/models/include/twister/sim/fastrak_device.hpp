// FastrakDevice: a model of a Polhemus FASTRAK as seen from its serial port (spec
// shared/spec/fastrak-protocol.md). It answers the command set a host uses (§2),
// streams records at 120 Hz shared by the active stations (§1 cycle), in ASCII or
// binary via the core encoder, limited to baud/10 bytes per second (whole solutions
// are dropped when the line is busy), models the stylus e-mode toggle (pitfall 4)
// and the slow ^Y reset, and injects the scenario's faults. Time is passed in by the
// caller (microseconds, any epoch fixed at construction), so it runs in virtual or
// real time. Steady state (record generation, the line, advance) uses no heap: the
// line is a fixed LineQueue; command handling (start-up) may allocate.
// Not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "twister/ports/clock.hpp"
#include "twister/sim/line_queue.hpp"
#include "twister/sim/scenario.hpp"
#include "twister/tracker/fastrak_event.hpp"
#include "twister/tracker/fastrak_wire.hpp"

namespace twister::sim {

struct FastrakDeviceConfig {
  int baud = 115200;                     // line rate; 10 bits per byte
  std::int64_t reset_time_us = 500'000;  // ^Y and power-up (a real unit: 10-20 s)
  bool start_continuous = false;         // power-up mode (the real default is polled)
  tracker::Format start_format = tracker::Format::ascii;
};

struct FastrakDeviceCounters {
  std::uint64_t records = 0;              // records queued for transmission
  std::uint64_t dropped_solutions = 0;    // cycles skipped because the line was busy
  std::uint64_t commands = 0;             // commands executed
  std::uint64_t command_errors = 0;       // error records sent
  std::uint64_t resets = 0;               // ^Y and power-ups
  std::uint64_t bytes_out = 0;            // bytes handed to the line
  std::uint64_t line_overflow = 0;        // bytes lost because the line queue was full
  std::array<std::uint64_t, 6> faults{};  // injected, indexed by FaultKind
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

  const FastrakDeviceCounters& counters() const { return counters_; }
  bool continuous() const { return continuous_; }
  const tracker::FastrakConfig& protocol() const { return proto_; }
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
  void queue(std::span<const std::byte> bytes, ports::TimestampUs now);
  void queue(std::string_view text, ports::TimestampUs now);
  void queue_noise(std::uint64_t count, ports::TimestampUs now);
  void queue_record(int station, ports::TimestampUs at);
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
  ports::TimestampUs busy_until_ = 0;  // reset in progress until then
  std::int64_t next_cycle_ = 0;
  std::size_t next_station_ = 0;

  // Command input.
  std::string pending_cmd_;
  bool in_param_cmd_ = false;

  // Line: chunks that finish transmitting at their ready time.
  LineQueue line_;
  ports::TimestampUs line_free_at_ = 0;

  // Faults.
  std::size_t next_fault_ = 0;
  std::uint64_t drop_left_ = 0;
  std::uint64_t truncate_left_ = 0;
  struct Window {
    FaultKind kind;
    ports::TimestampUs from, to;
  };
  std::vector<Window> windows_;  // reserved for every scenario fault: no growth later
  bool was_hung_up_ = false;
  FastrakDeviceCounters counters_{};
};

}  // namespace twister::sim
