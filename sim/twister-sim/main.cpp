// twister-sim: a simulated Polhemus Fastrak on a PTY (or a real serial port for HIL
// rigs), driven by a scenario file. Prints the device path on stdout as its first
// line (its output: clients wait for it). Logs through hal::Logger ("twister-sim:
// [error: ]component: message"); --log-level picks the threshold (default notice:
// errors and the exit summary).
// --buttons drives the scenario's button lines on GPIO output lines (a HIL rig's wiring
// to the station's button inputs, docs/hil.md) on the same clock as the records.
// Exit codes: 0 ok, 1 failure (PTY, device or GPIO lines), 2 bad options or scenario.
#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "device_server.hpp"
#include "gpio_buttons.hpp"
#include "twister/hal/logger.hpp"
#include "twister/sim/fastrak_device.hpp"
#include "twister/sim/scenario.hpp"
#ifdef TWISTER_SIM_GPIOD
#include "twister/hal/gpiod_line_output.hpp"
#endif

namespace {

using twister::hal::LogLevel;

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadOptions = 2;

volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

twister::hal::Logger& logger() { return twister::hal::process_log(); }

struct Options {
  std::string scenario_path;
  twister::sim::ServeOptions serve;
  twister::sim::FastrakDeviceConfig dev;
  double reset_s = twister::sim::kRealUnitBootUs / 1e6;  // a real unit's boot (10 s)
  double duration_s = 0.0;
  bool binary = false;
  std::string port = "usb";
  std::string filter = "off";
  std::vector<std::string> command_times;  // LETTER=SECONDS
  std::string log_level = "notice";
  std::string model = "fastrak";
  std::string buttons;  // --buttons spec (gpio_buttons.hpp)
  std::string scenario_clock = "power-up";
};

// "O=0.05", "x=1", "^K=3", "all=0": sets the processing time of that command.
bool set_command_time(const std::string& spec, twister::sim::CommandTimes& times) {
  const auto eq = spec.find('=');
  if (eq == std::string::npos) return false;
  const std::string name = spec.substr(0, eq);
  char* end = nullptr;
  const double s = std::strtod(spec.c_str() + eq + 1, &end);
  if (end == spec.c_str() + eq + 1 || *end != '\0' || !(s >= 0.0 && s <= 60.0)) return false;
  const auto us = static_cast<std::int32_t>(s * 1e6);
  if (name == "all") {
    times.fill(us);
  } else if (name.size() == 1) {
    times[static_cast<unsigned char>(name[0]) & 0x7Fu] = us;
  } else if (name.size() == 2 && name[0] == '^' && name[1] >= '@' && name[1] <= '_') {
    times[static_cast<std::size_t>(name[1] - '@')] = us;  // ^Y = 0x19, ^K = 0x0B
  } else {
    return false;
  }
  return true;
}

void add_options(CLI::App& app, Options& o) {
  app.add_option("--scenario", o.scenario_path,
                 "scenario file (docs/fastrak.md); default: resting hands");
  app.add_option("--link", o.serve.link, "PTY mode: keep a symlink to the current slave here");
  app.add_option("--device", o.serve.device,
                 "serve on this real serial device (HIL) instead of a PTY");
  app.add_option("--baud", o.dev.baud, "modelled line rate (bits/s, 10 bits per byte)")
      ->check(CLI::Range(300, 4000000));
  app.add_option("--reset-time", o.reset_s,
                 "seconds a ^Y or power-up takes (default 10, a real Fastrak; tests and "
                 "scripts pass 0.5 or less)")
      ->check(CLI::Range(0.0, 60.0));
  app.add_option("--scenario-clock", o.scenario_clock,
                 "where scenario time 0 is: power-up (default) or stream (the host's first "
                 "C: motion, faults and the scenario's duration count from there)")
      ->check(CLI::IsMember({"power-up", "stream"}));
  app.add_flag("--continuous", o.dev.start_continuous, "power up in continuous mode");
  app.add_flag("--binary", o.binary, "power up in binary format");
  app.add_flag("--binary16", o.dev.packed16,
               "the unit's binary format (f) is the 16-bit packed one (Isotrak II / 3SPACE)");
  app.add_option("--port", o.port,
                 "PTY mode: usb (a hang-up removes the tty and the link) or fixed (a "
                 "/dev/ttyS* port: the line just goes dead)")
      ->check(CLI::IsMember({"usb", "fixed"}));
  app.add_option("--filter", o.filter, "power-up position and attitude filter (x/v macros)")
      ->check(CLI::IsMember({"off", "low", "medium", "heavy"}));
  app.add_option("--command-time", o.command_times,
                 "processing time of a command, LETTER=SECONDS (^K=3, all=0; repeatable)");
  app.add_option("--duration", o.duration_s,
                 "stop after this many seconds (0: run until signalled)")
      ->check(CLI::Range(0.0, 1e9));
  app.add_option("--model", o.model,
                 "the unit played: fastrak (default), liberty or patriot (same commands; in "
                 "binary, frames of docs/liberty-protocol.md)")
      ->check(CLI::IsMember({"fastrak", "liberty", "patriot"}));
  app.add_option("--buttons", o.buttons,
                 "drive the scenario's button lines on GPIO output lines (HIL rig, "
                 "docs/hil.md): gpiod:CHIP:OFFSET,OFFSET,...[:active-low|:active-high]"
                 "[:open-drain]; button line i on the i-th offset, as the station reads "
                 "button i from [buttons.gpiod] lines[i]; default active-low (pressed = low)");
  app.add_option("--log-level", o.log_level, "error | warning | notice (default) | info | debug")
      ->check(CLI::IsMember({"error", "warning", "notice", "info", "debug"}));
}

void log_summary(const twister::sim::FastrakDevice& device,
                 const twister::sim::DeviceServer& server) {
  const auto& c = device.counters();
  logger().notice("summary",
                  "records=%llu dropped_solutions=%llu commands=%llu errors=%llu resets=%llu "
                  "input_lost=%llu corrupted=%llu status_letters=%llu dropped_bytes=%llu "
                  "drop_expired=%llu misclock_lost=%llu misclock_junk=%llu host_baud=%d "
                  "ptys=%llu hangups=%llu hangup_lost=%llu stylus_polls=%llu",
                  c.output.records, c.dropped_solutions, c.commands, c.command_errors, c.resets,
                  c.input_lost, c.corrupted_records, c.status_letters, c.dropped_bytes,
                  c.drop_expired, c.misclock_lost, c.misclock_junk, server.counters().host_baud,
                  server.counters().ptys_opened, server.counters().hangups, c.output.hangup_lost,
                  c.output.stylus_polls);
}

// The scenario's buttons on GPIO output lines (--buttons), or nothing.
class GpioButtons {
 public:
  // Opens the lines (all released). false: said why, exit 1.
  bool open(const twister::sim::GpioButtonsSpec& spec) {
#ifdef TWISTER_SIM_GPIOD
    twister::hal::GpiodOutputConfig config;
    config.chip = spec.chip;
    config.lines = spec.lines;
    config.active_low = spec.active_low;
    config.open_drain = spec.open_drain;
    const twister::Status s = output_.open(config);
    if (s.ok()) {
      std::string offsets;
      for (const std::uint32_t line : spec.lines) {
        offsets += (offsets.empty() ? "" : ",") + std::to_string(line);
      }
      logger().notice("buttons", "%zu lines on %s (offsets %s, %s%s), all released",
                      spec.lines.size(), spec.chip.c_str(), offsets.c_str(),
                      spec.active_low ? "active low" : "active high",
                      spec.open_drain ? ", open drain" : "");
      open_ = true;
      return true;
    }
    const int err = output_.last_errno();
    switch (s.code()) {
      case twister::StatusCode::unavailable:
        logger().error("buttons", "no GPIO chip %s (gpiodetect lists the chips)",
                       spec.chip.c_str());
        break;
      case twister::StatusCode::invalid_argument:
        logger().error("buttons",
                       "%s has no such line: an offset of --buttons is beyond the chip's lines "
                       "(gpioinfo %s lists them)",
                       spec.chip.c_str(), spec.chip.c_str());
        break;
      default:
        logger().error("buttons", "cannot request the lines on %s: %s (errno %d)%s",
                       spec.chip.c_str(), std::strerror(err), err,
                       err == EBUSY    ? "; another program or driver holds a line (gpioinfo "
                                         "shows its consumer)"
                       : err == EACCES ? "; add the user to the gpio group (udev rule)"
                                       : "");
        break;
    }
    return false;
#else
    (void)spec;
    logger().error("buttons", "--buttons: this twister-sim was built without libgpiod");
    return false;
#endif
  }
  bool is_open() const { return open_; }
  // Plays what is due at now_us, the edges of one instant in one write; false: said
  // why (the chip went away), exit 1.
  bool advance(twister::sim::ButtonPlayer& player, std::int64_t now_us) {
#ifdef TWISTER_SIM_GPIOD
    twister::Status s = player.advance(now_us, [this, now_us](std::size_t line, bool pressed) {
      logger().info("buttons", "line %zu %s at %.3f s", line, pressed ? "pressed" : "released",
                    static_cast<double>(now_us) / 1e6);
      return output_.stage(line, pressed);
    });
    if (s.ok()) s = output_.flush();
    if (s.ok()) return true;
    const int err = output_.last_errno();
    logger().error("buttons", "cannot set the lines: %s (errno %d)", std::strerror(err), err);
    return false;
#else
    (void)player;
    (void)now_us;
    return false;
#endif
  }

