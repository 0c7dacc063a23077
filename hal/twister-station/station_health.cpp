#include "station_health.hpp"

#include <systemd/sd-daemon.h>

#include <filesystem>

namespace twister::station_app {
namespace {

hal::TrackerHealth tracker_health(station::TrackerLinkState s) {
  switch (s) {
    case station::TrackerLinkState::starting:
      return hal::TrackerHealth::starting;
    case station::TrackerLinkState::streaming:
      return hal::TrackerHealth::streaming;
    case station::TrackerLinkState::lost:
      return hal::TrackerHealth::lost;
  }
  return hal::TrackerHealth::starting;
}

}  // namespace

void StationHealth::sample(const station::Station& core, const Backends& backends,
                           const DisplayLink& display, ports::TimestampUs now_us) {
  const station::StationStatus status = core.status();
  hal::HealthMetrics& m = metrics_;
  m.tracker = tracker_health(status.tracker);
  m.tracker_rate_hz = static_cast<double>(status.tracker_rate_hz);
  m.strokes_committed = core.counters().events.strokes_committed;
  m.strokes_not_saved = core.counters().events.strokes_not_saved;
  m.link_open = display.is_open();
  m.display_connected = display.connected();
  m.buttons_present = backends.buttons != nullptr && backends.buttons->connected();
  m.archive_free_bytes =
      config_.archive_path.empty() ? -1 : hal::free_bytes_at(config_.archive_path.c_str());
  m.uptime_s = static_cast<double>(now_us - start_us_) / 1e6;
  // Exhibit mode: today's sculptures that ended and were archived (the current
  // visitor's counts once it is archived).
  if (core.visitor_view_enabled()) m.visitors_today = core.exhibit_counters().ended_today;
  // Read-only displays connected now (issue 25).
  const station::StationLinkCounters* link = display.counters();
  m.spectators = link != nullptr ? link->spectators_now : 0;
}

void StationHealth::report(const station::Station& core, const Backends& backends,
                           const DisplayLink& display, hal::Logger& log,
                           ports::TimestampUs now_us) {
  if (!started_) {
    started_ = true;
    start_us_ = now_us;
  }
  last_us_ = now_us;
  sample(core, backends, display, now_us);
  ++reports_;
  if (config_.file != nullptr) {
    const Status s = config_.file->write(metrics_);
    if (!s.ok() && s.code() != last_write_.code()) {
      log.warning("health", "cannot write the metrics file %s (%s): %s; sculpting goes on",
                  config_.file->path().c_str(), s.name(), config_.file->last_error());
    } else if (s.ok() && !last_write_.ok()) {
      log.notice("health", "metrics file %s written again", config_.file->path().c_str());
    }
    last_write_ = s;
  }
  if (config_.status && hal::format_systemd_status(metrics_, status_line_) > 0) {
    sd_notify(0, status_line_.data());
  }
}

void StationHealth::poll(const station::Station& core, const Backends& backends,
                         const DisplayLink& display, hal::Logger& log, ports::TimestampUs now_us) {
  if (!enabled()) return;
  if (started_ && now_us - last_us_ < config_.period_us) return;
  report(core, backends, display, log, now_us);
}

hal::Expected<StationHealthConfig> make_health_config(const StationFileConfig& config,
                                                      const std::string& config_dir) {
  namespace fs = std::filesystem;
  StationHealthConfig h;
  h.period_us = static_cast<ports::TimestampUs>(config.health.period_s * 1e6);
  h.status = config.health.status && config.systemd.notify;
  fs::path archive = config.health.archive_path;
  if (archive.empty()) archive = fs::path(config.station.journal).parent_path();
  if (archive.empty()) archive = ".";
  if (archive.is_relative() && !config.health.archive_path.empty()) archive = config_dir / archive;
  h.archive_path = archive.string();
  if (!config.health.metrics_file.empty()) {
    fs::path path = config.health.metrics_file;
    if (path.is_relative()) path = config_dir / path;
    auto file = hal::MetricsFile::open(path.string());
    if (!file) {
      return hal::Error{file.error().status, "health.metrics_file: " + file.error().message};
    }
    h.file = std::move(*file);
  }
  return h;
}

}  // namespace twister::station_app
