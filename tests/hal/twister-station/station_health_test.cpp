// The station's fleet health (issue 25, label exhibit): the [health] keys, and the
// real loop (simulator in virtual time, four scripted strokes) writing the metrics
// file every period without allocating, whose numbers equal the run's counts and
// which promtool accepts; a metrics path holding someone else's file is refused at
// start.
#include "station_health.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "allocation_counter.hpp"
#include "config/station_config.hpp"
#include "prometheus_text.hpp"
#include "station_assembly.hpp"
#include "station_loop.hpp"
#include "twister/hal/logger.hpp"
#include "twister/hal/socket_link.hpp"
#include "twister/link/link_codec.hpp"

namespace twister::station_app {
namespace {

namespace fs = std::filesystem;

std::string temp_path(const char* name) {
  return "/tmp/twister_health_" + std::to_string(::getpid()) + "_" + name;
}

std::string slurp(const std::string& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

ConfigParseResult parse(const std::string& health) {
  return parse_station_config(
      "[station]\njournal = \"/tmp/j\"\nmesh = \"m.obj\"\n[tracker]\nbackend = \"sim\"\n"
      "[tracker.sim]\nscenario_file = \"x.scn\"\n[buttons]\nbackend = \"sim\"\n" +
          health,
      "h.toml");
}

TEST(HealthConfig, KeysAndTheirChecks) {
  const ConfigParseResult none = parse("");
  ASSERT_TRUE(none.ok()) << none.errors[0].to_string();
  EXPECT_EQ(none.config.health.metrics_file, "");
  EXPECT_EQ(none.config.health.period_s, 15.0);
  const ConfigParseResult all = parse(
      "[health]\nmetrics_file = \"/var/lib/prometheus/node-exporter/twister.prom\"\n"
      "period_s = 5\narchive_path = \"/var/lib/twister\"\nstatus = false\n");
  ASSERT_TRUE(all.ok()) << all.errors[0].to_string();
  EXPECT_EQ(all.config.health.metrics_file, "/var/lib/prometheus/node-exporter/twister.prom");
  EXPECT_EQ(all.config.health.period_s, 5.0);
  EXPECT_EQ(all.config.health.archive_path, "/var/lib/twister");
  EXPECT_FALSE(all.config.health.status);
  const ConfigParseResult bad =
      parse("[health]\nmetrics_file = \"/tmp/x.txt\"\nperiod_s = 0\nperiod = 3\n");
  ASSERT_EQ(bad.errors.size(), 3U);
  EXPECT_NE(bad.errors[0].to_string().find("health.metrics_file: expected a name ending in .prom"),
            std::string::npos)
      << bad.errors[0].to_string();
  EXPECT_NE(bad.errors[1].to_string().find("health.period_s"), std::string::npos);
  EXPECT_NE(bad.errors[2].to_string().find("health.period"), std::string::npos);
}

TEST(HealthConfig, ForeignMetricsFileIsRefusedAtStart) {
  const std::string path = temp_path("foreign.prom");
  std::ofstream(path) << "node_something 1\n";
  StationFileConfig config = parse("").config;
  config.health.metrics_file = path;
  auto refused = make_health_config(config, "/");
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("health.metrics_file: metrics file " + path),
            std::string::npos)
      << refused.error().message;
  EXPECT_EQ(slurp(path), "node_something 1\n");
  ::unlink(path.c_str());
}

TEST(StationHealthLoop, MetricsFileFollowsTheRunWithoutAllocating) {
  const std::string journal = temp_path("journal.bin");
  const std::string metrics = temp_path("twister.prom");
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
  ::unlink(metrics.c_str());
  const std::string text = "[station]\njournal = \"" + journal +
                           "\"\nmesh = \"" TWISTER_DEPLOY_DIR
                           "/sim_sphere.obj\"\n"
                           "[tracker]\nbackend = \"sim\"\n[tracker.sim]\nscenario_file = \"" +
                           TWISTER_SCENARIO_DIR
                           "/loop_strokes.scn\"\ntime = \"virtual\"\n"
                           "[buttons]\nbackend = \"sim\"\n[sculpt]\nrefine = false\n"
                           "[systemd]\nnotify = false\nwatchdog = false\n"
                           "[health]\nmetrics_file = \"" +
                           metrics + "\"\nperiod_s = 1\n";
  const ConfigParseResult parsed = parse_station_config(text, "health.toml");
  ASSERT_TRUE(parsed.ok()) << parsed.errors[0].to_string();
  auto health_config = make_health_config(parsed.config, TWISTER_DEPLOY_DIR);
  ASSERT_TRUE(health_config) << health_config.error().message;
  StationHealth health(std::move(*health_config));
  health.metrics().visitors_today = 3;  // as the visitor lifecycle would
  auto assembled = assemble_station(parsed.config, {TWISTER_DEPLOY_DIR, ""});
  ASSERT_TRUE(assembled) << assembled.error().message;
  StationParts& parts = **assembled;
  hal::Logger log({"twister-station", hal::LogLevel::warning, false, 2});
  StationLoop loop(*parts.core, parts.backends, parts.display, log,
                   make_loop_config(parsed.config, 0.0, parts.backends));
  loop.report_health(&health);
  ports::Clock& clock = *parts.backends.clock;
  const ports::TimestampUs t0 = clock.now_us();
  ASSERT_TRUE(loop.start());
  while (clock.now_us() - t0 < 2'500'000) ASSERT_TRUE(loop.step());
  // Written at the first pass and each second since.
  EXPECT_GE(health.reports(), 2U);
  const std::uint64_t reports_before = health.reports();
  std::size_t allocations = 0;
  {
    test::AllocationCounter counter;
    while (loop.step()) {
    }
    allocations = counter.count();
  }
  EXPECT_EQ(allocations, 0U);
  const double simulated_s = static_cast<double>(clock.now_us() - t0) / 1e6;
  EXPECT_GE(health.reports() - reports_before, static_cast<std::uint64_t>(simulated_s) - 4);
  ASSERT_TRUE(loop.finish().ok());

  const std::string prom = slurp(metrics);
  const auto& counters = parts.core->counters().events;
  EXPECT_EQ(counters.strokes_committed, 4U);
  EXPECT_EQ(test::prometheus_sample(prom, "twister_strokes_committed_total"),
            static_cast<double>(counters.strokes_committed));
  EXPECT_EQ(test::prometheus_sample(prom, "twister_strokes_not_saved_total"), 0.0);
  EXPECT_EQ(test::prometheus_sample(prom, "twister_visitors_today"), 3.0);
  EXPECT_EQ(test::prometheus_sample(prom, "twister_tracker_state{state=\"streaming\"}"), 1.0);
  EXPECT_GT(test::prometheus_sample(prom, "twister_tracker_rate_hertz"), 50.0);
  EXPECT_EQ(test::prometheus_sample(prom, "twister_buttons_present"), 1.0);
  EXPECT_EQ(test::prometheus_sample(prom, "twister_link_open"), 0.0);
  EXPECT_GT(test::prometheus_sample(prom, "twister_archive_free_bytes"), 0.0);
  EXPECT_NEAR(test::prometheus_sample(prom, "twister_uptime_seconds"), simulated_s, 0.5);
  FILE* p = popen(("promtool check metrics < " + metrics + " 2>&1").c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::array<char, 512> buf{};
  std::string out;
  while (fgets(buf.data(), buf.size(), p) != nullptr) out += buf.data();
  EXPECT_EQ(pclose(p), 0) << out;
  EXPECT_EQ(out, "");
  ::unlink(metrics.c_str());
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
}

// Issue 25: a spectator display connected to the station's link shows in the metrics
// (twister_spectators) and the display link's gauges; its hello is answered in the loop.
TEST(StationHealthLoop, ASpectatorOnTheLinkIsCountedInTheMetrics) {
  const std::string journal = temp_path("spect_journal.bin");
  const std::string metrics = temp_path("spect.prom");
  const std::string sock = temp_path("spect.sock");
  for (const std::string& f : {journal, journal + ".ckpt", metrics}) ::unlink(f.c_str());
  const std::string text =
      "[station]\njournal = \"" + journal +
      "\"\nmesh = \"" TWISTER_DEPLOY_DIR
      "/sim_sphere.obj\"\n[tracker]\nbackend = \"sim\"\n[tracker.sim]\nscenario_file = \"" +
      TWISTER_SCENARIO_DIR
      "/loop_strokes.scn\"\ntime = \"virtual\"\n[buttons]\nbackend = \"sim\"\n"
      "[sculpt]\nrefine = false\n[systemd]\nnotify = false\nwatchdog = false\n"
      "[link]\naddress = \"unix:" +
      sock + "\"\nmax_spectators = 2\n[health]\nmetrics_file = \"" + metrics + "\"\nperiod_s = 1\n";
  const ConfigParseResult parsed = parse_station_config(text, "spect.toml");
  ASSERT_TRUE(parsed.ok()) << parsed.errors[0].to_string();
  auto health_config = make_health_config(parsed.config, TWISTER_DEPLOY_DIR);
  ASSERT_TRUE(health_config) << health_config.error().message;
  StationHealth health(std::move(*health_config));
  auto assembled = assemble_station(parsed.config, {TWISTER_DEPLOY_DIR, ""});
  ASSERT_TRUE(assembled) << assembled.error().message;
  StationParts& parts = **assembled;
  hal::Logger log({"twister-station", hal::LogLevel::warning, false, 2});
  StationLoop loop(*parts.core, parts.backends, parts.display, log,
                   make_loop_config(parsed.config, 0.0, parts.backends));
  loop.report_health(&health);
  ASSERT_TRUE(loop.start());
  ASSERT_TRUE(parts.display.is_open());
  hal::SocketLink spectator({"unix:" + sock, false, 0});
  ASSERT_TRUE(spectator.open());
  std::array<std::byte, 128> hello{};
  const auto n =
      link::encode_frame(link::Hello{link::Role::bridge, link::kHelloSpectator, 0, 0, {}}, hello);
  ASSERT_TRUE(n.ok());
  ASSERT_EQ(*spectator.send(std::span<const std::byte>(hello).first(*n)), *n);
  ports::Clock& clock = *parts.backends.clock;
  const ports::TimestampUs t0 = clock.now_us();
  std::vector<std::byte> sink(1 << 16);
  while (clock.now_us() - t0 < 2'500'000) {
    ASSERT_TRUE(loop.step());
    (void)spectator.receive(sink);  // it reads what it is sent
  }
  ASSERT_NE(parts.display.counters(), nullptr);
  EXPECT_EQ(parts.display.counters()->spectators_now, 1U);
  EXPECT_FALSE(parts.display.connected());  // no main display: the spectator took none
  const std::string prom = slurp(metrics);
  EXPECT_EQ(test::prometheus_sample(prom, "twister_spectators"), 1.0) << prom;
  EXPECT_EQ(test::prometheus_sample(prom, "twister_link_open"), 1.0);
  ASSERT_TRUE(loop.finish().ok());
  for (const std::string& f : {journal, journal + ".ckpt", metrics}) ::unlink(f.c_str());
}

}  // namespace
}  // namespace twister::station_app