 private:
#ifdef TWISTER_SIM_GPIOD
  twister::hal::GpiodLineOutput output_;  // releases every line (inactive) when it goes
#endif
  bool open_ = false;
};

// Serves the device until signalled or the duration is over.
int serve(Options& o, const twister::sim::Scenario& scenario,
          const twister::sim::GpioButtonsSpec* buttons_spec) {
  o.serve.baud = o.dev.baud;
  o.serve.port =
      o.port == "fixed" ? twister::sim::PortKind::fixed : twister::sim::PortKind::usb_adapter;
  o.dev.reset_time_us = static_cast<std::int64_t>(o.reset_s * 1e6);
  o.dev.scenario_clock = o.scenario_clock == "stream"
                             ? twister::sim::ScenarioClock::first_continuous
                             : twister::sim::ScenarioClock::power_up;
  o.dev.model = o.model == "liberty"   ? twister::sim::DeviceModel::liberty
                : o.model == "patriot" ? twister::sim::DeviceModel::patriot
                                       : twister::sim::DeviceModel::fastrak;
  if (o.binary) {
    o.dev.start_format =
        o.dev.packed16 ? twister::tracker::Format::binary16 : twister::tracker::Format::binary;
  }
  const twister::sim::FilterParams filter = o.filter == "low"      ? twister::sim::kFilterLow
                                            : o.filter == "medium" ? twister::sim::kFilterMedium
                                            : o.filter == "heavy"  ? twister::sim::kFilterHeavy
                                                                   : twister::sim::kFilterOff;
  o.dev.start_position_filter = o.dev.start_attitude_filter = filter;
  // --duration counts from start-up; the scenario's own duration on its clock.
  const double duration_s = o.duration_s;

  // The lines first (all released), so that the scenario's clock starts with them ready.
  GpioButtons buttons;
  twister::sim::ButtonPlayer player(scenario.buttons);
  if (buttons_spec != nullptr && !buttons.open(*buttons_spec)) return kExitFailure;

  twister::sim::FastrakDevice device(o.dev, scenario, 0);
  twister::sim::DeviceServer server(device, o.serve);
  if (const auto started = server.start(); !started) {
    logger().error("device", "%s", started.error().message.c_str());
    return kExitFailure;
  }
  std::printf("%s\n", o.serve.link.empty() ? server.slave_path().c_str() : o.serve.link.c_str());
  std::fflush(stdout);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGPIPE, SIG_IGN);
  while (g_stop == 0) {
    if (const auto stepped = server.step(1); !stepped) {
      logger().error("device", "%s", stepped.error().message.c_str());
      return kExitFailure;
    }
    // The buttons on the scenario's clock, as the tracker's motion (--scenario-clock).
    if (buttons.is_open() && device.scenario_started() &&
        !buttons.advance(player, device.scenario_time_us(server.now_us()))) {
      return kExitFailure;
    }
    if (duration_s > 0.0 && static_cast<double>(server.now_us()) / 1e6 >= duration_s) break;
    if (duration_s == 0.0 && scenario.duration_s > 0.0 && device.scenario_started() &&
        device.scenario_time_s(server.now_us()) >= scenario.duration_s) {
      break;
    }
  }
  log_summary(device, server);
  if (buttons.is_open()) {
    logger().notice("buttons", "edges=%llu not_played=%zu",
                    static_cast<unsigned long long>(player.edges()), player.remaining());
  }
  // Only our symbolic link goes (never a file that took its place meanwhile).
  struct stat st {};
  if (!o.serve.link.empty() && ::lstat(o.serve.link.c_str(), &st) == 0 && S_ISLNK(st.st_mode)) {
    ::unlink(o.serve.link.c_str());
  }
  return kExitOk;
}

