// twister-station: the composition root. Reads station.toml, assembles the
// backends, the journal, the model and the core once (the only place that
// allocates), then hands over to StationLoop (poll(2) on the backends' descriptors
// and a signalfd; Station::poll() each pass; SIGINT/SIGTERM end it cleanly with the
// journal synced; optional sd_notify READY / WATCHDOG / STOPPING).
// Logging goes through hal::Logger ("twister-station: ..."; sd-daemon priority
// prefixes when stderr is the journal): --log-level error|warning|notice|info|debug
// (default notice; -q = warning). The start and stop summary lines (mesh, running,
// mesh checksum, stopped) are the run's results and are always printed.
// Exit codes: 0 clean stop, 1 runtime failure, 2 invalid config or options.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "config/station_config.hpp"
#include "station_assembly.hpp"
#include "station_loop.hpp"
#include "station_setup.hpp"
#include "twister/hal/logger.hpp"

namespace {

namespace app = twister::station_app;
namespace hal = twister::hal;
using app::StationConfig;

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadConfig = 2;
constexpr const char* kProgram = "twister-station";

struct Options {
  std::string config_path;
  bool check = false;
  std::string journal_override;
  double duration_s = 0.0;  // 0 = until signalled (or the scenario ends)
  bool quiet = false;
  std::string log_level;     // empty: notice (warning with --quiet)
  std::string link_address;  // --link: serve twister-bridge (unix:PATH | tcp:HOST:PORT)
  double link_wait_s = 0.0;  // --link-wait: wait for a bridge before running
};

// The process log at the requested level, and a logger for the run's result lines
// that shows them whatever the level (same program name and prefixes).
hal::Logger& configure_logs(const Options& opt, hal::Logger& results) {
  hal::LogLevel level = opt.quiet ? hal::LogLevel::warning : hal::LogLevel::notice;
  if (!opt.log_level.empty()) hal::parse_log_level(opt.log_level, level);
  const bool journal = hal::stderr_is_journal();
  hal::Logger& log = hal::process_log();
  log.configure({kProgram, level, journal, 2});
  results.configure({kProgram, hal::LogLevel::debug, journal, 2});
  return log;
}

int check_config(hal::Logger& log, const Options& opt, const StationConfig& cfg) {
  int errors = 0;
  if (const auto setup = app::make_station_setup(cfg); !setup) {
    log.error("", "%s: %s", opt.config_path.c_str(), setup.error().message.c_str());
    ++errors;
  }
  if (!app::tracker_backend_built(cfg.tracker.backend)) {
    log.error("", "%s: tracker.backend: \"%s\" is not built into this binary",
              opt.config_path.c_str(), app::to_string(cfg.tracker.backend));
    ++errors;
  }
  if (!app::button_backend_built(cfg.buttons.backend)) {
    log.error("", "%s: buttons.backend: \"%s\" is not built into this binary",
              opt.config_path.c_str(), app::to_string(cfg.buttons.backend));
    ++errors;
  }
  return errors;
}

void log_summary(hal::Logger& results, const twister::station::Station& core,
                 const app::StationLoop& loop, twister::Status flushed) {
  results.notice("", "mesh checksum %016llx",
                 static_cast<unsigned long long>(core.mesh().checksum()));
  const auto& c = core.counters();
  const auto& tc = core.tracker_session().counters();
  results.notice("",
                 "stopped (%s); journal %s (%u records); strokes committed %llu, cancelled %llu; "
                 "tracker start-ups %llu, poses %llu, io errors %llu",
                 app::stop_reason_name(loop.stop_reason()), flushed.ok() ? "synced" : "SYNC FAILED",
                 core.journal_records(), static_cast<unsigned long long>(c.strokes_committed),
                 static_cast<unsigned long long>(c.strokes_cancelled),
                 static_cast<unsigned long long>(tc.streams_started),
                 static_cast<unsigned long long>(c.poses),
                 static_cast<unsigned long long>(tc.io_errors));
}

int run(const Options& opt, StationConfig cfg, hal::Logger& log, hal::Logger& results) {
  if (!opt.journal_override.empty()) cfg.station.journal = opt.journal_override;
  auto assembled = app::assemble_station(
      cfg, {std::filesystem::path(opt.config_path).parent_path(), opt.link_address});
  if (!assembled) {
    log.error("", "%s", assembled.error().message.c_str());
    return kExitFailure;
  }
  app::StationParts& parts = **assembled;
  const auto& mesh = parts.core->mesh();
  results.notice("", "mesh %s: %zu vertices, %zu triangles, checksum %016llx",
                 parts.mesh_path.c_str(), mesh.vertex_count(), mesh.triangle_count(),
                 static_cast<unsigned long long>(mesh.checksum()));
  if (const auto refine = parts.core->refinement(); refine.enabled) {
    log.notice("refine", "on: edges split above %g m, room for %zu more vertices",
               refine.threshold_m, refine.spare_vertices);
  }
  if (parts.display.is_open() && opt.link_wait_s > 0.0 &&
      !parts.display.wait_for_peer(parts.core->sculpt(), opt.link_wait_s)) {
    log.warning("", "no bridge on %s after %.1f s; running without", opt.link_address.c_str(),
                opt.link_wait_s);
  }
  app::StationLoop loop(*parts.core, parts.backends, parts.display, log,
                        app::make_loop_config(cfg, opt.duration_s, parts.backends));
  results.notice("", "running (tracker %s, buttons %s, journal %s)",
                 parts.backends.tracker_name.c_str(), parts.backends.buttons_name.c_str(),
                 cfg.station.journal.c_str());
  const twister::Status flushed = loop.run();
  log_summary(results, *parts.core, loop, flushed);
  return flushed.ok() ? kExitOk : kExitFailure;
}

void add_options(CLI::App& app, Options& opt) {
  app.add_option("-c,--config", opt.config_path, "station.toml to use")->required();
  app.add_flag("--check", opt.check,
               "validate the config and exit (0 valid, 2 invalid); touches no hardware");
  app.add_option("--journal", opt.journal_override, "override station.journal");
  app.add_option("--duration", opt.duration_s,
                 "stop after this many seconds (default: run until SIGINT/SIGTERM, or the "
                 "simulator scenario ends)")
      ->check(CLI::NonNegativeNumber);
  auto* level =
      app.add_option("--log-level", opt.log_level,
                     "error|warning|notice|info|debug (default notice; info shows every stroke)")
          ->check(CLI::IsMember({"error", "warning", "notice", "info", "debug"}));
  app.add_flag("-q,--quiet", opt.quiet,
               "log warnings and errors only (= --log-level warning), plus the start and stop "
               "summary")
      ->excludes(level);
  app.add_option("--link", opt.link_address,
                 "serve the display link to twister-bridge on unix:PATH or tcp:HOST:PORT");
  app.add_option("--link-wait", opt.link_wait_s,
                 "seconds to wait for a bridge to connect and receive the mesh before running")
      ->check(CLI::NonNegativeNumber);
  app.set_version_flag("--version", "twister-station 0.1.0");
}

int station_main(int argc, char** argv) {
  CLI::App cli{
      "twister-station: the Twister sculpting station (tracker + buttons -> strokes -> journal)"};
  Options opt;
  add_options(cli, opt);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = cli.exit(e);
    return rc == 0 ? kExitOk : kExitBadConfig;
  }
  hal::Logger results({kProgram});
  hal::Logger& log = configure_logs(opt, results);
  const auto parsed = app::load_station_config(opt.config_path);
  for (const auto& e : parsed.errors) log.error("", "%s", e.to_string().c_str());
  if (!parsed.ok()) {
    log.error("", "%zu error(s) in %s; refusing to start", parsed.errors.size(),
              opt.config_path.c_str());
    return kExitBadConfig;
  }
  if (check_config(log, opt, parsed.config) > 0) {
    log.error("", "%s cannot run with this binary; refusing to start", opt.config_path.c_str());
    return kExitBadConfig;
  }
  if (opt.check) {
    std::printf("%s: valid (tracker %s, buttons %s)\n", opt.config_path.c_str(),
                app::to_string(parsed.config.tracker.backend),
                app::to_string(parsed.config.buttons.backend));
    return kExitOk;
  }
  return run(opt, parsed.config, log, results);
}

}  // namespace

int main(int argc, char** argv) {
  // Init-time code (config, loaders, std containers) may throw; nothing may escape.
  try {
    return station_main(argc, argv);
  } catch (const std::exception& e) {
    hal::process_log().error("", "fatal: %s", e.what());
  } catch (...) {
    hal::process_log().error("", "fatal: unknown exception");
  }
  return kExitFailure;
}
