// Test harness for refinement at commit (issue 13): a box (meshio's generator) with
// spare capacity, a session with refinement memory and an in-memory journal, and the
// twist of the paper's Figure 6 (one hand holds the bottom, the other turns the top).
// Test-only (allocates once at set-up).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>

#include "fakes/fake_storage.hpp"
#include "session_harness.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/journal/journal_writer.hpp"
#include "twister/meshio/mesh_buffer.hpp"
#include "twister/meshio/mesh_generator.hpp"
#include "twister/session/sculpt_session.hpp"

namespace twister::session::test_support {

inline constexpr std::size_t kRefineVertices = 16'000;
inline constexpr std::size_t kRefineTriangles = 2 * kRefineVertices;
using RefineSession =
    SculptSessionWithStorage<kRefineVertices, kRefineVertices, 1 << 17, 32, kRefineTriangles>;
using RefineStorage = twister::test::FakeStorageWithStorage<1 << 20>;

inline SculptSessionConfig refine_config(double threshold_m, bool on = true) {
  SculptSessionConfig c = test_config();
  c.refine.enabled = on;
  c.refine.threshold_m = threshold_m;
  return c;
}

// A box of n x n vertices per face, half size 0.5 m, with room for `spare` more
// vertices (and twice as many triangles, what splits of a closed mesh need).
struct RefineStation {
  RefineStation(std::size_t n, std::size_t spare, SculptSessionConfig config,
                bool with_journal = true)
      : buffer(meshio::box_vertices(n) + spare, meshio::box_triangles(n) + 2 * spare),
        writer(storage) {
    EXPECT_TRUE(meshio::make_box(buffer.mesh(), n, 0.5f).ok());
    if (with_journal) {
      EXPECT_TRUE(writer.open().ok());
    }
    session =
        std::make_unique<RefineSession>(config, buffer.mesh(), with_journal ? &writer : nullptr);
  }
  mesh::Mesh& mesh() { return buffer.mesh(); }
  void button(std::uint8_t line, bool pressed) {
    EXPECT_TRUE(session->feed_button({line, pressed, now_us}).ok());
  }
  void hand(std::uint8_t h, const math::Frame& f) {
    EXPECT_TRUE(session->set_hand(h, true, f).ok());
  }
  SessionEvents tick(ports::TimestampUs dt_us = 10'000) {
    now_us += dt_us;
    return session->step(now_us);
  }

  meshio::MeshBuffer buffer;
  RefineStorage storage;
  journal::JournalWriter writer;
  std::unique_ptr<RefineSession> session;
  ports::TimestampUs now_us = 0;
};

// The paper's twist: hand 0 holds the bottom face's centre, hand 1 grabs the top
// face's centre and turns it by `turn_rad` about z in `steps` steps (radius 1 m:
// each ball just reaches the other hand). Both release together: one commit.
// Returns the events of the release step.
inline SessionEvents twist_box(RefineStation& s, double turn_rad, int steps = 8) {
  s.hand(0, math::identity_frame({0, 0, -0.5}));
  s.hand(1, math::identity_frame({0, 0, 0.5}));
  s.button(kGrab0, true);
  s.button(kGrab1, true);
  (void)s.tick();
  for (int k = 1; k <= steps; ++k) {
    s.hand(1, z_turn({0, 0, 0.5}, turn_rad * k / steps));
    (void)s.tick();
  }
  s.button(kGrab0, false);
  s.button(kGrab1, false);
  return s.tick();
}

inline const SessionEvent* find_event(const SessionEvents& events, SessionEventKind kind) {
  for (const SessionEvent& e : events.items()) {
    if (e.kind == kind) return &e;
  }
  return nullptr;
}

}  // namespace twister::session::test_support
