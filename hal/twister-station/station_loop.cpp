#include "station_loop.hpp"

#include <pthread.h>
#include <sys/signalfd.h>
#include <systemd/sd-daemon.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <span>

#include "station_log.hpp"

namespace twister::station_app {

StationLoopConfig make_loop_config(const StationFileConfig& config, double duration_s,
                                   const Backends& backends) {
  StationLoopConfig c;
  c.timeout_ms = static_cast<int>(config.station.loop_timeout_ms);
  c.stop_after_s = duration_s > 0.0 ? duration_s : backends.scenario_duration_s;
  c.button_retry_us = static_cast<ports::TimestampUs>(config.tracker.reconnect_interval_ms) * 1000;
  c.notify = config.systemd.notify;
  c.watchdog = config.systemd.watchdog;
  return c;
}

const char* stop_reason_name(StopReason reason) {
  switch (reason) {
    case StopReason::end_of_run:
      return "end of run";
    case StopReason::sigint:
      return "SIGINT";
    case StopReason::sigterm:
      return "SIGTERM";
    case StopReason::sighup:
      return "SIGHUP";
    case StopReason::station_failed:
      return "station failed";
  }
  return "unknown";
}

StationLoop::StationLoop(station::Station& core, Backends& backends, DisplayLink& display,
                         hal::Logger& log, const StationLoopConfig& config)
    : core_(core), backends_(backends), display_(display), log_(log), config_(config) {}

StationLoop::~StationLoop() {
  if (signal_fd_ >= 0) ::close(signal_fd_);
  if (mask_saved_) pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
}

hal::Expected<void> StationLoop::start() {
  sigset_t mask;
  sigemptyset(&mask);
  sigaddset(&mask, SIGINT);
  sigaddset(&mask, SIGTERM);
  sigaddset(&mask, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &mask, &old_mask_);
  mask_saved_ = true;
  signal_fd_ = signalfd(-1, &mask, SFD_NONBLOCK | SFD_CLOEXEC);
  if (signal_fd_ < 0) {
    return hal::make_error(StatusCode::io_error,
                           std::string("cannot create a signalfd: ") + std::strerror(errno));
  }
  std::uint64_t watchdog_usec = 0;
  watchdog_ = config_.watchdog && sd_watchdog_enabled(0, &watchdog_usec) > 0;
  watchdog_interval_us_ = static_cast<ports::TimestampUs>(watchdog_usec / 2);
  if (config_.notify) sd_notify(0, "READY=1\nSTATUS=running");
  start_us_ = backends_.clock->now_us();
  last_watchdog_us_ = start_us_;
  last_button_retry_us_ = start_us_;
  return {};
}

std::size_t StationLoop::fill_poll_set() {
  const std::span<pollfd> all(fds_);
  std::size_t n = 0;
  fds_[n++] = {signal_fd_, POLLIN, 0};
  n += backends_.tracker_poll->poll_fds(all.subspan(n));
  if (backends_.buttons->connected()) n += backends_.buttons_poll->poll_fds(all.subspan(n));
  n += display_.poll_fds(all.subspan(n));
  return n;
}

bool StationLoop::signalled() {
  if ((fds_[0].revents & POLLIN) == 0) return false;
  signalfd_siginfo info{};
  if (::read(signal_fd_, &info, sizeof info) != static_cast<ssize_t>(sizeof info)) return false;
  stop_reason_ = info.ssi_signo == SIGINT   ? StopReason::sigint
                 : info.ssi_signo == SIGHUP ? StopReason::sighup
                                            : StopReason::sigterm;
  return true;
}

bool StationLoop::step() {
  ++passes_;
  const std::size_t n = fill_poll_set();
  // Virtual time: never wait; the clock steps instead.
  ::poll(fds_.data(), n, backends_.virtual_clock != nullptr ? 0 : config_.timeout_ms);
  if (signalled()) return false;
  if (backends_.virtual_clock != nullptr)
    backends_.virtual_clock->advance_us(config_.virtual_step_us);
  const ports::TimestampUs now_us = backends_.clock->now_us();
  if (!core_.poll().ok()) {
    stop_reason_ = StopReason::station_failed;
    return false;
  }
  display_.poll(core_, now_us);  // the display's commands run at the next core_.poll()
  // Virtual time: the clock waits for the display (no update dropped for want of room).
  if (backends_.virtual_clock != nullptr) display_.settle(core_, now_us, 5.0);
  log_events();
  retry_buttons(now_us);
  pet_watchdog(now_us);
  if (health_ != nullptr) health_->poll(core_, backends_, display_, log_, now_us);
  if (time_is_up(now_us)) {
    stop_reason_ = StopReason::end_of_run;
    return false;
  }
  return true;
}

void StationLoop::log_events() {
  for (auto e = core_.next_event(); e.ok(); e = core_.next_event()) {
    if (e->kind == session::SessionEventKind::tracker_streaming) {
      log_tracker_search(&*e);
      continue;
    }
    log_station_event(*e, log_, journal_ != nullptr ? journal_->last_errno() : 0);
  }
  log_tracker_search(nullptr);
  log_tracker_report();
}

// A tracker backend that searches for its device (usb): its finding, once per change
// (at start, found, lost, waiting for firmware, another model).
void StationLoop::log_tracker_report() {
  const hal::DeviceReport* report = backends_.tracker_report;
  if (report == nullptr || report->changes() == tracker_report_seen_) return;
  tracker_report_seen_ = report->changes();
  switch (report->level()) {
    case hal::DeviceReport::Level::info:
      log_.notice("tracker", "%s", report->text());
      return;
    case hal::DeviceReport::Level::warning:
      log_.warning("tracker", "%s", report->text());
      return;
    case hal::DeviceReport::Level::error:
      log_.error("tracker", "%s", report->text());
      return;
  }
}

// Found: the streaming line names the model and where. Not found: once, when the
// first start-up failed, what was looked for where and why it failed (a backend with
// a DeviceReport says that itself: log_tracker_report).
void StationLoop::log_tracker_search(const session::SessionEvent* e) {
  const tracker::FastrakSession& session = core_.tracker_session();
  const char* model = tracker::tracker_model_name(session.config().model);
  const char* where = backends_.tracker_name.c_str();
  if (e != nullptr) {
    log_.notice("tracker", "streaming (start-up #%u): %s found on %s",
                e->tracker_streaming().start_ups, model, where);
    tracker_found_ = true;
    return;
  }
  const auto& c = session.counters();
  // A backend that reports its search (usb) has said already that it found nothing
  // usable; a unit found that never streams is still worth this line.
  const hal::DeviceReport* report = backends_.tracker_report;
  if (report != nullptr && report->level() != hal::DeviceReport::Level::info) return;
  if (tracker_found_ || tracker_missing_said_ || c.inits < 2) return;
  tracker_missing_said_ = true;
  log_.warning("tracker",
               "no %s found on %s yet (status timeouts %llu, io errors %llu, garbage %llu); "
               "still looking (is it on, at this baud, and tracker.model right?)",
               model, where, static_cast<unsigned long long>(c.status_timeouts),
               static_cast<unsigned long long>(c.io_errors),
               static_cast<unsigned long long>(c.garbage_faults));
}

// A missing or vanished button device is tried again every retry interval; the
// station's next poll sees it connected and says so (buttons_found). A device that
// is there but cannot be opened (a bad line offset, a busy line, permissions) fails
// every retry: one line when that starts or its reason changes, not one per retry.
void StationLoop::retry_buttons(ports::TimestampUs now_us) {
  if (backends_.buttons->connected() || now_us - last_button_retry_us_ < config_.button_retry_us)
    return;
  last_button_retry_us_ = now_us;
  const Status s = backends_.buttons_poll->reopen();
  if (!s.ok() && s.code() != StatusCode::unavailable && s.code() != last_retry_code_) {
    log_.warning("buttons",
                 "device there but cannot be opened (%s); still running without "
                 "buttons, retrying",
                 s.name());
  }
  last_retry_code_ = s.code();
}

void StationLoop::pet_watchdog(ports::TimestampUs now_us) {
  if (!watchdog_ || now_us - last_watchdog_us_ < watchdog_interval_us_) return;
  sd_notify(0, "WATCHDOG=1");
  last_watchdog_us_ = now_us;
}

bool StationLoop::time_is_up(ports::TimestampUs now_us) const {
  return config_.stop_after_s > 0.0 &&
         static_cast<double>(now_us - start_us_) / 1e6 >= config_.stop_after_s;
}

Status StationLoop::finish() {
  if (config_.notify) sd_notify(0, "STOPPING=1");
  core_.stop();
  log_events();
  display_.drain(core_, backends_.clock->now_us(), 2.0);
  const Status flushed = core_.flush();
  // The final counts (the file then stays as the run left it; its age tells a stop).
  if (health_ != nullptr && health_->enabled()) {
    health_->report(core_, backends_, display_, log_, backends_.clock->now_us());
  }
  return flushed;
}

Status StationLoop::run() {
  if (auto started = start(); !started) {
    log_.error("", "%s", started.error().message.c_str());
    return StatusCode::io_error;
  }
  while (step()) {
  }
  return finish();
}

}  // namespace twister::station_app
