#include "station_memory.hpp"

#include <memory>
#include <span>
#include <type_traits>

#include "twister/link/link_codec.hpp"
#include "twister/meshio/symmetry_buffer.hpp"
#include "twister/station/station_link_spectators.hpp"

namespace twister::station_app {
namespace {

// Carves `n` default-constructed T from the front of `rest` (T's alignment divides
// every preceding block's size: the largest alignment comes first).
template <typename T>
std::span<T> carve(std::byte*& rest, std::size_t n) {
  T* first = std::uninitialized_default_construct_n(reinterpret_cast<T*>(rest), n) - n;
  rest += n * sizeof(T);
  return {first, n};
}

}  // namespace

MemoryBudget memory_budget(std::size_t vertex_capacity, std::size_t triangle_capacity,
                           std::size_t undo_changes, std::size_t undo_entries, bool link,
                           bool refine, std::size_t max_spectators) {
  MemoryBudget b;
  b.mesh = 3 * sizeof(float) * vertex_capacity + 3 * sizeof(std::uint32_t) * triangle_capacity;
  b.live = 3 * sizeof(float) * vertex_capacity;
  b.plan = (sizeof(std::uint32_t) + 2 * sizeof(float)) * vertex_capacity;
  b.undo = undo_changes * sizeof(session::VertexChange) + undo_entries * sizeof(session::UndoEntry);
  b.normals = 3 * sizeof(float) * vertex_capacity;
  if (refine) {
    b.refine = mesh::kRefinerBytesPerVertex * vertex_capacity +
               mesh::kRefinerBytesPerTriangle * triangle_capacity +
               session::kDefaultUndoTriangleChanges * sizeof(session::TriangleChange) +
               3 * sizeof(float) * vertex_capacity;  // a clutch chain's start
  }
  b.symmetry = meshio::SymmetryBuffer::bytes_for(vertex_capacity);
  if (link) {
    b.link = 3 * sizeof(float) * vertex_capacity + 3 * sizeof(std::uint32_t) * triangle_capacity +
             512 * link::kMaxFrameBytes + spectator_link_bytes(max_spectators);
  }
  return b;
}

std::size_t spectator_link_bytes(std::size_t max_spectators) {
  const std::size_t queues =
      max_spectators == 0 ? 0 : (max_spectators + 1) * kSpectatorQueueFrames * link::kMaxFrameBytes;
  return queues + sizeof(station::StationSpectators);
}

WorkMemory::WorkMemory(std::size_t vertex_capacity, std::size_t undo_changes,
                       std::size_t undo_entries) {
  const MemoryBudget b = memory_budget(vertex_capacity, 0, undo_changes, undo_entries);
  bytes_ = b.live + b.plan + b.undo + b.normals;
  static_assert(alignof(session::UndoEntry) >= alignof(session::VertexChange));
  static_assert(alignof(session::VertexChange) >= alignof(float));
  static_assert(sizeof(session::UndoEntry) % alignof(session::VertexChange) == 0);
  static_assert(sizeof(session::VertexChange) % alignof(float) == 0);
  static_assert(alignof(session::UndoEntry) <= __STDCPP_DEFAULT_NEW_ALIGNMENT__);
  static_assert(std::is_trivially_destructible_v<session::UndoEntry> &&
                std::is_trivially_destructible_v<session::VertexChange>);
  arena_.reset(new std::byte[bytes_]);
  std::byte* rest = arena_.get();
  storage_.undo_entries = carve<session::UndoEntry>(rest, undo_entries);
  storage_.undo_changes = carve<session::VertexChange>(rest, undo_changes);
  storage_.live_x = carve<float>(rest, vertex_capacity);
  storage_.live_y = carve<float>(rest, vertex_capacity);
  storage_.live_z = carve<float>(rest, vertex_capacity);
  const std::span<float> w1 = carve<float>(rest, vertex_capacity);
  const std::span<float> w2 = carve<float>(rest, vertex_capacity);
  const std::span<std::uint32_t> indices = carve<std::uint32_t>(rest, vertex_capacity);
  storage_.plan = math::WarpPlanStorage{indices, w1, w2};
  storage_.normals =
      mesh::NormalColumns{carve<float>(rest, vertex_capacity), carve<float>(rest, vertex_capacity),
                          carve<float>(rest, vertex_capacity)};
}

session::SculptStorage WorkMemory::storage() { return storage_; }

RefineMemory::RefineMemory(std::size_t vertex_capacity, std::size_t triangle_capacity)
    : refiner_(vertex_capacity, triangle_capacity),
      undo_triangles_(session::kDefaultUndoTriangleChanges),
      chain_x_(vertex_capacity),
      chain_y_(vertex_capacity),
      chain_z_(vertex_capacity) {}

session::SculptStorage RefineMemory::attach(session::SculptStorage storage) {
  storage.refine = refiner_.storage();
  storage.undo_triangle_changes = undo_triangles_;
  storage.chain_start = math::VertexColumns{chain_x_, chain_y_, chain_z_};
  return storage;
}

}  // namespace twister::station_app
