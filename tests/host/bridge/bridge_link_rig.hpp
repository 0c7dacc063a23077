// A station (real SculptSession + StationLink) and a BridgeApp (no display) on the
// two ends of an in-memory wire, for the bridge's link tests. The bridge's time is
// `clock` (virtual: it moves only when a test advances it).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <glm/geometric.hpp>
#include <memory>
#include <vector>

#include "bridge_app.hpp"
#include "fakes/fake_clock.hpp"
#include "fakes/memory_wire.hpp"
#include "session_harness.hpp"
#include "support/station_link_buffers.hpp"
#include "twister/station/station_link.hpp"

namespace twister::bridge::test_support {

using session::test_support::kGrab0;
using session::test_support::Station;
using session::test_support::z_turn;

struct BridgeLinkRig {
  explicit BridgeLinkRig(ports::LogSink& log,
                         session::SculptSessionConfig config = session::test_support::test_config())
      : station(33, config),
        station_end(wire, true),
        bridge_end(wire, false),
        bridge(bridge_end, clock, nullptr, {}, log) {
    buffers.size_for(station.mesh);
    link = std::make_unique<station::StationLink>(station_end, buffers.storage(),
                                                  station::StationLinkConfig{});
    EXPECT_TRUE(link->start(*station.session).ok());
  }
  void run(int rounds = 20) {
    for (int i = 0; i < rounds; ++i) {
      bridge.step();
      link->poll(*station.session, station.now_us);
    }
    bridge.step();
  }
  void stroke(double lift) {
    station.hand(0, math::identity_frame({0, 0, 0}));
    station.button(kGrab0, true);
    (void)station.tick();
    run(2);
    for (int k = 1; k <= 4; ++k) {
      station.hand(0, z_turn({0.1 * k, 0, lift * k}, 0.2 * k));
      (void)station.tick();
      run(2);
    }
    station.button(kGrab0, false);
    (void)station.tick();
  }

  Station station;
  test::MemoryWire wire;
  test::MemoryLinkEnd station_end;
  test::MemoryLinkEnd bridge_end;
  test::StationLinkBuffers buffers;
  std::unique_ptr<station::StationLink> link;
  twister::test::FakeClock clock;
  BridgeApp bridge;
};

// Largest distance between the station's live positions and the bridge's CPU warp
// over the stroke's influenced vertices; -1 when either side has no live stroke.
inline double warp_difference(const BridgeLinkRig& r) {
  const session::LiveWarp live = r.station.session->live();
  const math::ConstVertexColumns positions = r.station.session->live_positions();
  const MeshData bridge = r.bridge.replica().cpu_warp();
  if (!live.active || live.plan == nullptr || bridge.vertex_count() == 0) return -1.0;
  double worst = 0.0;
  for (const std::uint32_t i : live.plan->indices()) {
    const glm::dvec3 s(positions.x[i], positions.y[i], positions.z[i]);
    const glm::dvec3 b(bridge.x[i], bridge.y[i], bridge.z[i]);
    worst = std::max(worst, glm::length(s - b));
  }
  return worst;
}

}  // namespace twister::bridge::test_support
