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
#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "attract_showcase.hpp"
#include "bridge_app.hpp"
#include "camera_config.hpp"
#include "gl_context.hpp"
#include "mesh_export.hpp"
#include "scene_view.hpp"
#include "twister/hal/expected.hpp"
#include "twister/hal/logger.hpp"
#include "twister/hal/monotonic_clock.hpp"
#include "twister/hal/serial_link.hpp"
#include "twister/hal/socket_link.hpp"
#include "twister/hal/sodium_authenticator.hpp"
#include "window_input.hpp"

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
  bool force = false;  // --force: --export may replace a file of the same kind
  unsigned exit_after_commits = 0;
  double timeout_s = 0.0;
  twister::bridge::ViewConfig view;  // --azimuth, --elevation, or --camera FILE
  std::string camera_file;           // a kiosk's fixed camera (TOML)
  bool fixed_camera = false;
  bool exit_on_disconnect = false;
  std::string log_level = "notice";
  bool quiet = false;
  int baud = 230400;                      // serial: links
  std::string link_key;                   // pre-shared key file (the station's psk_file)
  twister::bridge::ReplicaLimits limits;  // --max-vertices / --max-triangles
  bool no_cues = false;                   // the model alone (no glyphs, spheres, axes, ...)
  bool no_hud = false;
  float crease_angle_deg = twister::bridge::kDefaultCreaseAngleDeg;  // --crease-angle
  bool no_live_refine = false;    // the live stroke unrefined even on OpenGL 4
  std::uint32_t movie_every = 0;  // --movie-every N: frame-<n>.png every N-th hands update
  std::string frame;              // --frame model|workspace|auto ("": auto unless a free camera)
  std::string hud;         // --hud visitor|operator ("": visitor in kiosk mode, else operator)
  bool spectator = false;  // --spectator: a read-only display
  // --attract-archive / --attract-models / --attract-seconds (or the kiosk file's
  // [attract]): attract mode's turntable of recent sculptures.
  twister::bridge::AttractConfig attract;
  bool attract_models_given = false;  // on the command line (it wins over the file)
  bool attract_seconds_given = false;
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
  explicit Display(twister::ports::Clock& clock) : view(renderer, clock) {}
  std::unique_ptr<twister::bridge::GlContext> context;
  twister::bridge::MeshRenderer renderer;
  twister::bridge::SceneView view;
};

Expected<void> open_display(const Options& opt, Size size, Display& display) {
  auto context = opt.offscreen
                     ? twister::bridge::make_offscreen_context(size.width, size.height)
                     : twister::bridge::make_window_context(size.width, size.height, opt.kiosk);
  if (!context) return context.error();
  display.context = std::move(*context);
  if (Expected<void> ready = display.renderer.init(
          display.context->width(), display.context->height(), opt.offscreen, opt.view);
      !ready) {
    return ready;
  }
  if (opt.no_cues)
    display.view.options().cues = twister::bridge::CueOptions{false, false, false, false, false};
  display.view.options().hud = !opt.no_hud;
  display.view.options().offscreen = opt.offscreen;
  const bool visitor = opt.hud == "visitor" || (opt.hud.empty() && opt.kiosk);
  display.view.options().audience =
      visitor ? twister::bridge::Audience::visitor : twister::bridge::Audience::operator_hud;
  return display.view.init();
}

// Steps the app until the window closes, the awaited commits or disconnect came, or
// the timeout; returns the exit code.
int run_loop(const Options& opt, BridgeApp& app, Display& display, const int link_fd,
             twister::ports::Clock& clock) {
  const twister::ports::TimestampUs start_us = clock.now_us();
  twister::bridge::GlContext& context = *display.context;
  for (;;) {
    app.step();
    if (context.offscreen() && app.stopped() != twister::bridge::BridgeStop::none) {
      return kExitFailure;  // refused: nothing more will come
    }
    if (context.offscreen() && app.yielding()) {
      return kExitOk;  // a snapshot run another display took over: its pictures are done
    }
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
    const double elapsed = 1e-6 * static_cast<double>(clock.now_us() - start_us);
    if (opt.timeout_s > 0.0 && elapsed > opt.timeout_s) {
      // A timeout is the planned end of a run unless commits were awaited.
      const bool failed = opt.exit_after_commits > 0;
      logger().write(failed ? LogLevel::error : LogLevel::notice, "run",
                     "timeout after %.1f s (%llu commits seen)", {elapsed, commits});
      return failed ? kExitFailure : kExitOk;
    }
  }
}

