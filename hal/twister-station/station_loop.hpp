// StationLoop: twister-station's event loop, the program's steady state. One pass:
//   wait in poll(2) on a fixed set of descriptors (a signalfd for SIGINT/SIGTERM/SIGHUP,
//   then each backend's PollSource: tracker, buttons while connected, display
//   link) for at most loop_timeout_ms, or not at all in virtual time, where the
//   simulator's clock steps 1 ms per pass instead;
//   Station::poll(); the display link; the station's events to the log; a reopen
//   of missing or vanished buttons every reconnect interval (the station runs on
//   without them; a device there that cannot be opened is logged once); the systemd
//   watchdog.
// It stops on SIGINT, SIGTERM or SIGHUP (all three end the run the same way:
// Station::stop()'s policy for an open stroke, then the summary), after the run's
// length (--duration, else the simulator scenario's), or when the core fails. No pass allocates:
// the poll set is a std::array, events are logged through hal::Logger (no heap), and every backend,
// the core and the link work in memory sized before the loop.
// One thread; start() blocks SIGINT/SIGTERM/SIGHUP in it (the destructor restores
// the mask).
#pragma once

#include <poll.h>
#include <signal.h>

#include <array>
#include <cstddef>
#include <cstdint>

#include "backend_factory.hpp"
#include "display_link.hpp"
#include "station_health.hpp"
#include "twister/hal/expected.hpp"
#include "twister/hal/logger.hpp"
#include "twister/hal/posix_file_storage.hpp"
#include "twister/station/station.hpp"

namespace twister::station_app {

struct StationLoopConfig {
  int timeout_ms = 10;                             // real time: longest wait per pass
  ports::TimestampUs virtual_step_us = 1000;       // virtual time: clock step per pass
  double stop_after_s = 0.0;                       // 0: until a signal
  ports::TimestampUs button_retry_us = 1'000'000;  // between reopen attempts
  bool notify = false;                             // sd_notify READY / STOPPING
  bool watchdog = false;                           // sd_notify WATCHDOG=1 when systemd asks for it
};

// The loop's settings from the config: `duration_s` (--duration) wins over the
// simulator scenario's length; 0 for both runs until signalled.
StationLoopConfig make_loop_config(const StationFileConfig& config, double duration_s,
                                   const Backends& backends);

enum class StopReason : std::uint8_t { end_of_run, sigint, sigterm, sighup, station_failed };
const char* stop_reason_name(StopReason reason);

class StationLoop {
 public:
  // Signal fd + the most descriptors of tracker, buttons and link.
  static constexpr std::size_t kMaxPollFds = 1 + 3 * hal::PollSource::kMaxFds;

  // Everything must outlive the loop; `core` has been started.
  StationLoop(station::Station& core, Backends& backends, DisplayLink& display, hal::Logger& log,
              const StationLoopConfig& config);
  ~StationLoop();
  StationLoop(const StationLoop&) = delete;
  StationLoop& operator=(const StationLoop&) = delete;

  // Routes SIGINT/SIGTERM/SIGHUP to a signalfd, tells systemd READY=1 and starts the
  // clock of the run. io_error: no signalfd.
  hal::Expected<void> start();
  // One pass. false once the loop stops (stop_reason() says why).
  bool step();
  // Ends the run: STOPPING=1, Station::stop() (an open stroke is cancelled), the
  // display link drained (until 2 s pass without progress), the journal flushed; returns the flush
  // status.
  Status finish();
  // start(), step() until the loop stops, finish(). The flush status, or the
  // start() error as io_error.
  Status run();

  // The journal file whose errno names the reason of a stroke that was not saved.
  void watch_journal(const hal::PosixFileStorage* journal) { journal_ = journal; }
  // Reports the station's health every pass it is due ([health]); nullptr: none.
  void report_health(StationHealth* health) { health_ = health; }

  StopReason stop_reason() const { return stop_reason_; }
  std::uint64_t passes() const { return passes_; }

 private:
  std::size_t fill_poll_set();
  bool signalled();
  void log_events();
  // The tracker model configured, where it was found, or that it is not found yet.
  void log_tracker_search(const session::SessionEvent* e);
  void log_tracker_report();
  void retry_buttons(ports::TimestampUs now_us);
  void pet_watchdog(ports::TimestampUs now_us);
  bool time_is_up(ports::TimestampUs now_us) const;

  station::Station& core_;
  Backends& backends_;
  DisplayLink& display_;
  hal::Logger& log_;
  const hal::PosixFileStorage* journal_ = nullptr;
  StationHealth* health_ = nullptr;
  StationLoopConfig config_;
  std::array<pollfd, kMaxPollFds> fds_{};
  int signal_fd_ = -1;
  sigset_t old_mask_{};
  bool mask_saved_ = false;
  bool watchdog_ = false;  // systemd asked for pings (and the config allows them)
  ports::TimestampUs watchdog_interval_us_ = 0;
  ports::TimestampUs start_us_ = 0;
  ports::TimestampUs last_watchdog_us_ = 0;
  ports::TimestampUs last_button_retry_us_ = 0;
  StatusCode last_retry_code_ = StatusCode::unavailable;  // of the last button reopen
  std::uint64_t passes_ = 0;
  bool tracker_found_ = false;             // the tracker has streamed since start
  bool tracker_missing_said_ = false;      // "not found yet" was logged
  std::uint32_t tracker_report_seen_ = 0;  // DeviceReport::changes() last logged
  StopReason stop_reason_ = StopReason::end_of_run;
};

}  // namespace twister::station_app
