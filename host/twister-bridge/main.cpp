// twister-bridge: the display side of the station. Connects to twister-station's
// link (unix:PATH or tcp:HOST:PORT; reconnects after loss and resyncs by mesh
// version), keeps the scene replica and shows it: a GLFW window, kiosk full
// screen, or offscreen (EGL surfaceless, no display server) writing PNG snapshots.
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
#include "twister/hal/socket_link.hpp"

namespace {

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
  bool quiet = false;
};

int run(const Options& opt) {
  int width = 800;
  int height = 600;
  if (std::sscanf(opt.size.c_str(), "%dx%d", &width, &height) != 2 || width < 16 || height < 16 ||
      width > 8192 || height > 8192) {
    std::fprintf(stderr, "twister-bridge: --size must be WxH (16..8192), got %s\n",
                 opt.size.c_str());
    return 2;
  }
  if (!opt.snapshots.empty()) std::filesystem::create_directories(opt.snapshots);
  std::string error;
  std::unique_ptr<twister::bridge::GlContext> context =
      opt.offscreen ? twister::bridge::make_offscreen_context(width, height, error)
                    : twister::bridge::make_window_context(width, height, opt.kiosk, error);
  if (!context) {
    std::fprintf(stderr, "twister-bridge: %s\n", error.c_str());
    return 1;
  }
  twister::bridge::MeshRenderer renderer;
  if (const std::string e =
          renderer.init(context->width(), context->height(), opt.offscreen, opt.view);
      !e.empty()) {
    std::fprintf(stderr, "twister-bridge: %s\n", e.c_str());
    return 1;
  }
  twister::hal::SocketLink link({opt.connect, false, 200});
  if (!link.open().ok()) {
    std::fprintf(stderr, "twister-bridge: bad link address %s (unix:PATH | tcp:HOST:PORT)\n",
                 opt.connect.c_str());
    return 2;
  }
  twister::bridge::BridgeApp app(link, &renderer, {opt.snapshots, !opt.quiet});
  const auto start = std::chrono::steady_clock::now();
  int rc = 0;
  for (;;) {
    app.step();
    if (!context->offscreen()) {
      context->poll_events();
      if (!context->open()) break;
      renderer.resize(context->width(), context->height());
      app.draw();
      context->swap();
    } else {
      pollfd p{link.poll_fd(), POLLIN, 0};
      ::poll(&p, p.fd >= 0 ? 1 : 0, p.fd >= 0 ? 5 : 20);
    }
    if (opt.exit_on_disconnect && app.counters().disconnects > 0 && app.replica().has_mesh()) {
      break;
    }
    if (opt.exit_after_commits > 0 && app.replica().counters().commits >= opt.exit_after_commits) {
      break;
    }
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (opt.timeout_s > 0.0 && elapsed > opt.timeout_s) {
      std::fprintf(stderr, "twister-bridge: timeout after %.1f s (%llu commits seen)\n", elapsed,
                   static_cast<unsigned long long>(app.replica().counters().commits));
      rc = opt.exit_after_commits > 0 ? 1 : 0;
      break;
    }
  }
  if (!opt.export_path.empty()) {
    if (!app.replica().has_mesh()) {
      std::fprintf(stderr, "twister-bridge: no mesh received; nothing exported\n");
      return 1;
    }
    std::string message;
    if (!twister::bridge::export_mesh(opt.export_path, app.replica().mesh(), message)) {
      std::fprintf(stderr, "twister-bridge: export: %s\n", message.c_str());
      return 1;
    }
    std::fprintf(stderr, "twister-bridge: exported mesh version %u (checksum %016llx) to %s\n",
                 app.replica().version(), static_cast<unsigned long long>(app.replica().checksum()),
                 opt.export_path.c_str());
  }
  const auto& c = app.replica().counters();
  const std::uint64_t bad_frames = app.decoder_counters().bad_crc +
                                   app.decoder_counters().bad_cobs +
                                   app.decoder_counters().bad_payload;
  std::fprintf(stderr,
               "twister-bridge: mesh version %u; full meshes %llu, commits %llu, checksum "
               "mismatches %llu, resend requests %llu, live frames %llu, connects %llu, bad "
               "frames %llu\n",
               app.replica().version(), static_cast<unsigned long long>(c.full_meshes),
               static_cast<unsigned long long>(c.commits),
               static_cast<unsigned long long>(c.checksum_mismatches),
               static_cast<unsigned long long>(c.resend_requests),
               static_cast<unsigned long long>(c.live_frames),
               static_cast<unsigned long long>(app.counters().connects),
               static_cast<unsigned long long>(bad_frames));
  for (const std::string& p : app.pictures()) std::printf("%s\n", p.c_str());
  return rc;
}

}  // namespace

int main(int argc, char** argv) try {
  CLI::App cli{"twister-bridge: scene replica and display of a twister-station"};
  Options opt;
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
  cli.add_flag("-q,--quiet", opt.quiet, "log only errors and the summary");
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = cli.exit(e);
    return rc == 0 ? 0 : 2;
  }
  try {
    return run(opt);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "twister-bridge: %s\n", e.what());
    return 1;
  }
} catch (...) {
  std::fprintf(stderr, "twister-bridge: unexpected error\n");
  return 1;
}
