// Issue 20 (label architecture): the bridge takes its time from the ports::Clock
// its composition root injects, so a fake clock drives everything time-dependent
// in it, deterministically: the hello retry while the station is silent at
// connect, the new hello after a silent station, the HUD's hands rate, and the
// displaced display's back-off (2 s doubling to 60 s, yielding hellos).
// Nothing here depends on how long the test takes to run.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <span>
#include <vector>

#include "bridge_app.hpp"
#include "fakes/fake_clock.hpp"
#include "fakes/memory_wire.hpp"
#include "twister/link/link_codec.hpp"

namespace twister::bridge {
namespace {

constexpr ports::TimestampUs kMs = 1000;

// Counts warnings about a silent station.
struct SilenceLog final : ports::LogSink {
  int silences = 0;
  bool do_enabled(ports::LogLevel) const override { return true; }
  void do_write(ports::LogLevel level, const char*, const char* format,
                std::span<const ports::LogArg>) override {
    if (level == ports::LogLevel::warning && std::strstr(format, "silent") != nullptr) ++silences;
  }
};

// A BridgeApp on an in-memory wire whose station end the test scripts, on a clock
// that moves only when the test says.
struct ClockRig {
  explicit ClockRig(ports::TimestampUs start_us)
      : clock(start_us), bridge(bridge_end, clock, nullptr, {}, log) {}

  template <typename M>
  void station_sends(const M& m) {
    std::vector<std::byte> f(link::kMaxFrameBytes);
    const auto n = link::encode_frame(m, f);
    ASSERT_TRUE(n.ok());
    ASSERT_EQ(*station_end.send(std::span<const std::byte>(f.data(), *n)), *n);
  }
  void station_hello() {
    link::Hello hello;
    hello.role = link::Role::station;
    station_sends(hello);
  }
  void station_hands(std::uint16_t sequence) {
    link::Hands hands;
    hands.sequence = sequence;
    station_sends(hands);
  }
  std::uint64_t hellos() const { return bridge.counters().hellos_sent; }
  // The hellos the bridge sent since the last call, decoded at the station's end.
  std::vector<link::Hello> bridge_hellos() {
    std::vector<link::Hello> got;
    std::array<std::byte, 4096> buf{};
    for (auto n = station_end.receive(buf); n.ok() && *n > 0; n = station_end.receive(buf)) {
      for (std::size_t i = 0; i < *n; ++i) {
        if (const auto m = decoder.process(buf[i]); m.ok()) {
          if (const auto* h = std::get_if<link::Hello>(*m)) got.push_back(*h);
        }
      }
    }
    return got;
  }