// The link transport: a socket client (unix:, tcp:) or a tty (serial:).
struct Transport {
  std::unique_ptr<twister::hal::SocketLink> socket;
  std::unique_ptr<twister::hal::SerialLink> serial;
  twister::ports::LinkPort* port = nullptr;
  int poll_fd() const {
    if (socket) return socket->poll_fd();
    std::array<pollfd, 1> fds{};
    return serial && serial->poll_fds(fds) == 1 ? fds[0].fd : -1;
  }
};

Expected<void> open_transport(const Options& opt, Transport& t) {
  if (opt.connect.rfind("serial:", 0) == 0) {
    twister::hal::SerialLinkConfig config;
    config.path = opt.connect.substr(7);
    config.baud = opt.baud;
    t.serial = std::make_unique<twister::hal::SerialLink>(config);
    t.port = t.serial.get();
    Expected<void> opened = t.serial->open();
    // Not there yet: retried on use, like a socket's reconnect.
    if (!opened && opened.error().status.code() != StatusCode::unavailable) return opened;
    return {};
  }
  t.socket = std::make_unique<twister::hal::SocketLink>(
      twister::hal::SocketLinkConfig{opt.connect, false, 200});
  t.port = t.socket.get();
  if (!t.socket->open()) {
    return twister::hal::make_error(
        StatusCode::invalid_argument,
        "bad link address " + opt.connect + " (unix:PATH | tcp:HOST:PORT | serial:DEVICE)");
  }
  return {};
}

int export_final_mesh(const std::string& path, bool force, const BridgeApp& app) {
  if (!app.replica().has_mesh()) {
    logger().error("export", "no mesh received; nothing exported");
    return kExitFailure;
  }
  // Upright from the station's up (its work frame's +Z when calibrated).
  const glm::vec3 up = app.replica().has_workspace() ? app.replica().workspace().up
                                                     : twister::bridge::kTransmitterUp;
  if (const Expected<void> done = twister::bridge::export_mesh(path, app.replica().mesh(),
                                                               app.replica().shading(), force, up);
      !done) {
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
                  "resend requests %llu, live frames %llu (missed %llu, busiest second %llu), "
                  "connects %llu, bad frames %llu",
                  app.replica().version(), c.full_meshes, c.commits, c.checksum_mismatches,
                  c.resend_requests, c.live_frames, c.live_missed,
                  app.counters().hands_busiest_second, app.counters().connects,
                  d.bad_crc + d.bad_cobs + d.bad_payload);
}

// The --camera file's view and attract settings into `options` (the command line
// wins over the file); false after logging why it cannot be read.
bool with_camera_file(Options& options) {
  if (options.camera_file.empty()) return true;
  const Expected<twister::bridge::CameraConfig> camera =
      twister::bridge::load_camera_config(options.camera_file);
  if (!camera) {
    logger().error("options", "--camera: %s", camera.error().message.c_str());
    return false;
  }
  options.view = camera->view;
  options.fixed_camera = camera->fixed;
  if (options.attract.archive.empty()) options.attract.archive = camera->attract.archive;
  if (!options.attract_models_given) options.attract.models = camera->attract.models;
  if (!options.attract_seconds_given) options.attract.seconds = camera->attract.seconds;
  return true;
}

// The pre-shared key's authenticator when --link-key is given; false after logging why not.
bool load_authenticator(const Options& opt,
                        std::unique_ptr<twister::hal::SodiumAuthenticator>& auth) {
  if (opt.link_key.empty()) return true;
  auto key = twister::hal::SodiumAuthenticator::init()
                 ? twister::hal::load_link_key(opt.link_key)
                 : Expected<twister::hal::LinkKey>(
                       twister::hal::make_error(StatusCode::io_error, "libsodium failed to start"));
  if (!key) {
    logger().error("options", "%s", key.error().message.c_str());
    return false;
  }
  auth = std::make_unique<twister::hal::SodiumAuthenticator>(*key);
  return true;
}

