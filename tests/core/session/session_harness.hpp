// Test harness for SculptSession: a grid mesh, an in-memory journal and helpers to
// press buttons and move hands in virtual time. Test-only (allocates once at setup).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>

#include "fakes/fake_storage.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/journal/journal_writer.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/session/sculpt_session.hpp"

namespace twister::session::test_support {

inline constexpr std::size_t kVertices = 4096;
using TestMesh = mesh::MeshWithStorage<kVertices, 2 * kVertices>;
// With refinement memory for the mesh (refinement itself is off unless configured).
using TestSession = SculptSessionWithStorage<kVertices, kVertices, 8192, 32, 2 * kVertices>;
using TestStorage = twister::test::FakeStorageWithStorage<1 << 20>;

// Paper-default lines.
inline constexpr std::uint8_t kGrab0 = 0, kRadius0 = 1, kMove0 = 2;
inline constexpr std::uint8_t kGrab1 = 3, kRadius1 = 4, kFreeze1 = 5;

// n x n grid over [-1, 1]^2 at z = 0 (two triangles per cell).
inline void make_grid(mesh::Mesh& m, int n) {
  m.clear();
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const float x = -1.0f + 2.0f * static_cast<float>(i) / static_cast<float>(n - 1);
      const float y = -1.0f + 2.0f * static_cast<float>(j) / static_cast<float>(n - 1);
      (void)m.add_vertex({x, y, 0.0f});
    }
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const auto a = static_cast<std::uint32_t>(j * n + i);
      const auto nn = static_cast<std::uint32_t>(n);
      (void)m.add_triangle(a, a + 1, a + nn);
      (void)m.add_triangle(a + 1, a + nn + 1, a + nn);
    }
  }
}

// A frame at `origin` rotated by `angle_rad` about z.
inline math::Frame z_turn(glm::dvec3 origin, double angle_rad) {
  return math::frame_from_uv(origin, {std::cos(angle_rad), std::sin(angle_rad), 0.0},
                             {-std::sin(angle_rad), std::cos(angle_rad), 0.0});
}

inline SculptSessionConfig test_config() {
  SculptSessionConfig c;
  for (auto& i : c.debounce.interval_us) i = 0;  // debounce has its own tests
  c.interaction.initial_radius_m = 1.0f;
  c.interaction.radius_max_m = 4.0f;
  c.interaction.lost_timeout_us = 100'000;
  return c;
}

struct Station {
  explicit Station(int grid = 33, SculptSessionConfig config = test_config(),
                   bool with_journal = true)
      : writer(storage) {
    make_grid(mesh, grid);
    if (with_journal) {
      EXPECT_TRUE(writer.open().ok());
    }
    session = std::make_unique<TestSession>(config, mesh, with_journal ? &writer : nullptr);
  }
  void button(std::uint8_t line, bool pressed) {
    EXPECT_TRUE(session->feed_button({line, pressed, now_us}).ok());
  }
  void hand(std::uint8_t h, const math::Frame& f) {
    EXPECT_TRUE(session->set_hand(h, true, f).ok());
  }
  void lose(std::uint8_t h) { (void)session->set_hand(h, false, {}); }
  SessionEvents tick(ports::TimestampUs dt_us = 10'000) {
    now_us += dt_us;
    return session->step(now_us);
  }

  TestMesh mesh;
  TestStorage storage;
  journal::JournalWriter writer;
  std::unique_ptr<TestSession> session;
  ports::TimestampUs now_us = 0;
};

inline bool has_event(const SessionEvents& events, SessionEventKind kind) {
  for (const SessionEvent& e : events.items()) {
    if (e.kind == kind) return true;
  }
  return false;
}

}  // namespace twister::session::test_support
