// twister-station: the composition root. Reads station.toml, assembles the
// backends, the journal, the model and the core once (the only place that
// allocates), then hands over to StationLoop (poll(2) on the backends' descriptors
// and a signalfd; Station::poll() each pass; SIGINT/SIGTERM/SIGHUP end it cleanly:
// an open stroke is cancelled, a final checkpoint, the journal synced, the summary;
// optional sd_notify READY / WATCHDOG / STOPPING).
// Logging goes through hal::Logger ("twister-station: ..."; sd-daemon priority
// prefixes when stderr is the journal): --log-level error|warning|notice|info|debug
// (default notice; -q = warning). The start and stop summary lines (mesh, running,
// mesh checksum, stopped) are the run's results and are always printed.
// Exit codes: 0 clean stop with every stroke saved, 1 runtime failure or a stroke not
// saved, 2 invalid config or options, or a missing file the config names (all checked
// before the journal is opened).
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "config/station_config.hpp"
#include "station_assembly.hpp"
#include "station_checks.hpp"
#include "station_health.hpp"
#include "station_loop.hpp"
#include "station_setup.hpp"
#include "twister/hal/logger.hpp"
#include "twister/hal/sodium_authenticator.hpp"
#include "twister/hal/startup_signals.hpp"

namespace {

namespace app = twister::station_app;
namespace hal = twister::hal;
using app::StationFileConfig;

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

int check_config(hal::Logger& log, const Options& opt, const StationFileConfig& cfg) {
  int errors = 0;
  const auto dir = std::filesystem::path(opt.config_path).parent_path();
  for (const std::string& problem : app::referenced_file_problems(cfg, dir)) {
    log.error("", "%s: %s", opt.config_path.c_str(), problem.c_str());
    ++errors;
  }
  if (!opt.link_address.empty()) {
    if (const std::string why = app::link_address_problem(opt.link_address); !why.empty()) {
      log.error("", "--link %s: %s", opt.link_address.c_str(), why.c_str());
      ++errors;
    }
  }
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
  if (!cfg.link.psk_file.empty()) {
    // The key file is checked like at start (private regular file of 64 hex digits).
    if (const auto key = hal::load_link_key(cfg.link.psk_file); !key) {
      log.error("", "%s: link.psk_file: %s", opt.config_path.c_str(), key.error().message.c_str());
      ++errors;
    }
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
                 "stopped (%s); journal %s (%u records); strokes committed %llu, cancelled %llu, "
                 "not saved %llu; tracker start-ups %llu, poses %llu, io errors %llu",
                 app::stop_reason_name(loop.stop_reason()), flushed.ok() ? "synced" : "SYNC FAILED",
                 core.journal_records(),
                 static_cast<unsigned long long>(c.events.strokes_committed),
                 static_cast<unsigned long long>(c.events.strokes_cancelled),
                 static_cast<unsigned long long>(c.events.strokes_not_saved),
                 static_cast<unsigned long long>(tc.streams_started),
                 static_cast<unsigned long long>(c.input.poses),
                 static_cast<unsigned long long>(tc.io_errors));
  // Poses the faults spoiled, none of which reached a hand (scripts parse this line).
  results.notice("", "poses: applied %llu, conversion errors %llu, rejected %llu, held back %llu",
                 static_cast<unsigned long long>(c.input.poses),
                 static_cast<unsigned long long>(c.input.pose_errors),
                 static_cast<unsigned long long>(tc.rejected_poses),
                 static_cast<unsigned long long>(tc.jump_rejects));
  if (c.events.strokes_not_saved > 0) {
    results.error("", "%llu stroke(s) were not saved (see the errors above); exit status 1",
                  static_cast<unsigned long long>(c.events.strokes_not_saved));
  }
}

void log_link_summary(hal::Logger& results, const app::DisplayLink& display) {
  const twister::station::StationLinkCounters* l = display.counters();
  if (l == nullptr) return;
  const std::uint64_t refused = l->refused.errors();
  results.notice(
      "link",
      "displays admitted %llu, hands sent %llu, dropped %llu; commits %llu, full "
      "meshes %llu; refused %llu",
      static_cast<unsigned long long>(l->connects), static_cast<unsigned long long>(l->live_sent),
      static_cast<unsigned long long>(l->live_dropped),
      static_cast<unsigned long long>(l->commits_sent),
      static_cast<unsigned long long>(l->full_sends), static_cast<unsigned long long>(refused));
}

int run(const Options& opt, const StationFileConfig& cfg, hal::Logger& log, hal::Logger& results,
        hal::StartupSignals& startup_signals) {
  const std::filesystem::path config_dir = std::filesystem::path(opt.config_path).parent_path();
  // [health] first: a metrics path that is not ours is refused before anything opens.
  auto health_config = app::make_health_config(cfg, config_dir.string());
  if (!health_config) {
    log.error("", "%s", health_config.error().message.c_str());
    return kExitFailure;
  }
  app::StationHealth health(std::move(*health_config));
  auto assembled = app::assemble_station(cfg, {config_dir, opt.link_address});
  if (!assembled) {
    log.error("", "%s", assembled.error().message.c_str());
    return kExitFailure;
  }
  if (const int sig = hal::startup_stop_signal(); sig != 0) {
    log.notice("", "stopped by signal %d during start-up", sig);
    return kExitFailure;
  }
  app::StationParts& parts = **assembled;
  for (const auto& note : parts.recovery_notes) {
    if (note.warning) {
      log.warning("journal", "%s", note.text.c_str());
    } else {
      log.notice("journal", "%s", note.text.c_str());
    }
  }
  const auto& mesh = parts.core->mesh();
  results.notice("", "mesh %s: %zu vertices, %zu triangles, checksum %016llx",
                 parts.mesh_path.c_str(), mesh.vertex_count(), mesh.triangle_count(),
                 static_cast<unsigned long long>(mesh.checksum()));
  if (const auto refine = parts.core->refinement(); refine.enabled) {
    log.notice("refine", "on: edges split above %g m, room for %zu more vertices",
               refine.threshold_m, refine.spare_vertices);
  }
  if (parts.display.is_open() && opt.link_wait_s > 0.0 &&
      !parts.display.wait_for_peer(*parts.core, opt.link_wait_s) &&
      hal::startup_stop_signal() == 0) {
    log.warning("", "no bridge on %s after %.1f s; running without", opt.link_address.c_str(),
                opt.link_wait_s);
  }
  // From here the loop's signalfd takes the stop signals (one that came during
  // start-up stops the first pass).
  startup_signals.end();
  app::StationLoop loop(*parts.core, parts.backends, parts.display, log,
                        app::make_loop_config(cfg, opt.duration_s, parts.backends));
  results.notice("", "running (tracker %s, model %s, buttons %s, journal %s)",
                 parts.backends.tracker_name.c_str(),
                 twister::tracker::tracker_model_name(parts.core->tracker_session().config().model),
                 parts.backends.buttons_name.c_str(), cfg.station.journal.c_str());
  loop.watch_journal(&parts.journal);
  loop.report_health(&health);
  const twister::Status flushed = loop.run();
  log_summary(results, *parts.core, loop, flushed);
  log_link_summary(results, parts.display);
  // A run that lost a stroke did not succeed, whatever else went well.
  const bool all_saved = parts.core->counters().events.strokes_not_saved == 0;
  return flushed.ok() && all_saved ? kExitOk : kExitFailure;
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
                 "serve the display link to twister-bridge on unix:PATH, tcp:HOST:PORT or "
                 "serial:DEVICE (overrides [link] address)");
  app.add_option("--link-wait", opt.link_wait_s,
                 "seconds to wait for a bridge to connect and receive the mesh before running")
      ->check(CLI::NonNegativeNumber);
  app.set_version_flag("--version", "twister-station 0.1.0");
}

