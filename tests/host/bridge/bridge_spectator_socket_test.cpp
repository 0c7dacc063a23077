// Issue 25 (label exhibit): spectator displays over real sockets with a pre-shared
// key. A station (SculptSession + StationLink on a listening hal::SocketLink with
// spectator slots) and three twister-bridge BridgeApps on TCP loopback: the main
// display and two --spectator displays, each authenticated with the same key, end
// every stroke with the station's checksum; a spectator with the wrong key is refused
// (unauthorised) like a main display would be; nobody is displaced.
#include <gtest/gtest.h>
#include <poll.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "bridge_app.hpp"
#include "session_harness.hpp"
#include "support/station_link_buffers.hpp"
#include "twister/hal/monotonic_clock.hpp"
#include "twister/hal/socket_link.hpp"
#include "twister/hal/sodium_authenticator.hpp"
#include "twister/station/station_link.hpp"

namespace twister::bridge {
namespace {

using session::test_support::kGrab0;
using session::test_support::Station;
using session::test_support::z_turn;

hal::LinkKey key_of(std::uint8_t seed) {
  hal::LinkKey k{};
  for (std::size_t i = 0; i < k.size(); ++i) k[i] = static_cast<std::uint8_t>(seed + 5 * i);
  return k;
}

struct StationSide {
  explicit StationSide(const std::string& address) : socket({address, true, 0}), auth(key_of(3)) {
    EXPECT_TRUE(hal::SodiumAuthenticator::init());
    const auto opened = socket.open();
    EXPECT_TRUE(opened) << (opened ? "" : opened.error().message);
    buffers.size_for(station.mesh, 2);
    station::StationLinkOptions options;
    options.newcomers = &socket;
    options.authenticator = &auth;
    options.spectators = &socket;
    options.max_spectators = 2;
    options.spectator_queues = buffers.queues;
    options.spectator_staging = buffers.staging;
    link = std::make_unique<station::StationLink>(socket, buffers.storage(),
                                                  station::StationLinkConfig{}, options);
    EXPECT_TRUE(link->start(*station.session).ok());
  }
  void poll() {
    station.now_us += 1000;
    link->poll(*station.session, station.now_us);
  }

  Station station;
  hal::SocketLink socket;
  hal::SodiumAuthenticator auth;
  test::StationLinkBuffers buffers;
  std::unique_ptr<station::StationLink> link;
};

struct Display {
  Display(const std::string& address, const hal::LinkKey& key, bool spectator)
      : socket({address, false, 0}), auth(key) {
    BridgeOptions options;
    options.authenticator = &auth;
    options.spectator = spectator;
    app = std::make_unique<BridgeApp>(socket, clock, nullptr, options, log);
  }
  ports::NullLogSink log;
  hal::MonotonicClock clock;
  hal::SocketLink socket;
  hal::SodiumAuthenticator auth;
  std::unique_ptr<BridgeApp> app;
};

template <typename Done>
bool run(StationSide& s, const std::vector<Display*>& displays, int ms, Done done) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
  while (std::chrono::steady_clock::now() < until) {
    s.poll();
    for (Display* d : displays) d->app->step();
    if (done()) return true;
    std::array<pollfd, hal::PollSource::kMaxFds> fds{};
    ::poll(fds.data(), s.socket.poll_fds(fds), 2);
  }
  return false;
}

std::string address() { return "tcp:127.0.0.1:" + std::to_string(26000 + ::getpid() % 20000); }

TEST(SpectatorSockets, MainAndTwoAuthenticatedSpectatorsEndWithTheSameChecksum) {
  StationSide s(address());
  const hal::LinkKey key = key_of(3);
  Display main(address(), key, false);
  ASSERT_TRUE(run(s, {&main}, 3000, [&] { return main.app->replica().has_mesh(); }));
  Display one(address(), key, true);
  ASSERT_TRUE(run(s, {&main, &one}, 3000, [&] { return one.app->replica().has_mesh(); }));
  // The wrong key, a slot free: refused like a main display would be, nobody disturbed.
  const hal::LinkKey wrong = key_of(9);
  Display bad(address(), wrong, true);
  EXPECT_TRUE(
      run(s, {&main, &one, &bad}, 3000, [&] { return bad.app->stopped() != BridgeStop::none; }));
  EXPECT_EQ(bad.app->stopped(), BridgeStop::unauthorised);
  EXPECT_GE(s.link->counters().refused.unauthorised, 1u);
  EXPECT_EQ(s.link->counters().spectators_now, 1u);
  auto two_owner = std::make_unique<Display>(address(), key, true);
  Display& two = *two_owner;
  const std::vector<Display*> all{&main, &one, &two};
  ASSERT_TRUE(run(s, all, 5000, [&] { return two.app->replica().has_mesh(); }));
  EXPECT_EQ(s.link->counters().spectators_now, 2u);
  for (int k = 1; k <= 3; ++k) {
    s.station.hand(0, math::identity_frame({0, 0, 0}));
    s.station.button(kGrab0, true);
    (void)s.station.tick();
    (void)run(s, all, 20, [] { return false; });
    s.station.hand(0, z_turn({0.05 * k, 0, 0.02 * k}, 0.2 * k));
    (void)s.station.tick();
    (void)run(s, all, 20, [] { return false; });
    s.station.button(kGrab0, false);
    (void)s.station.tick();
  }
  const std::uint64_t want = s.station.mesh.checksum();
  EXPECT_TRUE(run(s, all, 5000, [&] {
    return main.app->replica().checksum() == want && one.app->replica().checksum() == want &&
           two.app->replica().checksum() == want;
  }));
  for (const Display* d : all) {
    EXPECT_EQ(d->app->replica().checksum(), want);
    EXPECT_EQ(d->app->counters().displaced, 0u);
    EXPECT_TRUE(d->app->ready());
  }
  EXPECT_EQ(s.link->counters().displaced, 0u);
  EXPECT_EQ(s.link->counters().spectators.admitted, 2u);
  EXPECT_EQ(s.link->counters().connects, 1u);
  // A spectator leaves: its slot is closed and counted.
  two_owner.reset();
  EXPECT_TRUE(run(s, {&main, &one}, 3000, [&] { return s.link->counters().spectators_now == 1u; }));
  EXPECT_EQ(s.link->counters().spectators.left, 1u);
}

}  // namespace
}  // namespace twister::bridge
