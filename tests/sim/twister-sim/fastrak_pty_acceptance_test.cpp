// Acceptance (issue 5): each fault kind injected by the simulator on a real PTY; the
// FastrakSession on TermiosByteStream recovers by itself, no invalid pose reaches the
// consumer (every pose lies on the scenario's trajectory and converts to a proper
// frame), and the counters show what happened. Real time: about 6 s per fault kind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <thread>

#include "device_server.hpp"
#include "support/poll_wait.hpp"
#include "twister/hal/monotonic_clock.hpp"
#include "twister/hal/termios_byte_stream.hpp"
#include "twister/sim/fastrak_device.hpp"
#include "twister/tracker/fastrak_session.hpp"
#include "twister/tracker/pose_conversion.hpp"

namespace twister::sim {
namespace {

using tracker::Format;
using tracker::Item;
using tracker::OutputList;

struct FaultCase {
  const char* name;
  const char* fault;
  Format format;
  double fault_end_s;  // when the injected condition is over
};

// Names the case in test output instead of dumping its bytes.
void PrintTo(const FaultCase& c, std::ostream* os) { *os << c.name; }

class FastrakPtyAcceptance : public ::testing::TestWithParam<FaultCase> {};

TEST_P(FastrakPtyAcceptance, SessionRecoversAndNoInvalidPoseReachesTheConsumer) {
  const FaultCase& fc = GetParam();
  // Slow, known trajectories: x grows 1 in/s on station 1; station 2 turns in azimuth.
  const std::string text = std::string("receivers 2\nseed 11\n") +
                           "key 0 1 10 0 0 0 0 0\nkey 60 1 70 -30 6 60 30 0\n" +
                           "key 0 2 15 5 0 0 0 0\nkey 60 2 15 5 0 -120 0 0\n" + fc.fault + "\n";
  Scenario sc;
  std::string err;
  ASSERT_TRUE(parse_scenario(text, sc, err)) << err;
  FastrakDeviceConfig dev;
  dev.reset_time_us = 200'000;
  FastrakDevice device(dev, sc, 0);
  ServeOptions opts;
  opts.link = ::testing::TempDir() + "fastrak_acc_" + std::to_string(::getpid()) + "_" + fc.name;
  DeviceServer server(device, opts);
  const hal::Expected<void> started = server.start();
  ASSERT_TRUE(started) << started.error().message;
  // The simulator runs in its own thread; stopped and joined even when an assertion
  // returns early.
  struct SimThread {
    DeviceServer& server;
    std::atomic<bool> stop{false};
    std::thread thread;
    explicit SimThread(DeviceServer& s)
        : server(s), thread([this] {
            while (!stop.load() && server.step(1)) {
            }
          }) {}
    ~SimThread() { join(); }
    void join() {
      stop = true;
      if (thread.joinable()) thread.join();
    }
  } sim(server);

  tracker::FastrakSessionConfig cfg;
  cfg.protocol.format = fc.format;
  for (int s = 0; s < 2; ++s) {
    cfg.protocol.stations[static_cast<std::size_t>(s)].enabled = true;
    cfg.protocol.stations[static_cast<std::size_t>(s)].list =
        fc.format == Format::binary
            ? OutputList::of({Item::position, Item::quaternion, Item::crlf})
            : OutputList::of({Item::position, Item::dcm_x, Item::dcm_y, Item::dcm_z, Item::space});
  }
  cfg.ladder_char_pause_us = 20'000;
  cfg.reset_wait_us = 400'000;
  cfg.settle_us = 50'000;
  cfg.reply_timeout_us = 300'000;
  cfg.command_pause_us = 50'000;  // the simulator's default command times (40 ms)
  cfg.backoff.initial_us = 100'000;
  hal::TermiosByteStream port({opts.link, 115200, hal::FlowControl::none});
  hal::MonotonicClock clock;
  tracker::FastrakSession session(port, clock, cfg);
  tracker::PoseConversion conv;
  conv.format = fc.format;

  std::size_t after_fault[2] = {0, 0};
  std::size_t total = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < deadline) {
    for (auto p = session.poll(); p.ok(); p = session.poll()) {
      ++total;
      const double t = static_cast<double>(server.now_us()) / 1e6;
      if (p->station == 1) {
        // On the path x = 10 + s, y = -s/2, z = s/10 (s = sample time), sampled no
        // later than now and at most 2 s earlier (scheduling lag on a loaded machine).
        const double s_time = p->position[0] - 10.0;
        ASSERT_LE(s_time, t + 0.05) << "t=" << t;
        ASSERT_GE(s_time, t - 2.0) << "t=" << t;
        ASSERT_NEAR(p->position[1], -s_time / 2.0, 0.02) << "t=" << t;
        ASSERT_NEAR(p->position[2], s_time / 10.0, 0.02) << "t=" << t;
      } else {
        ASSERT_EQ(p->station, 2);
        ASSERT_NEAR(p->position[0], 15.0, 0.02);
        ASSERT_NEAR(p->position[1], 5.0, 0.02);
      }
      auto frame = tracker::to_station_frame(*p, conv);
      ASSERT_TRUE(frame.ok());
      ASSERT_NEAR(glm::dot(glm::cross(frame->u, frame->v), frame->w), 1.0, 1e-9);
      if (t > fc.fault_end_s + 0.5) ++after_fault[p->station - 1];
    }
    if (after_fault[0] > 60 && after_fault[1] > 60) break;
    // As the station's loop: wake on input, or after the session's timer tick (its
    // command and reconnect timers need polling while the port is quiet or closed).
    if (!test::wait_ready(port, 5) && !port.is_open()) ::poll(nullptr, 0, 5);
  }
  sim.join();

