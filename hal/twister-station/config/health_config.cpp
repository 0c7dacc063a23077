// [health]: metrics_file, period_s, archive_path, status.
#include "health_config.hpp"

namespace twister::station_app::internal {

void read_health(ConfigReader& root, StationFileConfig& cfg) {
  ConfigReader h = root.table("health", false);
  HealthSection& health = cfg.health;
  if (h.string("metrics_file", false, health.metrics_file) && health.metrics_file.empty()) {
    h.error(h.node("metrics_file"), "metrics_file",
            "expected a file path (e.g. /var/lib/prometheus/node-exporter/twister.prom), or "
            "leave the key out for no metrics file");
  }
  if (!health.metrics_file.empty() && !health.metrics_file.ends_with(".prom")) {
    h.error(h.node("metrics_file"), "metrics_file",
            "expected a name ending in .prom (node_exporter's textfile collector reads only "
            "*.prom), got \"" +
                health.metrics_file + "\"");
  }
  h.real("period_s", false, 1.0, 3600.0, health.period_s);
  h.string("archive_path", false, health.archive_path);
  h.boolean("status", health.status);
  h.finish();
}

}  // namespace twister::station_app::internal
