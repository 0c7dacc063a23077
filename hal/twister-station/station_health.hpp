// StationHealth: what the station's loop reports to whoever looks after the kiosks
// (issue 25): every [health] period_s it samples the station (tracker state and
// rate, strokes committed and not saved, the display link, the button device, the
// archive's free space, uptime) into a hal::HealthMetrics, writes the metrics file
// (hal::MetricsFile: Prometheus text, atomic replace) and sends systemd STATUS=.
// visitors_today comes from the visitor lifecycle, spectators from the display
// link's read-only displays connected now. No allocation after construction:
// the loop calls poll() every pass. A failed write is logged once per change of
// reason (the station sculpts on).
#pragma once

#include <array>
#include <memory>
#include <string>

#include "backend_factory.hpp"
#include "display_link.hpp"
#include "twister/hal/health_metrics.hpp"
#include "twister/hal/logger.hpp"
#include "twister/station/station.hpp"

namespace twister::station_app {

struct StationHealthConfig {
  std::unique_ptr<hal::MetricsFile> file;  // none: no metrics file
  ports::TimestampUs period_us = 15'000'000;
  std::string archive_path;  // statvfs target for archive_free_bytes
  bool status = false;       // sd_notify STATUS=
};

class StationHealth {
 public:
  explicit StationHealth(StationHealthConfig config) : config_(std::move(config)) {}

  // Samples and reports when a period has passed since the last report (the first
  // call reports at once).
  void poll(const station::Station& core, const Backends& backends, const DisplayLink& display,
            hal::Logger& log, ports::TimestampUs now_us);
  // Samples and reports now (the loop's end: the final counts).
  void report(const station::Station& core, const Backends& backends, const DisplayLink& display,
              hal::Logger& log, ports::TimestampUs now_us);

  hal::HealthMetrics& metrics() { return metrics_; }
  const hal::HealthMetrics& metrics() const { return metrics_; }
  std::uint64_t reports() const { return reports_; }
  bool enabled() const { return config_.file != nullptr || config_.status; }

 private:
  void sample(const station::Station& core, const Backends& backends, const DisplayLink& display,
              ports::TimestampUs now_us);

  StationHealthConfig config_;
  hal::HealthMetrics metrics_{};
  bool started_ = false;
  ports::TimestampUs start_us_ = 0;
  ports::TimestampUs last_us_ = 0;
  std::uint64_t reports_ = 0;
  Status last_write_{};  // of the last failed write, logged once per change
  std::array<char, 256> status_line_{};
};

// The [health] section as a StationHealthConfig: opens the metrics file (relative
// paths against `config_dir`; refused when a file there is not ours) and takes the
// archive path (default: the journal's folder). Errors name the key.
hal::Expected<StationHealthConfig> make_health_config(const StationFileConfig& config,
                                                      const std::string& config_dir);

}  // namespace twister::station_app
