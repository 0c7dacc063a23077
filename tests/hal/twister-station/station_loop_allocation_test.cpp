// The station program's steady state allocates nothing. The REAL loop: the station
// assembled from a station.toml (simulator backend in virtual time, scripted
// two-hand strokes with button presses, the deploy sphere, a journal file, a
// display link on a Unix socket), StationLoop passes with events logged at info
// level, and a bridge-side peer in its own thread (twister-bridge's BridgeApp,
// headless: it says hello, decodes every frame, keeps the replica and asks for
// resends). After the warm-up (tracker start-up), every pass of >= 10 s of
// simulated time, in which four strokes commit, is counted: 0 allocations on the
// station's thread (the counter is per thread; the peer's thread does not count).
// Refinement is on (issue 13): every commit refines the sphere into its spare
// capacity, and the bridge still ends with the station's mesh.
#include <gtest/gtest.h>
#include <poll.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>

#include "allocation_counter.hpp"
#include "bridge_app.hpp"
#include "station_assembly.hpp"
#include "station_loop.hpp"
#include "twister/hal/logger.hpp"
#include "twister/hal/monotonic_clock.hpp"
#include "twister/hal/socket_link.hpp"

namespace twister::station_app {
namespace {

std::string temp_path(const char* name) {
  return "/tmp/twister_loop_alloc_" + std::to_string(::getpid()) + "_" + name;
}

StationFileConfig loop_config(const std::string& journal) {
  const std::string text = std::string("[station]\njournal = \"") + journal +
                           "\"\nmesh = \"" TWISTER_DEPLOY_DIR
                           "/sim_sphere.obj\"\nspare_vertices = 20000\n"
                           "[tracker]\nbackend = \"sim\"\n[tracker.sim]\nscenario_file = \"" +
                           TWISTER_SCENARIO_DIR
                           "/loop_strokes.scn\"\ntime = \"virtual\"\n"
                           "[buttons]\nbackend = \"sim\"\n"
                           "[sculpt]\nrefine = true\nrefine_threshold_m = 0.0005\n"
                           "[systemd]\nnotify = false\nwatchdog = false\n";
  const ConfigParseResult parsed = parse_station_config(text, "loop.toml");
  EXPECT_TRUE(parsed.ok()) << (parsed.errors.empty() ? "" : parsed.errors[0].to_string());
  return parsed.config;
}

// twister-bridge's loop body in a thread: reads, answers, keeps the replica. It
// waits on the socket's readiness; the test waits on `cv` for the version it needs.
class BridgePeer {
 public:
  explicit BridgePeer(const std::string& address)
      : link_({address, false, 20}), app_(link_, clock_, nullptr, {}, quiet_) {
    EXPECT_TRUE(link_.open());
    thread_ = std::thread([this] { run(); });
  }
  ~BridgePeer() {
    stop_ = true;
    thread_.join();
  }
  // Waits (up to `seconds`) until the replica holds `version`; its checksum then.
  bool wait_for_version(std::uint32_t version, double seconds, std::uint64_t& checksum) {
    std::unique_lock lock(mutex_);
    const bool ok = cv_.wait_for(lock, std::chrono::duration<double>(seconds),
                                 [&] { return version_ == version; });
    checksum = checksum_;
    return ok;
  }
  std::uint64_t commits() {
    std::lock_guard lock(mutex_);
    return commits_;
  }
  // Protocol 2 beside the mesh: hands updates received, missed, and the status.
  void live(std::uint64_t& frames, std::uint64_t& missed, bool& status) {
    std::lock_guard lock(mutex_);
    frames = live_frames_;
    missed = live_missed_;
    status = has_status_;
  }

 private:
  void run() {
    while (!stop_) {
      app_.step();
      {
        std::lock_guard lock(mutex_);
        version_ = app_.replica().version();
        checksum_ = app_.replica().checksum();
        commits_ = app_.replica().counters().commits;
        live_frames_ = app_.replica().counters().live_frames;
        live_missed_ = app_.replica().counters().live_missed;
        has_status_ = app_.replica().has_status();
      }
      cv_.notify_all();
      std::array<pollfd, 2> fds{};
      ::poll(fds.data(), link_.poll_fds(fds), 20);
    }
  }

  ports::NullLogSink quiet_;  // the peer's messages are not under test