  const auto& c = session.counters();
  const auto& pc = session.parser_counters();
  std::printf(
      "[pty %s] poses=%zu inits=%llu streams=%llu status_timeouts=%llu io=%llu "
      "silence=%llu garbage=%llu rejected=%llu resyncs=%llu dropped_bytes=%llu "
      "ptys=%llu\n",
      fc.name, total, (unsigned long long)c.inits, (unsigned long long)c.streams_started,
      (unsigned long long)c.status_timeouts, (unsigned long long)c.io_errors,
      (unsigned long long)c.silence_faults, (unsigned long long)c.garbage_faults,
      (unsigned long long)c.rejected_poses, (unsigned long long)pc.resyncs,
      (unsigned long long)pc.dropped_bytes, (unsigned long long)server.counters().ptys_opened);
  ::unlink(opts.link.c_str());
  EXPECT_GT(after_fault[0], 60u) << "station 1 did not come back";
  EXPECT_GT(after_fault[1], 60u) << "station 2 did not come back";
  EXPECT_TRUE(session.streaming());
  EXPECT_EQ(device.counters().faults[static_cast<std::size_t>(sc.faults[0].kind)], 1u);
  const std::string name = fc.name;
  if (name == "noise" || name == "drop" || name == "truncate") {
    EXPECT_GE(pc.resyncs, 1u);
    EXPECT_GT(pc.dropped_bytes, 0u);
  } else if (name == "stall") {
    EXPECT_EQ(c.silence_faults, 1u);
    EXPECT_GE(c.streams_started, 2u);
  } else if (name == "hangup") {
    EXPECT_GE(c.io_errors, 1u);
    EXPECT_EQ(server.counters().hangups, 1u);
    EXPECT_EQ(server.counters().ptys_opened, 2u);
    EXPECT_GE(c.streams_started, 2u);
  } else if (name == "wrongbaud") {
    EXPECT_GE(c.garbage_faults, 1u);
    EXPECT_GE(c.streams_started, 2u);
  }
}

INSTANTIATE_TEST_SUITE_P(
    EachFaultKind, FastrakPtyAcceptance,
    ::testing::Values(FaultCase{"noise", "fault 2 noise 400", Format::binary, 2.0},
                      FaultCase{"drop", "fault 2 drop 45", Format::binary, 2.0},
                      FaultCase{"truncate", "fault 2 truncate 6", Format::ascii, 2.1},
                      FaultCase{"stall", "fault 2 stall 2.5", Format::binary, 4.5},
                      FaultCase{"hangup", "fault 2 hangup 1", Format::binary, 3.0},
                      FaultCase{"wrongbaud", "fault 2 wrongbaud 2.5", Format::ascii, 4.5}),
    [](const auto& param_info) { return std::string(param_info.param.name); });

}  // namespace
}  // namespace twister::sim