int run(int argc, char** argv) {
  CLI::App app{"twister-sim: simulated Polhemus Fastrak on a PTY or serial port"};
  Options o;
  add_options(app, o);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? kExitOk : kExitBadOptions;
  }
  for (const std::string& spec : o.command_times) {
    if (!set_command_time(spec, o.dev.command_time_us)) {
      logger().error("", "--command-time %s: expected LETTER=SECONDS (0..60)", spec.c_str());
      return kExitBadOptions;
    }
  }
  LogLevel level = LogLevel::notice;
  (void)twister::hal::parse_log_level(o.log_level, level);  // checked by CLI11
  logger().set_threshold(level);

  twister::sim::Scenario scenario;
  if (!o.scenario_path.empty()) {
    auto loaded = twister::sim::load_scenario_file(o.scenario_path);
    if (!loaded) {
      logger().error("scenario", "%s", loaded.error().message.c_str());
      return kExitBadOptions;
    }
    scenario = std::move(*loaded);
  }
  if (o.buttons.empty()) return serve(o, scenario, nullptr);
  auto spec = twister::sim::parse_gpio_buttons(o.buttons);
  if (!spec) {
    logger().error("", "%s", spec.error().message.c_str());
    return kExitBadOptions;
  }
  if (auto wired = twister::sim::ButtonPlayer(scenario.buttons).check_lines(spec->lines.size());
      !wired) {
    logger().error("buttons", "%s", wired.error().message.c_str());
    return kExitBadOptions;
  }
  return serve(o, scenario, &*spec);
}

}  // namespace

int main(int argc, char** argv) {
  logger().configure({"twister-sim", LogLevel::notice, twister::hal::stderr_is_journal(), 2});
  // Anything thrown (allocation failure, I/O library) ends the run with a message.
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    logger().error("", "%s", e.what());
    return kExitFailure;
  }
}
