// Test harness for SculptSession's parts used on their own: a grid mesh with its
// live columns (LiveMesh), poses, a warp plan and a SessionHistory journaling into
// an in-memory file. Test-only; large, so tests allocate it with make_unique.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <cstdint>

#include "session_harness.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/journal/journal_writer.hpp"
#include "twister/math/warp_plan.hpp"
#include "twister/session/live_mesh.hpp"
#include "twister/session/session_events.hpp"
#include "twister/session/session_history.hpp"
#include "twister/session/session_poses.hpp"

namespace twister::session::test_support {

template <std::size_t kInfluenced = 1024, std::size_t kChanges = 4096, std::size_t kEntries = 16>
struct PartsRig {
  static constexpr std::size_t kCapacity = 1024;

  explicit PartsRig(int grid = 17) {
    make_grid(mesh, grid);
    EXPECT_TRUE(writer.open().ok());  // before any commit reaches the history
  }

  // Every record in the journal so far (at most 16).
  std::size_t read_records(std::array<journal::JournalRecord, 16>& out) {
    journal::JournalReader reader(storage);
    EXPECT_TRUE(reader.open().ok());
    std::size_t n = 0;
    for (auto r = reader.next(); r.ok() && n < out.size(); r = reader.next()) out[n++] = *r;
    return n;
  }

  mesh::MeshWithStorage<kCapacity, 2 * kCapacity> mesh;
  std::array<float, kCapacity> live_x{};
  std::array<float, kCapacity> live_y{};
  std::array<float, kCapacity> live_z{};
  LiveMesh live{mesh, live_x, live_y, live_z};
  SessionPoses poses;
  math::WarpPlanWithStorage<kInfluenced> plan;
  std::array<VertexChange, kChanges> changes{};
  std::array<UndoEntry, kEntries> entries{};
  TestStorage storage;
  journal::JournalWriter writer{storage};
  SessionHistory history{live, poses, changes, entries, &writer};
};

inline std::size_t count_events(const SessionEvents& events, SessionEventKind kind) {
  std::size_t n = 0;
  for (const SessionEvent& e : events.items()) n += e.kind == kind ? 1 : 0;
  return n;
}

}  // namespace twister::session::test_support
