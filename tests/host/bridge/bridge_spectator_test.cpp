// Issue 25 (label exhibit): spectator displays. A station (real SculptSession +
// StationLink) on a fake listening transport with spectator slots
// (tests/fakes/fake_link_listener.hpp) and the display's own BridgeApp on each wire:
//   - the main display and two spectators (one joining mid-stroke) end every stroke
//     with the station's mesh checksum; the late one catches the open stroke at once;
//   - a spectator that stops reading has its hands updates dropped (counted), then is
//     dropped, while the main display gets every live update (0 dropped, no gap);
//   - a spectator's command is refused with notice command_refused_spectator and
//     never reaches the session;
//   - a spectator displaces nobody; a main display's newcomer displaces only the main
//     display; with every slot taken a spectator is told busy;
//   - polling with spectators does not allocate.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <vector>

#include "bridge_app.hpp"
#include "fakes/fake_clock.hpp"
#include "fakes/fake_link_listener.hpp"
#include "fakes/memory_wire.hpp"
#include "session_harness.hpp"
#include "support/allocation_counter.hpp"
#include "support/station_link_buffers.hpp"
#include "twister/ports/log_sink.hpp"
#include "twister/station/station_link.hpp"

namespace twister::bridge {
namespace {

using session::test_support::kGrab0;
using session::test_support::z_turn;

// One display: its wire and its app (spectator or main).
struct Display {
  Display(test::FakeClock& clock, ports::LogSink& log, bool spectator)
      : end(wire, false), app(end, clock, nullptr, options(spectator), log) {}
  static BridgeOptions options(bool spectator) {
    BridgeOptions o;
    o.spectator = spectator;
    return o;
  }
  test::MemoryWire wire;
  test::MemoryLinkEnd end;
  BridgeApp app;
};

struct Rig {
  explicit Rig(std::size_t slots = 2, ports::TimestampUs stall_us = 5'000'000) : station(33) {
    buffers.size_for(station.mesh, slots);
    station::StationLinkOptions options;
    options.newcomers = &listener;
    options.spectators = &listener;
    options.max_spectators = slots;
    options.spectator_queues = buffers.queues;
    options.spectator_staging = buffers.staging;
    options.spectator_stall_us = stall_us;
    link = std::make_unique<station::StationLink>(listener, buffers.storage(),
                                                  station::StationLinkConfig{}, options);
    EXPECT_TRUE(link->start(*station.session).ok());
  }
  Display& add(bool spectator) {
    displays.push_back(std::make_unique<Display>(clock, log, spectator));
    return *displays.back();
  }
  // The display connects (the listener's newcomer) and the handshake runs.
  void join(Display& d) {
    listener.connect(d.wire);
    run(6);
  }
  // One station poll per round; every display that reads steps.
  void run(int rounds = 20) {
    for (int i = 0; i < rounds; ++i) {
      for (auto& d : displays) {
        if (!d->wire.up || !stalled(*d)) d->app.step();
      }
      link->poll(*station.session, station.now_us);
    }
  }
  bool stalled(const Display& d) const { return &d == stopped; }
  void tick() {
    (void)station.tick();
    clock.advance_us(10'000);
    run(2);
  }
  void stroke(double lift, int steps = 4) {
    station.hand(0, math::identity_frame({0, 0, 0}));
    station.button(kGrab0, true);
    tick();
    for (int k = 1; k <= steps; ++k) {
      station.hand(0, z_turn({0.1 * k / steps * 4, 0, lift * k}, 0.2 * k));
      tick();
    }
    station.button(kGrab0, false);
    tick();
  }

  ports::NullLogSink log;
  test::FakeClock clock;
  session::test_support::Station station;
  test::FakeListener listener;
  test::StationLinkBuffers buffers;
  std::unique_ptr<station::StationLink> link;
  std::vector<std::unique_ptr<Display>> displays;
  const Display* stopped = nullptr;  // a display that stopped reading
};

TEST(Spectators, MainAndTwoSpectatorsEndWithTheStationsChecksum) {
  Rig r;
  Display& main = r.add(false);
  Display& first = r.add(true);
  r.join(main);
  r.join(first);
  ASSERT_TRUE(main.app.ready());
  ASSERT_TRUE(first.app.ready());
  EXPECT_EQ(r.link->counters().spectators_now, 1u);
  r.stroke(0.02);
  r.run();
  // The second spectator joins while a stroke is open and sees it at once.
  Display& late = r.add(true);
  r.station.hand(0, math::identity_frame({0, 0, 0}));
  r.station.button(kGrab0, true);
  r.tick();
  r.station.hand(0, z_turn({0.05, 0, 0.03}, 0.3));
  r.tick();
  r.join(late);
  ASSERT_TRUE(late.app.ready());
  r.run();
  // The stroke's begin came at admission; once its mesh has gone, the hands go again
  // (unchanged: the hand stands still) and the stroke shows.
  EXPECT_TRUE(late.app.replica().live().active) << "the open stroke reached the late spectator";
  EXPECT_TRUE(first.app.replica().live().active);
  r.station.button(kGrab0, false);
  r.tick();
  for (int s = 0; s < 3; ++s) r.stroke(0.01 * (s + 1));
  r.run(60);
  const std::uint64_t want = r.station.mesh.checksum();
  for (const auto& d : r.displays) {
    EXPECT_EQ(d->app.replica().version(), r.link->mesh_version());
    EXPECT_EQ(d->app.replica().checksum(), want);
    EXPECT_EQ(d->app.replica().counters().checksum_mismatches, 0u);
  }
  EXPECT_EQ(r.link->counters().spectators_now, 2u);
  EXPECT_EQ(r.link->counters().displaced, 0u);
  const station::SpectatorCounters t = r.link->counters().spectators;
  EXPECT_EQ(t.admitted, 2u);
  EXPECT_GE(t.commits_sent, 6u);  // change sets, not full meshes, after the first
  EXPECT_EQ(t.commits_resent, 0u);
  EXPECT_EQ(t.live_dropped, 0u);
}

TEST(Spectators, AStalledSpectatorIsDroppedWhileTheMainDisplayMissesNothing) {
  Rig r(2);
  Display& main = r.add(false);
  Display& slow = r.add(true);
  slow.wire.capacity = 16 * 1024;  // its socket buffer
  r.join(main);
  r.join(slow);
  ASSERT_TRUE(slow.app.ready());
  r.run(40);
  r.stopped = &slow;  // it stops reading
  const std::uint64_t live_before = r.link->counters().live_sent;
  const std::uint64_t frames_before = main.app.replica().counters().live_frames;
  bool dropped_hands = false;
  for (int s = 0; s < 100 && r.link->counters().spectators.dropped == 0; ++s) {
    r.stroke(0.002, 20);
    dropped_hands = dropped_hands || r.link->spectator(0).counters.live_dropped > 0;
  }
  const station::StationLinkCounters& c = r.link->counters();
  std::printf(
      "stalled spectator: %llu hands updates dropped, %llu commits resent as full sends, "
      "dropped: %llu; main display: %llu hands updates sent, %llu received, %llu dropped\n",
      static_cast<unsigned long long>(c.spectators.live_dropped),
      static_cast<unsigned long long>(c.spectators.commits_resent),
      static_cast<unsigned long long>(c.spectators.dropped),
      static_cast<unsigned long long>(c.live_sent - live_before),
      static_cast<unsigned long long>(main.app.replica().counters().live_frames - frames_before),
      static_cast<unsigned long long>(c.live_dropped));
  EXPECT_TRUE(dropped_hands) << "the slow spectator's hands updates were dropped and counted";
  EXPECT_GT(c.spectators.live_dropped, 0u);
  EXPECT_GT(c.spectators.commits_resent, 0u);  // commits that found no room: a full send due
  EXPECT_EQ(c.spectators.dropped, 1u);
  EXPECT_EQ(c.spectators_now, 0u);
  EXPECT_FALSE(r.link->spectator(0).open);
  // The main display: every live update sent and received, none dropped.
  EXPECT_EQ(c.live_dropped, 0u);
  EXPECT_EQ(main.app.replica().counters().live_frames - frames_before, c.live_sent - live_before);
  EXPECT_EQ(main.app.replica().counters().live_missed, 0u);
  EXPECT_EQ(main.app.replica().checksum(), r.station.mesh.checksum());
}

TEST(Spectators, ASpectatorsCommandIsRefusedWithANotice) {
  Rig r;
  Display& main = r.add(false);
  r.join(main);
  test::MemoryWire wire;
  test::MemoryLinkEnd end(wire, false);
  r.listener.connect(wire);
  const auto send = [&end](const auto& m) {
    std::vector<std::byte> f(link::kMaxFrameBytes);
    const auto n = link::encode_frame(m, f);
    ASSERT_TRUE(n.ok());
    ASSERT_EQ(*end.send(std::span<const std::byte>(f).first(*n)), *n);
  };
  send(link::Hello{link::Role::bridge, link::kHelloSpectator, 0, 0, {}});
  r.run(10);
  ASSERT_EQ(r.link->counters().spectators_now, 1u);
  send(link::Command{link::CommandKind::undo, 0});
  r.run(10);
  link::LinkDecoder decoder;
  std::vector<std::byte> buf(1 << 20);
  bool notice = false;
  for (;;) {
    const auto n = end.receive(buf);
    if (!n.ok() || *n == 0) break;
    for (std::size_t i = 0; i < *n; ++i) {
      if (const auto m = decoder.process(buf[i]); m.ok()) {
        if (const auto* k = std::get_if<link::Notice>(*m)) {
          notice = notice || k->code == link::NoticeCode::command_refused_spectator;
        }
      }
    }
  }
  EXPECT_TRUE(notice);
  EXPECT_EQ(r.link->counters().spectators.commands_refused, 1u);
  EXPECT_EQ(r.link->counters().commands, 0u);  // nothing reached the session
}

TEST(Spectators, DisplaceNobodyAndAreToldBusyWhenEverySlotIsTaken) {
  Rig r(2);
  Display& main = r.add(false);
  r.join(main);
  Display& a = r.add(true);
  Display& b = r.add(true);
  r.join(a);
  r.join(b);
  EXPECT_TRUE(main.app.ready());
  EXPECT_EQ(main.app.counters().displaced, 0u);
  EXPECT_EQ(r.link->counters().displaced, 0u);
  Display& c = r.add(true);
  r.join(c);
  EXPECT_FALSE(c.app.ready());  // told busy and closed (the fake's wire goes down with it)
  EXPECT_EQ(r.link->counters().refused.full, 1u);
  EXPECT_EQ(r.link->counters().refused.errors(), 0u);
  // A second main display displaces the first, never the spectators.
  Display& next = r.add(false);
  r.join(next);
  EXPECT_TRUE(next.app.ready());
  EXPECT_EQ(main.app.counters().displaced, 1u);
  EXPECT_TRUE(a.app.ready());
  EXPECT_TRUE(b.app.ready());
  EXPECT_EQ(r.link->counters().spectators_now, 2u);
  // A spectator that leaves frees its slot for the next one.
  a.wire.cut();
  r.run(4);
  EXPECT_EQ(r.link->counters().spectators.left, 1u);
  Display& d = r.add(true);
  r.join(d);
  EXPECT_TRUE(d.app.ready());
  EXPECT_EQ(r.link->counters().spectators_now, 2u);
}

// A serial line has one fixed far end and no slots: a --spectator display there is
// admitted as a read-only main display (its commands refused with the notice).
TEST(Spectators, OnAPlainPortASpectatorIsAReadOnlyMainDisplay) {
  session::test_support::Station station(9);
  test::MemoryWire wire;
  test::MemoryLinkEnd station_end(wire, true);
  std::vector<float> x(station.mesh.vertex_capacity()), y(x.size()), z(x.size());
  std::vector<std::uint32_t> idx(3 * station.mesh.triangle_capacity());
  std::vector<std::byte> out(8 * link::kMaxFrameBytes);
  station::StationLink link(station_end, station::StationLinkStorage{x, y, z, idx, out},
                            station::StationLinkConfig{});
  ASSERT_TRUE(link.start(*station.session).ok());
  ports::NullLogSink log;
  test::FakeClock clock;
  test::MemoryLinkEnd bridge_end(wire, false);
  BridgeApp app(bridge_end, clock, nullptr, Display::options(true), log);
  for (int i = 0; i < 20; ++i) {
    app.step();
    link.poll(*station.session, station.now_us);
  }
  ASSERT_TRUE(app.ready());
  EXPECT_TRUE(link.admitted());
  EXPECT_EQ(app.replica().checksum(), station.mesh.checksum());
  test::MemoryLinkEnd raw(wire, false);
  std::vector<std::byte> f(link::kMaxFrameBytes);
  const auto n = link::encode_frame(link::Command{link::CommandKind::undo, 0}, f);
  ASSERT_TRUE(n.ok());
  ASSERT_EQ(*raw.send(std::span<const std::byte>(f).first(*n)), *n);
  for (int i = 0; i < 5; ++i) {
    link.poll(*station.session, station.now_us);
    app.step();
  }
  EXPECT_EQ(link.counters().commands, 0u);
  EXPECT_EQ(link.counters().spectators.commands_refused, 1u);
  bool shown = false;
  for (const auto& k : app.replica().notices()) {
    shown = shown || k.notice.code == link::NoticeCode::command_refused_spectator;
  }
  EXPECT_TRUE(shown);
}

TEST(Spectators, PollDoesNotAllocate) {
  Rig r(2);
  Display& main = r.add(false);
  Display& a = r.add(true);
  Display& b = r.add(true);
  r.join(main);
  r.join(a);
  r.join(b);
  r.run(40);
  session::test_support::Station& s = r.station;
  s.hand(0, math::identity_frame({0, 0, 0}));
  s.button(kGrab0, true);
  (void)s.tick();
  for (int k = 1; k <= 5; ++k) {
    s.hand(0, z_turn({0, 0, 0.01 * k}, 0.1 * k));
    (void)s.tick();
    EXPECT_NO_ALLOCATIONS(r.link->poll(*s.session, s.now_us));
    r.run(2);
  }
  s.button(kGrab0, false);
  (void)s.tick();
  EXPECT_NO_ALLOCATIONS(r.link->poll(*s.session, s.now_us));
  r.run(20);
  for (const auto& d : r.displays) EXPECT_EQ(d->app.replica().checksum(), s.mesh.checksum());
}

}  // namespace
}  // namespace twister::bridge