int run(const Options& opt) {
  const Expected<Size> size = parse_size(opt.size);
  if (!size) {
    logger().error("options", "%s", size.error().message.c_str());
    return kExitBadOptions;
  }
  // The export path is checked now, not after the session's work.
  if (!opt.export_path.empty()) {
    if (const Expected<void> ok = twister::bridge::check_export_path(opt.export_path, opt.force);
        !ok) {
      logger().error("options", "--export: %s", ok.error().message.c_str());
      return kExitBadOptions;
    }
  }
  if (!opt.snapshots.empty()) std::filesystem::create_directories(opt.snapshots);
  Options options = opt;
  if (!with_camera_file(options)) return kExitBadOptions;
  // The one clock of the display: link timing, frame times, the HUD, the timeout.
  twister::hal::MonotonicClock clock;
  Display display(clock);
  if (const Expected<void> opened = open_display(options, *size, display); !opened) {
    logger().error("display", "%s", opened.error().message.c_str());
    return kExitFailure;
  }
  Transport transport;
  if (const Expected<void> opened = open_transport(opt, transport); !opened) {
    logger().error("options", "%s", opened.error().message.c_str());
    return kExitBadOptions;
  }
  std::unique_ptr<twister::hal::SodiumAuthenticator> auth;
  if (!load_authenticator(opt, auth)) return kExitBadOptions;
  twister::bridge::BridgeOptions bridge_options;
  bridge_options.snapshot_dir = opt.snapshots;
  bridge_options.movie_every = opt.movie_every;
  bridge_options.authenticator = auth.get();
  bridge_options.spectator = opt.spectator;
  bridge_options.limits = opt.limits;
  // Kiosk, offscreen and a fixed camera frame the hands' working space when the station
  // has one (calibrated or configured); a window's free camera frames the model.
  using twister::bridge::Framing;
  bridge_options.framing =
      opt.frame == "model"       ? Framing::model
      : opt.frame == "workspace" ? Framing::workspace
      : opt.frame == "auto" || opt.kiosk || opt.offscreen || options.fixed_camera
          ? Framing::automatic
          : Framing::model;
  BridgeApp app(*transport.port, clock, &display.renderer, bridge_options, logger());
  app.set_view(&display.view);
  std::unique_ptr<twister::bridge::AttractShowcase> showcase;
  if (!options.attract.archive.empty()) {
    twister::bridge::ShowcaseOptions shown;
    shown.dir = options.attract.archive;
    shown.models = static_cast<std::size_t>(options.attract.models);
    shown.seconds_each = options.attract.seconds;
    showcase = std::make_unique<twister::bridge::AttractShowcase>(shown, logger());
    app.set_showcase(showcase.get());
  }
  app.replica().set_crease_angle(opt.crease_angle_deg);
  display.renderer.allow_live_refinement(!opt.no_live_refine);
  twister::bridge::WindowInput input(app, display.view, options.fixed_camera);
  input.attach(display.context->window());
  int rc = run_loop(opt, app, display, transport.poll_fd(), clock);
  // The display as it was when the run ended (the model the station left, the hands
  // where they went): final.png.
  if (!opt.snapshots.empty() && rc == kExitOk && app.replica().has_mesh()) app.snapshot("final");
  if (!opt.export_path.empty()) {
    if (const int exported = export_final_mesh(opt.export_path, opt.force, app);
        exported != kExitOk) {
      return exported;
    }
  }
  log_summary(app);
  for (const std::string& p : app.pictures()) std::printf("%s\n", p.c_str());
  return rc;
}

void add_link_options(CLI::App& cli, Options& opt) {
  cli.add_option("--connect", opt.connect,
                 "station link: unix:PATH, tcp:HOST:PORT or serial:DEVICE")
      ->required();
  cli.add_option("--baud", opt.baud, "serial: line speed (default 230400)")
      ->check(CLI::IsMember({9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600}));
  cli.add_option("--link-key", opt.link_key,
                 "pre-shared key file (64 hex digits, mode 0600): the station's link.psk_file");
  cli.add_option("--max-vertices", opt.limits.max_vertices,
                 "largest mesh accepted from the station (default 4194304 vertices)")
      ->check(CLI::Range(1u, 1u << 28));
  cli.add_option("--max-triangles", opt.limits.max_triangles,
                 "largest mesh accepted from the station (default 8388608 triangles)")
      ->check(CLI::Range(1u, 1u << 29));
  cli.add_flag("--spectator", opt.spectator,
               "a read-only display (a projector, a screen facing the queue): it watches the "
               "station and sends no commands");
}

void add_output_options(CLI::App& cli, Options& opt) {
  cli.add_flag("--offscreen", opt.offscreen,
               "no window: EGL surfaceless rendering (PNG snapshots)");
  cli.add_flag("--kiosk", opt.kiosk, "full screen on the primary monitor");
  cli.add_option("--size", opt.size, "WxH in pixels (window or offscreen)");
  cli.add_option(
      "--snapshots", opt.snapshots,
      "directory for PNGs: rest.png, live-<version>.png, commit-<version>.png, final.png "
      "(the display at exit)");
  cli.add_option("--movie-every", opt.movie_every,
                 "with --snapshots: also frame-<n>.png after every N-th hands update (the "
                 "station sends at most one per 8 ms of its clock): frames for an animation");
  cli.add_option("--export", opt.export_path,
                 "write the final mesh at exit (checked at start): .obj or .ply in the model's "
                 "frame, metres; .glb / .gltf (metres, +Y up, a material) or .stl "
                 "(millimetres, +Z up) upright from the station's up and centred");
  cli.add_flag("--force", opt.force,
               "--export may replace an existing file of the same kind (never a journal, "
               "checkpoint, a file a running station holds, or another kind of file)");
  cli.add_option("--exit-after-commits", opt.exit_after_commits,
                 "exit once this many commits were applied and verified");
  cli.add_flag("--exit-on-disconnect", opt.exit_on_disconnect,
               "exit when the station closes the link (after a mesh was received)");
  cli.add_option("--timeout", opt.timeout_s, "give up after this many seconds (0 = never)")
      ->check(CLI::NonNegativeNumber);
}