int station_main(int argc, char** argv) {
  // A file size limit (RLIMIT_FSIZE) must fail the write (EFBIG: "stroke not saved"),
  // not kill the station with SIGXFSZ.
  std::signal(SIGXFSZ, SIG_IGN);
  // A stop signal during start-up ends it cleanly at its next step (the journal's
  // lock released), within a second whatever it waits on; after start-up the loop's
  // signalfd takes over (hal/startup_signals.hpp).
  hal::StartupSignals startup_signals;
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
  auto parsed = app::load_station_config(opt.config_path);
  for (const auto& e : parsed.errors) log.error("", "%s", e.to_string().c_str());
  if (!parsed.ok()) {
    log.error("", "%zu error(s) in %s; refusing to start", parsed.errors.size(),
              opt.config_path.c_str());
    return kExitBadConfig;
  }
  if (!opt.journal_override.empty()) parsed.config.station.journal = opt.journal_override;
  // Every option and file is checked before anything is opened or replayed.
  if (check_config(log, opt, parsed.config) > 0) {
    log.error("", "%s cannot run (see above); refusing to start", opt.config_path.c_str());
    return kExitBadConfig;
  }
  if (opt.check) {
    std::printf("%s: valid (tracker %s, buttons %s)\n", opt.config_path.c_str(),
                app::to_string(parsed.config.tracker.backend),
                app::to_string(parsed.config.buttons.backend));
    return kExitOk;
  }
  return run(opt, parsed.config, log, results, startup_signals);
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
