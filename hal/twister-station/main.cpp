// twister-station: the composition root. Reads station.toml, builds the backends,
// initialises the core once (the only place that allocates), then runs the event
// loop: poll(2) on the tracker, the buttons and a signalfd; Station::poll() each
// wake-up. SIGINT/SIGTERM end the loop cleanly with the journal synced. Optional
// sd_notify READY / WATCHDOG / STOPPING (no effect without systemd).
// Exit codes: 0 clean stop, 1 runtime failure, 2 invalid config or options.
#include <poll.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <systemd/sd-daemon.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "backend_factory.hpp"
#include "config/station_config.hpp"
#include "display_link.hpp"
#include "station_log.hpp"
#include "station_setup.hpp"
#include "twister/hal/logger.hpp"
#include "twister/hal/posix_file_storage.hpp"
#include "twister/meshio/obj_file.hpp"
#include "twister/station/station.hpp"

namespace {

using twister::station_app::StationConfig;
namespace station = twister::station;

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadConfig = 2;

struct Options {
  std::string config_path;
  bool check = false;
  std::string journal_override;
  double duration_s = 0.0;  // 0 = until signalled (or the scenario ends)
  bool quiet = false;
  std::string link_address;  // --link: serve twister-bridge (unix:PATH | tcp:HOST:PORT)
  double link_wait_s = 0.0;  // --link-wait: wait for a bridge before running
};

void log_event(const station::StationEvent& e) {
  using K = station::StationEventKind;
  const double t = static_cast<double>(e.time_us) / 1e6;
  switch (e.kind) {
    case K::journal_recovered:
      std::fprintf(
          stderr, "[%9.3f] journal: %u good records%s\n", t, e.sequence,
          e.value ? (", cut a torn tail of " + std::to_string(e.value) + " bytes").c_str() : "");
      break;
    case K::tracker_streaming:
      std::fprintf(stderr, "[%9.3f] tracker: streaming (start-up #%llu)\n", t,
                   static_cast<unsigned long long>(e.value));
      break;
    case K::tracker_lost:
      std::fprintf(
          stderr,
          "[%9.3f] tracker: lost (unplugged, silent or garbled); waiting and re-initialising\n", t);
      break;
    case K::stroke_begin:
      std::fprintf(stderr, "[%9.3f] stroke: hand %u grabbed\n", t, e.hand);
      break;
    case K::stroke_committed:
      std::fprintf(stderr, "[%9.3f] stroke: hand %u committed as journal record %u\n", t, e.hand,
                   e.sequence);
      break;
    case K::stroke_cancelled:
      std::fprintf(stderr,
                   "[%9.3f] stroke: hand %u cancelled (tracking lost too long); model unchanged\n",
                   t, e.hand);
      break;
    case K::refused:
      std::fprintf(stderr, "[%9.3f] press refused: hand %u (%s)\n", t, e.hand,
                   twister::input::reason_name(static_cast<twister::input::Reason>(e.value)));
      break;
    case K::journal_error:
      std::fprintf(stderr, "[%9.3f] journal: append failed (%s); stroke not recorded\n", t,
                   e.status.name());
      break;
    case K::button_source_error:
      std::fprintf(stderr, "[%9.3f] buttons: device failed (%s); reopening\n", t, e.status.name());
      break;
    default:  // the sculptor's actions besides strokes (radius, clutch, undo, ...)
      twister::station_app::log_station_event(e, twister::hal::process_log());
      break;
  }
}

int check_config(const Options& opt, const StationConfig& cfg) {
  const auto setup = twister::station_app::make_station_setup(cfg);
  int errors = 0;
  if (!setup.ok()) {
    std::fprintf(stderr, "%s: %s\n", opt.config_path.c_str(), setup.error.c_str());
    ++errors;
  }
  if (!twister::station_app::tracker_backend_built(cfg.tracker.backend)) {
    std::fprintf(stderr, "%s: tracker.backend: \"%s\" is not built into this binary\n",
                 opt.config_path.c_str(), twister::station_app::to_string(cfg.tracker.backend));
    ++errors;
  }
  if (!twister::station_app::button_backend_built(cfg.buttons.backend)) {
    std::fprintf(stderr, "%s: buttons.backend: \"%s\" is not built into this binary\n",
                 opt.config_path.c_str(), twister::station_app::to_string(cfg.buttons.backend));
    ++errors;
  }
  return errors;
}

int run(const Options& opt, StationConfig cfg) {
  if (!opt.journal_override.empty()) cfg.station.journal = opt.journal_override;
  const auto setup = twister::station_app::make_station_setup(cfg);
  twister::station_app::Backends backends;
  std::string error;
  if (!twister::station_app::make_backends(cfg, backends, error)) {
    std::fprintf(stderr, "twister-station: %s\n", error.c_str());
    return kExitFailure;
  }
  twister::hal::PosixFileStorage storage;
  if (const auto s = storage.open({.path = cfg.station.journal}); !s.ok()) {
    std::fprintf(stderr, "twister-station: cannot open journal %s (%s, errno %d)\n",
                 cfg.station.journal.c_str(), s.name(), storage.last_errno());
    return kExitFailure;
  }
  // The initial model; a relative path is relative to the config file.
  std::filesystem::path mesh_path(cfg.station.mesh);
  if (mesh_path.is_relative())
    mesh_path = std::filesystem::path(opt.config_path).parent_path() / mesh_path;
  twister::meshio::ObjLoad model = twister::meshio::load_obj(mesh_path, cfg.station.spare_vertices);
  if (!model.status.ok()) {
    std::fprintf(stderr, "twister-station: mesh %s: %s\n", mesh_path.c_str(),
                 model.message.c_str());
    return kExitFailure;
  }
  // All working memory is sized here, once; the loop never allocates.
  twister::mesh::Mesh& mesh = model.buffer->mesh();
  const std::size_t n = mesh.vertex_capacity();
  std::vector<float> live_x(n), live_y(n), live_z(n), weights1(n), weights2(n);
  std::vector<std::uint32_t> plan_indices(n);
  std::vector<twister::input::VertexChange> undo_changes(twister::input::kDefaultUndoChanges);
  std::vector<twister::input::UndoEntry> undo_entries(twister::input::kDefaultUndoEntries);
  const twister::input::SculptStorage work{
      live_x,       live_y,
      live_z,       twister::math::WarpPlanStorage{plan_indices, weights1, weights2},
      undo_changes, undo_entries};
  auto core = std::make_unique<station::Station>(*backends.tracker, *backends.buttons,
                                                 *backends.clock, storage, mesh, work, setup.core);
  if (const auto s = core->start(); !s.ok()) {
    const char* why = s.name();
    if (s.code() == twister::StatusCode::data_loss) {
      why = "is not a Twister journal, or does not fit this mesh (left untouched)";
    }
    std::fprintf(stderr, "twister-station: journal %s: %s\n", cfg.station.journal.c_str(), why);
    return kExitFailure;
  }
  std::fprintf(stderr, "twister-station: mesh %s: %zu vertices, %zu triangles, checksum %016llx\n",
               mesh_path.c_str(), mesh.vertex_count(), mesh.triangle_count(),
               static_cast<unsigned long long>(mesh.checksum()));

  twister::station_app::DisplayLink display;
  if (!opt.link_address.empty()) {
    if (const std::string e = display.open(opt.link_address, core->sculpt()); !e.empty()) {
      std::fprintf(stderr, "twister-station: %s\n", e.c_str());
      return kExitFailure;
    }
    if (opt.link_wait_s > 0.0 && !display.wait_for_peer(core->sculpt(), opt.link_wait_s)) {
      std::fprintf(stderr, "twister-station: no bridge on %s after %.1f s; running without\n",
                   opt.link_address.c_str(), opt.link_wait_s);
    }
  }

  sigset_t mask;
  sigemptyset(&mask);
  sigaddset(&mask, SIGINT);
  sigaddset(&mask, SIGTERM);
  sigprocmask(SIG_BLOCK, &mask, nullptr);
  const int sig_fd = signalfd(-1, &mask, SFD_NONBLOCK | SFD_CLOEXEC);

  std::uint64_t watchdog_usec = 0;
  const bool watchdog = cfg.systemd.watchdog && sd_watchdog_enabled(0, &watchdog_usec) > 0;
  if (cfg.systemd.notify) sd_notify(0, "READY=1\nSTATUS=running");
  std::fprintf(stderr, "twister-station: running (tracker %s, buttons %s, journal %s)\n",
               backends.tracker_name.c_str(), backends.buttons_name.c_str(),
               cfg.station.journal.c_str());

  auto& clock = *backends.clock;
  const auto start_us = clock.now_us();
  auto last_watchdog_us = start_us;
  double stop_after_s = opt.duration_s;
  if (stop_after_s <= 0.0 && backends.scenario_duration_s > 0.0)
    stop_after_s = backends.scenario_duration_s;
  auto last_button_retry_us = start_us;
  bool buttons_broken = false;
  std::vector<pollfd> fds;
  fds.reserve(16);
  const char* stop_reason = "end of run";
  for (;;) {
    fds.clear();
    fds.push_back({sig_fd, POLLIN, 0});
    if (backends.tracker_fd) {
      if (const int fd = backends.tracker_fd(); fd >= 0) fds.push_back({fd, POLLIN, 0});
    }
    if (backends.button_fds && !buttons_broken) {
      for (const int fd : backends.button_fds()) fds.push_back({fd, POLLIN, 0});
    }
    if (const int fd = display.poll_fd(); fd >= 0) fds.push_back({fd, POLLIN, 0});
    // Virtual time: never wait, advance 1 ms per iteration instead.
    const int timeout_ms =
        backends.virtual_clock ? 0 : static_cast<int>(cfg.station.loop_timeout_ms);
    ::poll(fds.data(), fds.size(), timeout_ms);
    if (fds[0].revents & POLLIN) {
      signalfd_siginfo info{};
      if (::read(sig_fd, &info, sizeof info) == static_cast<ssize_t>(sizeof info)) {
        stop_reason = info.ssi_signo == SIGINT ? "SIGINT" : "SIGTERM";
        break;
      }
    }
    if (backends.virtual_clock) backends.virtual_clock->advance_us(1000);
    const auto now_us = clock.now_us();
    if (!core->poll().ok()) break;
    display.poll(core->sculpt(), now_us);
    for (auto e = core->next_event(); e.ok(); e = core->next_event()) {
      if (e->kind == station::StationEventKind::button_source_error) buttons_broken = true;
      if (!opt.quiet) log_event(*e);
    }
    if (buttons_broken && backends.reopen_buttons &&
        now_us - last_button_retry_us >=
            static_cast<std::int64_t>(cfg.tracker.reconnect_interval_ms) * 1000) {
      last_button_retry_us = now_us;
      if (backends.reopen_buttons()) {
        buttons_broken = false;
        std::fprintf(stderr, "twister-station: buttons reopened\n");
      }
    }
    if (watchdog && now_us - last_watchdog_us >= static_cast<std::int64_t>(watchdog_usec / 2)) {
      sd_notify(0, "WATCHDOG=1");
      last_watchdog_us = now_us;
    }
    if (stop_after_s > 0.0 && static_cast<double>(now_us - start_us) / 1e6 >= stop_after_s) break;
  }
  if (cfg.systemd.notify) sd_notify(0, "STOPPING=1");
  display.drain(core->sculpt(), clock.now_us(), 2.0);
  const auto flushed = core->flush();
  std::fprintf(stderr, "twister-station: mesh checksum %016llx\n",
               static_cast<unsigned long long>(core->mesh().checksum()));
  const auto& c = core->counters();
  const auto& tc = core->tracker_session().counters();
  std::fprintf(stderr,
               "twister-station: stopped (%s); journal %s (%u records); strokes committed %llu, "
               "cancelled %llu; tracker start-ups %llu, poses %llu, io errors %llu\n",
               stop_reason, flushed.ok() ? "synced" : "SYNC FAILED", core->journal_records(),
               static_cast<unsigned long long>(c.strokes_committed),
               static_cast<unsigned long long>(c.strokes_cancelled),
               static_cast<unsigned long long>(tc.streams_started),
               static_cast<unsigned long long>(c.poses),
               static_cast<unsigned long long>(tc.io_errors));
  if (sig_fd >= 0) ::close(sig_fd);
  return flushed.ok() ? kExitOk : kExitFailure;
}

int station_main(int argc, char** argv) {
  CLI::App app{
      "twister-station: the Twister sculpting station (tracker + buttons -> strokes -> journal)"};
  Options opt;
  twister::hal::process_log().configure(
      {"twister-station", twister::hal::LogLevel::notice, twister::hal::stderr_is_journal(), 2});
  app.add_option("-c,--config", opt.config_path, "station.toml to use")->required();
  app.add_flag("--check", opt.check,
               "validate the config and exit (0 valid, 2 invalid); touches no hardware");
  app.add_option("--journal", opt.journal_override, "override station.journal");
  app.add_option("--duration", opt.duration_s,
                 "stop after this many seconds (default: run until SIGINT/SIGTERM, or the "
                 "simulator scenario ends)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("-q,--quiet", opt.quiet, "log only start and stop");
  app.add_option("--link", opt.link_address,
                 "serve the display link to twister-bridge on unix:PATH or tcp:HOST:PORT");
  app.add_option("--link-wait", opt.link_wait_s,
                 "seconds to wait for a bridge to connect and receive the mesh before running")
      ->check(CLI::NonNegativeNumber);
  app.set_version_flag("--version", "twister-station 0.1.0");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? kExitOk : kExitBadConfig;
  }
  const auto parsed = twister::station_app::load_station_config(opt.config_path);
  for (const auto& e : parsed.errors) std::fprintf(stderr, "%s\n", e.to_string().c_str());
  if (!parsed.ok()) {
    std::fprintf(stderr, "twister-station: %zu error(s) in %s; refusing to start\n",
                 parsed.errors.size(), opt.config_path.c_str());
    return kExitBadConfig;
  }
  if (check_config(opt, parsed.config) > 0) {
    std::fprintf(stderr, "twister-station: %s cannot run with this binary; refusing to start\n",
                 opt.config_path.c_str());
    return kExitBadConfig;
  }
  if (opt.check) {
    std::printf("%s: valid (tracker %s, buttons %s)\n", opt.config_path.c_str(),
                twister::station_app::to_string(parsed.config.tracker.backend),
                twister::station_app::to_string(parsed.config.buttons.backend));
    return kExitOk;
  }
  return run(opt, parsed.config);
}

}  // namespace

int main(int argc, char** argv) {
  // Init-time code (config, loaders, std containers) may throw; nothing may escape.
  try {
    return station_main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "twister-station: fatal: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "twister-station: fatal: unknown exception\n");
  }
  return kExitFailure;
}
