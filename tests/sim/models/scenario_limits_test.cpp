// Issue 21 item 6: the simulator's input is bounded. Scenario files are refused by
// type (FIFO, device, directory) and size without blocking, read line by line (memory
// is what the scenario holds, not the file), fault amounts and other values are
// range-checked; an absurd noise amount built in code never spins the device model.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "twister/sim/fastrak_device.hpp"
#include "twister/sim/scenario.hpp"

namespace twister::sim {
namespace {

namespace fs = std::filesystem;

class ScenarioLimits : public ::testing::Test {
 protected:
  void SetUp() override { fs::create_directories(dir_); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_ = fs::temp_directory_path() / ("scenario_limits_" + std::to_string(::getpid()));
};

std::string refusal(const std::string& file) {
  const auto loaded = load_scenario_file(file);
  return loaded ? std::string("(loaded)") : loaded.error().message;
}

TEST_F(ScenarioLimits, FifosDevicesDirectoriesAndHugeFilesAreRefusedAtOnce) {
  ASSERT_EQ(::mkfifo(path("fifo.scn").c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_NE(refusal(path("fifo.scn")).find("is a FIFO, not a regular file"), std::string::npos);
  EXPECT_NE(refusal("/dev/zero").find("is a device, not a regular file"), std::string::npos);
  EXPECT_NE(refusal(dir_.string()).find("is a directory, not a regular file"), std::string::npos);
  // A sparse file past the limit: refused by its size, never read.
  { std::ofstream(path("big.scn")) << "# big\n"; }
  fs::resize_file(path("big.scn"), kMaxScenarioBytes + 1);
  EXPECT_NE(refusal(path("big.scn")).find("scenarios are limited to 16777216 bytes"),
            std::string::npos)
      << refusal(path("big.scn"));
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  // A line without end is refused at its limit.
  { std::ofstream(path("long.scn")) << "seed 1\n# " << std::string(5000, 'x') << "\n"; }
  EXPECT_NE(refusal(path("long.scn")).find("line 2: longer than 4096 bytes"), std::string::npos);
  EXPECT_NE(refusal(path("missing.scn")).find("cannot read scenario file"), std::string::npos);
}

TEST_F(ScenarioLimits, FaultAmountsTimesPositionsAndAnglesAreRangeChecked) {
  struct Case {
    const char* text;
    const char* why;
  };
  const Case cases[] = {
      {"fault 0.5 noise 1e12\n", "fault noise amount must be a whole number 0..1000000 bytes"},
      {"fault 0.5 noise 2.5\n", "whole number"},
      {"fault 0.5 drop 1e9\n", "fault drop amount must be a whole number 0..100000000 bytes"},
      {"fault 0.5 truncate 1e7\n", "0..1000000 records"},
      {"fault 0.5 corrupt -1\n", "0..1000000 records"},
      {"fault 0.5 stall 1e12\n", "fault stall amount must be 0..3600 seconds"},
      {"fault 0.5 hangup inf\n", "fault needs"},
      {"fault 0.5 wrongbaud 7200\n", "0..3600 seconds"},
      {"fault 1e300 noise 5\n", "fault time must be 0..1000000 s"},
      {"duration 1e12\n", "duration needs seconds 0..1000000"},
      {"key 0 1 1e12 0 0 0 0 0\n", "positions must be finite and within 1000 in"},
      {"key 0 1 1 0 0 1e300 0 0\n", "angles within 10000 degrees"},
      {"key 1e9 1 1 0 0 0 0 0\n", "time must be 0..1000000 s"},
      {"circle 1 0 0 0 1e9 1\n", "centre and radius must be finite"},
      {"circle 1 0 0 0 1 1e12\n", "period must be > 0 and at most 1000000 s"},
      {"button 1e10 0 1\n", "button time must be 0..1000000 s"},
      {"status 1 1 E 1e10\n", "status time and seconds must be 0..1000000"},
  };
  for (const Case& c : cases) {
    Scenario sc;
    std::string error;
    EXPECT_FALSE(parse_scenario(c.text, sc, error)) << c.text;
    EXPECT_NE(error.find(c.why), std::string::npos) << c.text << " -> " << error;
    EXPECT_EQ(error.rfind("line 1: ", 0), 0u) << error;
  }
  // The limits themselves are accepted.
  Scenario sc;
  std::string error;
  EXPECT_TRUE(parse_scenario(
      "fault 1 noise 1000000\nfault 1 drop 100000000\nfault 1 stall 3600\nfault 1 corrupt 1000000\n"
      "key 0 1 1000 -1000 0 10000 -90 0\n",
      sc, error))
      << error;
}

// Peak resident memory (KiB) of a child process that loads `file`.
long peak_kib_loading(const std::string& file) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const auto loaded = load_scenario_file(file);
    rusage usage{};
    ::getrusage(RUSAGE_SELF, &usage);
    const long kib = loaded ? usage.ru_maxrss : -1;
    std::ofstream(file + ".rss") << kib;
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  long kib = -1;
  std::ifstream(file + ".rss") >> kib;
  return kib;
}

TEST_F(ScenarioLimits, MemoryIsWhatTheScenarioHoldsNotTheFile) {
  {
    std::ofstream small(path("small.scn"));
    small << "seed 1\nkey 0 1 10 0 0 0 0 0\n";
    std::ofstream large(path("large.scn"));
    const std::string comment = "# " + std::string(1000, 'c') + "\n";
    while (large.tellp() < static_cast<std::streamoff>(15u << 20)) large << comment;
    large << "key 0 1 10 0 0 0 0 0\n";
  }
  const long small = peak_kib_loading(path("small.scn"));
  const long large = peak_kib_loading(path("large.scn"));
  ASSERT_GT(small, 0);
  ASSERT_GT(large, 0);
  EXPECT_LT(large - small, 4 * 1024)
      << "a 15 MiB file of comments took " << large - small << " KiB more than a two-line one";
}

TEST(ScenarioLimitsDevice, AnAbsurdNoiseAmountIsCountedNotGenerated) {
  Scenario sc;
  sc.faults.push_back({0.5, FaultKind::noise, 1e12});  // past the parser, built in code
  FastrakDeviceConfig config;
  config.reset_time_us = 0;
  FastrakDevice device(config, sc, 0);
  std::vector<std::byte> out;
  const auto start = std::chrono::steady_clock::now();
  device.advance(1'000'000, out);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  EXPECT_EQ(device.counters().faults[static_cast<std::size_t>(FaultKind::noise)], 1u);
  EXPECT_GT(device.counters().line_overflow, 999'000'000'000u);
}

}  // namespace
}  // namespace twister::sim
