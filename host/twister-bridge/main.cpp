// twister-bridge: the display side of the station. Connects to twister-station's
// link (unix:PATH or tcp:HOST:PORT; reconnects after loss and resyncs by mesh
// version), keeps the scene replica and shows it: a GLFW window, kiosk full
// screen, or offscreen (EGL surfaceless, no display server) writing PNG snapshots.
// Logs through hal::Logger ("twister-bridge: [error: ]component: message", sd-daemon
// prefixes under systemd); --log-level picks the threshold (-q = warning). Picture
// paths go to stdout: they are the program's output, not log lines.
// Exit codes: 0 ok, 1 failure (no context, timeout before the awaited commits,
// export failed), 2 bad options.
#include <poll.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "bridge_app.hpp"
#include "gl_context.hpp"
#include "mesh_export.hpp"
#include "twister/hal/expected.hpp"
#include "twister/hal/logger.hpp"
#include "twister/hal/socket_link.hpp"

namespace {

using twister::StatusCode;
using twister::bridge::BridgeApp;
using twister::hal::Expected;
using twister::hal::LogLevel;

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadOptions = 2;

struct Options {
  std::string connect;
  bool offscreen = false;
  bool kiosk = false;
  std::string size = "800x600";
  std::string snapshots;
  std::string export_path;
  unsigned exit_after_commits = 0;
  double timeout_s = 0.0;
  twister::bridge::ViewConfig view;  // --azimuth, --elevation
  bool exit_on_disconnect = false;
  std::string log_level = "notice";
  bool quiet = false;
};

twister::hal::Logger& logger() { return twister::hal::process_log(); }

struct Size {
  int width = 0;
  int height = 0;
};

Expected<Size> parse_size(const std::string& text) {
  Size s;
  if (std::sscanf(text.c_str(), "%dx%d", &s.width, &s.height) != 2 || s.width < 16 ||
      s.height < 16 || s.width > 8192 || s.height > 8192) {
    return twister::hal::make_error(StatusCode::invalid_argument,
                                    "--size must be WxH (16..8192), got " + text);
  }
  return s;
}

// The GL context and the renderer drawing into it (destroyed before the context).
struct Display {
  std::unique_ptr<twister::bridge::GlContext> context;
  twister::bridge::MeshRenderer renderer;
};

Expected<void> open_display(const Options& opt, Size size, Display& display) {
  auto context = opt.offscreen
                     ? twister::bridge::make_offscreen_context(size.width, size.height)
                     : twister::bridge::make_window_context(size.width, size.height, opt.kiosk);
  if (!context) return context.error();
  display.context = std::move(*context);
  return display.renderer.init(display.context->width(), display.context->height(), opt.offscreen,
                               opt.view);
}

// Steps the app until the window closes, the awaited commits or disconnect came, or
// the timeout; returns the exit code.
int run_loop(const Options& opt, BridgeApp& app, Display& display, const int link_fd) {
  const auto start = std::chrono::steady_clock::now();
  twister::bridge::GlContext& context = *display.context;
  for (;;) {
    app.step();
    if (!context.offscreen()) {
      context.poll_events();
      if (!context.open()) return kExitOk;
      display.renderer.resize(context.width(), context.height());
      app.draw();
      context.swap();
    } else {
      pollfd p{link_fd, POLLIN, 0};
      ::poll(&p, p.fd >= 0 ? 1 : 0, p.fd >= 0 ? 5 : 20);
    }
    const std::uint64_t commits = app.replica().counters().commits;
    if (opt.exit_on_disconnect && app.counters().disconnects > 0 && app.replica().has_mesh()) {
      return kExitOk;
    }
    if (opt.exit_after_commits > 0 && commits >= opt.exit_after_commits) return kExitOk;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (opt.timeout_s > 0.0 && elapsed > opt.timeout_s) {
      // A timeout is the planned end of a run unless commits were awaited.
      const bool failed = opt.exit_after_commits > 0;
      logger().write(failed ? LogLevel::error : LogLevel::notice, "run",
                     "timeout after %.1f s (%llu commits seen)", {elapsed, commits});
      return failed ? kExitFailure : kExitOk;
    }
  }
}

int export_final_mesh(const std::string& path, const BridgeApp& app) {
  if (!app.replica().has_mesh()) {
    logger().error("export", "no mesh received; nothing exported");
    return kExitFailure;
  }
  if (const Expected<void> done = twister::bridge::export_mesh(path, app.replica().mesh()); !done) {
    logger().error("export", "%s", done.error().message.c_str());
    return kExitFailure;
  }
  // No component: scripts read this line ("twister-bridge: exported mesh version N
  // (checksum X)"; host/twister-bridge/demo.sh).
  logger().notice("", "exported mesh version %u (checksum %016llx) to %s", app.replica().version(),
                  app.replica().checksum(), path.c_str());
  return kExitOk;
}

void log_summary(const BridgeApp& app) {
  const auto& c = app.replica().counters();
  const auto& d = app.decoder_counters();
  logger().notice("summary",
                  "mesh version %u; full meshes %llu, commits %llu, checksum mismatches %llu, "
                  "resend requests %llu, live frames %llu, connects %llu, bad frames %llu",
                  app.replica().version(), c.full_meshes, c.commits, c.checksum_mismatches,
                  c.resend_requests, c.live_frames, app.counters().connects,
                  d.bad_crc + d.bad_cobs + d.bad_payload);
}

int run(const Options& opt) {
  const Expected<Size> size = parse_size(opt.size);
  if (!size) {
    logger().error("options", "%s", size.error().message.c_str());
    return kExitBadOptions;
  }
  if (!opt.snapshots.empty()) std::filesystem::create_directories(opt.snapshots);
  Display display;
  if (const Expected<void> opened = open_display(opt, *size, display); !opened) {
    logger().error("display", "%s", opened.error().message.c_str());
    return kExitFailure;
  }
  twister::hal::SocketLink link({opt.connect, false, 200});
  if (!link.open().ok()) {
    logger().error("options", "bad link address %s (unix:PATH | tcp:HOST:PORT)",
                   opt.connect.c_str());
    return kExitBadOptions;
  }
  BridgeApp app(link, &display.renderer, {opt.snapshots}, logger());
  int rc = run_loop(opt, app, display, link.poll_fd());
  if (!opt.export_path.empty()) {
    if (const int exported = export_final_mesh(opt.export_path, app); exported != kExitOk) {
      return exported;
    }
  }
  log_summary(app);
  for (const std::string& p : app.pictures()) std::printf("%s\n", p.c_str());
  return rc;
}

void add_options(CLI::App& cli, Options& opt) {
  cli.add_option("--connect", opt.connect, "station link: unix:PATH or tcp:HOST:PORT")->required();
  cli.add_flag("--offscreen", opt.offscreen,
               "no window: EGL surfaceless rendering (PNG snapshots)");
  cli.add_flag("--kiosk", opt.kiosk, "full screen on the primary monitor");
  cli.add_option("--size", opt.size, "WxH in pixels (window or offscreen)");
  cli.add_option("--snapshots", opt.snapshots,
                 "directory for PNGs: rest.png, live-<version>.png, commit-<version>.png");
  cli.add_option("--export", opt.export_path, "write the final mesh (.obj or .ply) at exit");
  cli.add_option("--exit-after-commits", opt.exit_after_commits,
                 "exit once this many commits were applied and verified");
  cli.add_flag("--exit-on-disconnect", opt.exit_on_disconnect,
               "exit when the station closes the link (after a mesh was received)");
  cli.add_option("--timeout", opt.timeout_s, "give up after this many seconds (0 = never)")
      ->check(CLI::NonNegativeNumber);
  cli.add_option("--azimuth", opt.view.azimuth_deg, "camera azimuth in degrees");
  cli.add_option("--elevation", opt.view.elevation_deg, "camera elevation in degrees");
  cli.add_option("--log-level", opt.log_level,
                 "error | warning | notice (default) | info (each picture) | debug")
      ->check(CLI::IsMember({"error", "warning", "notice", "info", "debug"}));
  cli.add_flag("-q,--quiet", opt.quiet, "same as --log-level warning (which wins if given)");
}

}  // namespace

int main(int argc, char** argv) try {
  logger().configure({"twister-bridge", LogLevel::notice, twister::hal::stderr_is_journal(), 2});
  CLI::App cli{"twister-bridge: scene replica and display of a twister-station"};
  Options opt;
  add_options(cli, opt);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = cli.exit(e);
    return rc == 0 ? kExitOk : kExitBadOptions;
  }
  LogLevel level = LogLevel::notice;
  (void)twister::hal::parse_log_level(opt.log_level, level);  // checked by CLI11
  if (opt.quiet && cli.count("--log-level") == 0) level = LogLevel::warning;
  logger().set_threshold(level);
  try {
    return run(opt);
  } catch (const std::exception& e) {
    logger().error("", "%s", e.what());
    return kExitFailure;
  }
} catch (...) {
  logger().error("", "unexpected error");
  return kExitFailure;
}