void add_view_options(CLI::App& cli, Options& opt) {
  cli.add_option("--camera", opt.camera_file,
                 "camera file (TOML [camera]: azimuth_deg, elevation_deg, zoom, fov_deg, up, "
                 "target, fixed): a kiosk's fixed view");
  cli.add_option("--frame", opt.frame,
                 "what the camera frames: model, workspace (the station's working volume and "
                 "the model, grown to keep both cursors in view) or auto (workspace when the "
                 "station has a work frame or work_volume; the default in kiosk, offscreen and "
                 "with a fixed camera; a window's free camera: model)")
      ->check(CLI::IsMember({"model", "workspace", "auto"}));
  cli.add_option("--azimuth", opt.view.azimuth_deg, "camera azimuth in degrees");
  cli.add_option("--elevation", opt.view.elevation_deg, "camera elevation in degrees");
  cli.add_option_function<float>(
         "--zoom-out", [&opt](float f) { opt.view.zoom = 1.0F / f; },
         "camera distance x this (default 1: the first mesh fills the view)")
      ->check(CLI::Range(0.25, 10.0));
  cli.add_option("--log-level", opt.log_level,
                 "error | warning | notice (default) | info (each picture) | debug")
      ->check(CLI::IsMember({"error", "warning", "notice", "info", "debug"}));
  cli.add_flag("--no-cues", opt.no_cues,
               "draw the model alone: no hand glyphs, spheres, axes, trajectories (key C)");
  cli.add_flag("--no-hud", opt.no_hud, "no heads-up text or banners (key H)");
  cli.add_option("--hud", opt.hud,
                 "who the text speaks to: visitor (the model, the hands and a few friendly words; "
                 "the default in --kiosk) or operator (the technical HUD; the default otherwise); "
                 "key Tab switches")
      ->check(CLI::IsMember({"visitor", "operator"}));
  cli.add_option("--attract-archive", opt.attract.archive,
                 "attract mode turns recent sculptures from this directory (the station's "
                 "[exhibit] archive_dir: each archive's model.glb, captioned from its record.json) "
                 "instead of the station's model; the first grab shows the station's at once");
  cli.add_option("--attract-models", opt.attract.models,
                 "with --attract-archive: the newest archives shown (default 6)")
      ->check(CLI::Range(1, 32));
  cli.add_option("--attract-seconds", opt.attract.seconds,
                 "with --attract-archive: seconds each is shown (default 8)")
      ->check(CLI::Range(1.0, 600.0));
  cli.add_option("--crease-angle", opt.crease_angle_deg,
                 "an edge whose faces' normals differ by more than this keeps a normal per side "
                 "(degrees, default 45; 180: every edge smooth)")
      ->check(CLI::Range(0.0, 180.0));
  cli.add_flag("--no-live-refine", opt.no_live_refine,
               "draw the live stroke unrefined even on OpenGL 4 (the commit still refines)");
  cli.add_flag("-q,--quiet", opt.quiet, "same as --log-level warning (which wins if given)");
}

void add_options(CLI::App& cli, Options& opt) {
  add_link_options(cli, opt);
  add_output_options(cli, opt);
  add_view_options(cli, opt);
}

}  // namespace

int main(int argc, char** argv) try {
  logger().configure({"twister-bridge", LogLevel::notice, twister::hal::stderr_is_journal(), 2});
  CLI::App cli{"twister-bridge: scene replica and display of a twister-station"};
  Options opt;
  add_options(cli, opt);
  cli.footer(twister::bridge::key_help());
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = cli.exit(e);
    return rc == 0 ? kExitOk : kExitBadOptions;
  }
  LogLevel level = LogLevel::notice;
  (void)twister::hal::parse_log_level(opt.log_level, level);  // checked by CLI11
  if (opt.quiet && cli.count("--log-level") == 0) level = LogLevel::warning;
  opt.attract_models_given = cli.count("--attract-models") > 0;
  opt.attract_seconds_given = cli.count("--attract-seconds") > 0;
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