  test::MemoryWire wire;
  test::MemoryLinkEnd station_end{wire, true};
  test::MemoryLinkEnd bridge_end{wire, false};
  link::LinkDecoder decoder;
  SilenceLog log;
  test::FakeClock clock;
  BridgeApp bridge;
};

TEST(BridgeClock, HelloRetryAndSilenceFollowTheInjectedClock) {
  ClockRig rig(5'000 * kMs);
  rig.bridge.step();  // connects and says hello
  ASSERT_TRUE(rig.bridge.connected());
  EXPECT_EQ(rig.hellos(), 1u);
  // However many steps, no time passes unless the clock moves.
  for (int i = 0; i < 1000; ++i) rig.bridge.step();
  EXPECT_EQ(rig.hellos(), 1u);
  // The station stays silent: hello again after exactly hello_retry_ms (1000).
  rig.clock.advance_us(999 * kMs);
  rig.bridge.step();
  EXPECT_EQ(rig.hellos(), 1u);
  rig.clock.advance_us(1 * kMs);
  rig.bridge.step();
  EXPECT_EQ(rig.hellos(), 2u);

  // The station answers: ready. Then it falls silent; after silence_ms (3000) of
  // the clock the bridge says hello again (a new session) and warns once.
  rig.station_hello();
  rig.bridge.step();
  ASSERT_TRUE(rig.bridge.ready());
  rig.clock.advance_us(2'999 * kMs);
  rig.bridge.step();
  EXPECT_EQ(rig.hellos(), 2u);
  EXPECT_TRUE(rig.bridge.ready());
  EXPECT_EQ(rig.log.silences, 0);
  rig.clock.advance_us(1 * kMs);
  rig.bridge.step();
  EXPECT_EQ(rig.hellos(), 3u);
  EXPECT_FALSE(rig.bridge.ready());  // until the station answers the new hello
  EXPECT_EQ(rig.log.silences, 1);
}

TEST(BridgeClock, HudHandsRateCountsUpdatesPerSecondOfTheClock) {
  ClockRig rig(10'000 * kMs);
  rig.bridge.step();
  rig.station_hello();
  rig.bridge.step();
  ASSERT_TRUE(rig.bridge.ready());
  // Seven hands updates in second 10 of the clock (at 10.2 s).
  rig.clock.advance_us(200 * kMs);
  for (std::uint16_t s = 1; s <= 7; ++s) rig.station_hands(s);
  rig.bridge.step();
  // During second 10 the rate is that of second 9: none.
  EXPECT_EQ(rig.bridge.hud_input().hands_rate_hz, 0.0);
  // In second 11 the HUD shows second 10's count, whatever the wall clock did.
  rig.clock.advance_us(800 * kMs);
  EXPECT_EQ(rig.bridge.hud_input().hands_rate_hz, 7.0);
  rig.clock.advance_us(999 * kMs);
  EXPECT_EQ(rig.bridge.hud_input().hands_rate_hz, 7.0);
  // Two updates in second 12; a second later the rate says 2.
  rig.clock.advance_us(1 * kMs);
  rig.station_hands(8);
  rig.station_hands(9);
  rig.bridge.step();
  EXPECT_EQ(rig.bridge.hud_input().hands_rate_hz, 0.0);  // second 11 had none
  rig.clock.advance_us(1'000 * kMs);
  EXPECT_EQ(rig.bridge.hud_input().hands_rate_hz, 2.0);
  // A second with nothing after it: the rate falls to 0.
  rig.clock.advance_us(1'000 * kMs);
  EXPECT_EQ(rig.bridge.hud_input().hands_rate_hz, 0.0);
  EXPECT_EQ(rig.bridge.counters().hands_busiest_second, 7u);
}

TEST(BridgeClock, ADisplacedDisplayTriesAgainYieldingWithBackOffUntilTheLinkIsFree) {
  ClockRig rig(1'000 * kMs);
  rig.bridge.step();
  rig.station_hello();
  rig.bridge.step();
  ASSERT_TRUE(rig.bridge.ready());
  ASSERT_EQ(rig.bridge_hellos().size(), 1u);
  // Another display took the link.
  rig.station_sends(link::Bye{link::ByeReason::displaced});
  rig.bridge.step();
  EXPECT_TRUE(rig.bridge.yielding());
  EXPECT_FALSE(rig.bridge.ready());
  EXPECT_EQ(rig.bridge.link_view(), LinkView::displaced);
  EXPECT_EQ(rig.bridge.stopped(), BridgeStop::none);
  // Each try comes exactly when due, a yielding hello, and each `busy` doubles
  // the wait: 2, 4, 8, 16, 32, then 60 s at most.
  for (const std::int64_t wait_s : {2, 4, 8, 16, 32, 60, 60}) {
    rig.clock.advance_us((wait_s * 1000 - 1) * kMs);
    for (int i = 0; i < 100; ++i) rig.bridge.step();
    EXPECT_TRUE(rig.bridge_hellos().empty()) << "too early, wait " << wait_s << " s";
    rig.clock.advance_us(1 * kMs);
    rig.bridge.step();
    const auto hellos = rig.bridge_hellos();
    ASSERT_EQ(hellos.size(), 1u) << "wait " << wait_s << " s";
    EXPECT_EQ(hellos[0].flags & link::kHelloYield, link::kHelloYield);
    rig.station_sends(link::Bye{link::ByeReason::busy});
    rig.bridge.step();
  }
  EXPECT_EQ(rig.bridge.counters().busy, 7u);
  EXPECT_EQ(rig.bridge.counters().displaced, 1u);
  // The link is free at the next try: the station answers, the display is back
  // and its later hellos no longer yield.
  rig.clock.advance_us(60'000 * kMs);
  rig.bridge.step();
  ASSERT_EQ(rig.bridge_hellos().size(), 1u);
  rig.station_hello();
  rig.bridge.step();
  EXPECT_TRUE(rig.bridge.ready());
  EXPECT_FALSE(rig.bridge.yielding());
  EXPECT_EQ(rig.bridge.link_view(), LinkView::connected);
  rig.clock.advance_us(3'000 * kMs);  // silence: a new session's hello
  rig.bridge.step();
  const auto later = rig.bridge_hellos();
  ASSERT_EQ(later.size(), 1u);
  EXPECT_EQ(later[0].flags & link::kHelloYield, 0);
}

}  // namespace
}  // namespace twister::bridge
