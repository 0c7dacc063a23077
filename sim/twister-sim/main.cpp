// twister-sim: a simulated Polhemus Fastrak on a PTY (or a real serial port for HIL
// rigs), driven by a scenario file. Prints the device path on stdout as its first line.
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>

#include "device_server.hpp"
#include "twister/sim/fastrak_device.hpp"
#include "twister/sim/scenario.hpp"

namespace {
volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

int run(int argc, char** argv) {
  CLI::App app{"twister-sim: simulated Polhemus Fastrak on a PTY or serial port"};
  std::string scenario_path;
  twister::sim::ServeOptions serve;
  twister::sim::FastrakDeviceConfig dev;
  double reset_s = 0.5;
  double duration_s = 0.0;
  bool binary = false;
  app.add_option("--scenario", scenario_path,
                 "scenario file (docs/fastrak.md); default: resting hands");
  app.add_option("--link", serve.link, "PTY mode: keep a symlink to the current slave here");
  app.add_option("--device", serve.device,
                 "serve on this real serial device (HIL) instead of a PTY");
  app.add_option("--baud", dev.baud, "modelled line rate (bits/s, 10 bits per byte)")
      ->check(CLI::Range(300, 4000000));
  app.add_option("--reset-time", reset_s, "seconds a ^Y or power-up takes (real unit: 10-20)")
      ->check(CLI::Range(0.0, 60.0));
  app.add_flag("--continuous", dev.start_continuous, "power up in continuous mode");
  app.add_flag("--binary", binary, "power up in binary format");
  app.add_option("--duration", duration_s, "stop after this many seconds (0: run until signalled)")
      ->check(CLI::Range(0.0, 1e9));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  serve.baud = dev.baud;
  dev.reset_time_us = static_cast<std::int64_t>(reset_s * 1e6);
  if (binary) dev.start_format = twister::tracker::Format::binary;

  twister::sim::Scenario scenario;
  if (!scenario_path.empty()) {
    auto loaded = twister::sim::load_scenario_file(scenario_path);
    if (!loaded) {
      std::fprintf(stderr, "twister-sim: %s\n", loaded.error().message.c_str());
      return 2;
    }
    scenario = std::move(*loaded);
  }
  if (duration_s == 0.0) duration_s = scenario.duration_s;

  twister::sim::FastrakDevice device(dev, scenario, 0);
  twister::sim::DeviceServer server(device, serve);
  std::string error;
  if (!server.start(error)) {
    std::fprintf(stderr, "twister-sim: %s\n", error.c_str());
    return 1;
  }
  std::printf("%s\n", serve.link.empty() ? server.slave_path().c_str() : serve.link.c_str());
  std::fflush(stdout);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGPIPE, SIG_IGN);
  while (g_stop == 0) {
    if (!server.step(1, error)) {
      std::fprintf(stderr, "twister-sim: %s\n", error.c_str());
      return 1;
    }
    if (duration_s > 0.0 && static_cast<double>(server.now_us()) / 1e6 >= duration_s) break;
  }
  const auto& c = device.counters();
  std::fprintf(stderr,
               "twister-sim: records=%llu dropped_solutions=%llu commands=%llu errors=%llu "
               "resets=%llu ptys=%llu hangups=%llu\n",
               static_cast<unsigned long long>(c.records),
               static_cast<unsigned long long>(c.dropped_solutions),
               static_cast<unsigned long long>(c.commands),
               static_cast<unsigned long long>(c.command_errors),
               static_cast<unsigned long long>(c.resets),
               static_cast<unsigned long long>(server.counters().ptys_opened),
               static_cast<unsigned long long>(server.counters().hangups));
  if (!serve.link.empty()) std::remove(serve.link.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Anything thrown (allocation failure, I/O library) ends the run with a message.
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "twister-sim: %s\n", e.what());
    return 1;
  }
}
