// The station (core Station: Fastrak session, hands, sculpt session, journal) on the
// in-process simulator, in virtual time, with every fault kind the simulator injects,
// in-record corruption and a baud mismatch included: it recovers by itself (both
// hands valid again at the end) and never applies a pose that failed validation.
// Every applied hand pose is checked against the scenario's truth after every poll:
// exactly on it for framing faults; for in-record corruption within the continuity
// limits (a corrupted value that stays within them cannot be told from noise,
// docs/fastrak-protocol.md §6 pitfall 14). Counters are printed per fault kind.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <memory>
#include <string>

#include "fakes/fake_button_source.hpp"
#include "fakes/fake_clock.hpp"
#include "fakes/fake_storage.hpp"
#include "twister/sim/sim_fastrak_stream.hpp"
#include "twister/station/station.hpp"

namespace twister::sim {
namespace {

using tracker::Format;
using tracker::Item;
using tracker::OutputList;

constexpr double kInch = 0.0254;
constexpr std::size_t kGrid = 11;
using Mesh = mesh::MeshWithStorage<kGrid * kGrid, 2 * kGrid * kGrid>;
using Work = session::SculptStorageArrays<kGrid * kGrid, kGrid * kGrid, 2048, 8>;

struct FaultCase {
  const char* name;
  const char* faults;
  Format format;
};
void PrintTo(const FaultCase& c, std::ostream* os) { *os << c.name; }

station::StationConfig station_config(Format format) {
  station::StationConfig c{};
  auto& p = c.session.protocol;
  p.format = format;
  for (std::size_t s = 0; s < 2; ++s) {
    p.stations[s].enabled = true;
    p.stations[s].list = OutputList::of({Item::position, Item::quaternion, Item::crlf});
  }
  c.session.ladder_char_pause_us = 20'000;
  c.session.reset_wait_us = 600'000;
  c.session.settle_us = 50'000;
  c.session.reply_timeout_us = 300'000;
  c.session.command_pause_us = 50'000;
  c.session.silence_timeout_us = 500'000;
  c.session.backoff.initial_us = 100'000;
  c.conversion.format = format;
  return c;
}

// Station 1 moves 1 in/s along x (and turns); station 2 rests, turned.
constexpr const char* kTrack =
    "receivers 2\nseed 5\nkey 0 1 10 -4 2 10 5 0\nkey 30 1 40 -4 2 70 5 30\n"
    "key 0 2 12 4 -3 -40 10 20\n";

class StationOnSim : public ::testing::TestWithParam<FaultCase> {};

TEST_P(StationOnSim, RecoversAndAppliesOnlyValidatedPoses) {
  const FaultCase& fc = GetParam();
  Scenario sc;
  std::string err;
  ASSERT_TRUE(parse_scenario(std::string(kTrack) + fc.faults, sc, err)) << err;
  test::FakeClock clock(1'000'000);
  FastrakDeviceConfig dev;
  dev.packed16 = fc.format == Format::binary16;
  SimFastrakStream stream(clock, dev, sc);
  test::FakeButtonSource buttons;
  test::FakeStorage storage;
  auto mesh = std::make_unique<Mesh>();
  auto work = std::make_unique<Work>();
  const station::StationConfig cfg = station_config(fc.format);
  station::Station st(stream, buttons, clock, storage, *mesh, work->spans(), cfg);
  ASSERT_TRUE(st.start().ok());
  const tracker::ContinuityLimits& lim = cfg.session.continuity;

  // Per hand: when its applied pose last changed; the worst distance of an applied
  // pose from the truth, and from the truth plus the continuity limits' reach.
  std::array<double, 2> last_change_s{};
  std::array<glm::dvec3, 2> last_origin{};
  double worst_off_in = 0.0, worst_excess_in = -1e9;
  double last_invalid_s = 0.0;  // the faults start at 3 s: recovery ends here
  std::uint64_t applied = 0;
  for (int tick = 0; tick < 14'000; ++tick) {  // 14 s in 1 ms steps
    ASSERT_TRUE(st.poll().ok());
    clock.advance_us(1'000);
    const double now_s = stream.device().scenario_time_s(clock.now_us());
    if (!st.hand_valid(0, clock.now_us()) || !st.hand_valid(1, clock.now_us())) {
      last_invalid_s = now_s;
    }
    for (std::uint8_t h = 0; h < 2; ++h) {
      const glm::dvec3 o = st.hand_pose(h).origin;
      if (o == last_origin[h] || !st.hand_valid(h, clock.now_us())) continue;
      ++applied;
      // Truth: the hand at any time in the last 50 ms (records are that fresh).
      double best = 1e9;
      for (double t = now_s - 0.05; t <= now_s; t += 0.001) {
        const HandSample s = sample(sc, h + 1, t);
        const glm::dvec3 truth(s.position_in[0], s.position_in[1], s.position_in[2]);
        best = std::min(best, glm::length(o / kInch - truth));
      }
      const double dt = std::max(now_s - last_change_s[h], 8'333e-6);
      const double reach = lim.max_speed_in_s * dt + lim.position_slack_in;
      worst_off_in = std::max(worst_off_in, best);
      worst_excess_in = std::max(worst_excess_in, best - reach);
      last_change_s[h] = now_s;
      last_origin[h] = o;
    }
  }
  const bool valid_at_end = st.hand_valid(0, clock.now_us()) && st.hand_valid(1, clock.now_us());
  const auto& c = st.tracker_session().counters();
  const auto& pc = st.tracker_session().parser_counters();
  const auto& d = stream.device().counters();
  std::printf(
      "[station %s] applied=%llu streams=%llu silence=%llu garbage=%llu io=%llu "
      "parser_rejects=%llu jump_rejects=%llu resyncs=%llu corrupted=%llu misclock_junk=%llu "
      "station_pose_errors=%llu worst_off=%.3f in hands_last_invalid=%.2f s\n",
      fc.name, static_cast<unsigned long long>(applied),
      static_cast<unsigned long long>(c.streams_started),
      static_cast<unsigned long long>(c.silence_faults),
      static_cast<unsigned long long>(c.garbage_faults),
      static_cast<unsigned long long>(c.io_errors),
      static_cast<unsigned long long>(c.rejected_poses),
      static_cast<unsigned long long>(c.jump_rejects), static_cast<unsigned long long>(pc.resyncs),
      static_cast<unsigned long long>(d.corrupted_records),
      static_cast<unsigned long long>(d.misclock_junk),
      static_cast<unsigned long long>(st.counters().input.pose_errors), worst_off_in,
      last_invalid_s);
  EXPECT_TRUE(valid_at_end) << "not recovered";
  EXPECT_TRUE(st.tracker_session().streaming());
  const std::string name = fc.name;
  if (name.rfind("corrupt", 0) == 0) {
    // Nothing beyond the limits is applied: no pose farther from the truth than the
    // hand could have moved since its previous pose.
    EXPECT_LE(worst_excess_in, 0.0);
    EXPECT_GT(c.rejected_poses + c.jump_rejects, 0u);
    EXPECT_EQ(pc.resyncs, 0u);  // framing never saw it
  } else {
    EXPECT_LT(worst_off_in, 0.02);  // framing faults: only true poses
  }
}

INSTANTIATE_TEST_SUITE_P(
    EveryFaultKind, StationOnSim,
    ::testing::Values(FaultCase{"noise", "fault 3 noise 500\n", Format::binary},
                      FaultCase{"drop", "fault 3 drop 200\n", Format::binary},
                      FaultCase{"drop_huge", "fault 3 drop 1000000\n", Format::binary},
                      FaultCase{"truncate", "fault 3 truncate 10\n", Format::ascii},
                      FaultCase{"stall", "fault 3 stall 2\n", Format::binary},
                      FaultCase{"hangup", "fault 3 hangup 1.5\n", Format::binary},
                      FaultCase{"wrongbaud", "fault 3 wrongbaud 3\n", Format::ascii},
                      FaultCase{"status", "status 3 1 E 2\nstatus 4 2 y 2\n", Format::ascii},
                      FaultCase{"corrupt_ascii", "fault 3 corrupt 400\n", Format::ascii},
                      FaultCase{"corrupt_binary", "fault 3 corrupt 400\n", Format::binary},
                      FaultCase{"corrupt_binary16", "fault 3 corrupt 400\n", Format::binary16}),
    [](const auto& param_info) { return std::string(param_info.param.name); });

}  // namespace
}  // namespace twister::sim