  hal::SocketLink link_;
  hal::MonotonicClock clock_;
  bridge::BridgeApp app_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::condition_variable cv_;
  std::uint32_t version_ = 0;
  std::uint64_t checksum_ = 0;
  std::uint64_t commits_ = 0;
  std::uint64_t live_frames_ = 0;
  std::uint64_t live_missed_ = 0;
  bool has_status_ = false;
  std::thread thread_;
};

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(StationLoopAllocation, SteadyStateWithStrokesButtonsLinkAndLogAllocatesNothing) {
  const std::string journal = temp_path("journal.bin");
  const std::string log_path = temp_path("log.txt");
  const std::string address = "unix:" + temp_path("link.sock");
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
  const StationFileConfig config = loop_config(journal);
  auto assembled = assemble_station(config, {TWISTER_DEPLOY_DIR, address});
  ASSERT_TRUE(assembled) << assembled.error().message;
  StationParts& parts = **assembled;
  ASSERT_NE(parts.backends.virtual_clock, nullptr);

  BridgePeer peer(address);
  ASSERT_TRUE(parts.display.wait_for_peer(*parts.core, 10.0));

  FILE* log_file = std::fopen(log_path.c_str(), "w");
  ASSERT_NE(log_file, nullptr);
  hal::Logger log({"twister-station", hal::LogLevel::info, false, ::fileno(log_file)});
  StationLoop loop(*parts.core, parts.backends, parts.display, log,
                   make_loop_config(config, 0.0, parts.backends));
  ports::Clock& clock = *parts.backends.clock;
  const ports::TimestampUs t0 = clock.now_us();
  ASSERT_TRUE(loop.start());

  // Warm-up: the tracker session configures the simulated unit (commands allocate
  // in the device model) and starts streaming at ~1.9 s.
  while (clock.now_us() - t0 < 2'500'000) ASSERT_TRUE(loop.step());
  ASSERT_TRUE(parts.core->tracker_session().streaming());
  const std::uint64_t passes_before = loop.passes();
  const ports::TimestampUs measured_from = clock.now_us();
  std::size_t allocations = 0;
  {
    test::AllocationCounter counter;
    while (loop.step()) {
    }
    allocations = counter.count();
  }
  const double simulated_s = static_cast<double>(clock.now_us() - measured_from) / 1e6;
  const std::uint64_t passes = loop.passes() - passes_before;
  const auto& counters = parts.core->counters();
  EXPECT_EQ(allocations, 0u);
  EXPECT_EQ(loop.stop_reason(), StopReason::end_of_run);
  EXPECT_GE(simulated_s, 10.0);
  // Four two-hand strokes: one journal record each, counted once each (issue 12:
  // strokes count as strokes, not hands).
  EXPECT_EQ(parts.core->journal_records(), 4u);
  EXPECT_EQ(counters.events.strokes_committed, 4u);
  EXPECT_EQ(counters.events.strokes_cancelled, 0u);
  EXPECT_EQ(counters.events.refined_commits, 4u);
  EXPECT_GT(parts.core->mesh().vertex_count(), 266u);
  std::printf(
      "steady state: %.1f s simulated, %llu passes, %u strokes committed, %zu "
      "allocations\n",
      simulated_s, static_cast<unsigned long long>(passes), parts.core->journal_records(),
      allocations);

  ASSERT_TRUE(loop.finish().ok());
  // The bridge side holds the station's final mesh, built from the link's commits.
  const auto* link = parts.display.counters();
  ASSERT_NE(link, nullptr);
  EXPECT_GE(link->commits_sent + link->full_sends, 5u);  // first full mesh + 4 commits
  EXPECT_GT(link->live_sent, 0u);
  std::uint64_t bridge_checksum = 0;
  EXPECT_TRUE(peer.wait_for_version(5, 10.0, bridge_checksum));
  EXPECT_EQ(bridge_checksum, parts.core->mesh().checksum());
  // The v2 stream in the measured passes: hands at the tracker rate whether or not
  // they grab (virtual time outruns the peer, so some may be dropped), and the status.
  EXPECT_GT(link->live_sent, 100u);
  std::uint64_t frames = 0;
  std::uint64_t missed = 0;
  bool status = false;
  peer.live(frames, missed, status);
  EXPECT_GT(frames, 100u);
  EXPECT_TRUE(status);
  std::fclose(log_file);
  const std::string lines = read_file(log_path);
  EXPECT_NE(lines.find("twister-station: stroke: hand 0 committed as journal record 3"),
            std::string::npos)
      << lines;
  ::unlink(log_path.c_str());
  ::unlink(journal.c_str());
  ::unlink((journal + ".ckpt").c_str());  // its checkpoint
}

}  // namespace
}  // namespace twister::station_app
