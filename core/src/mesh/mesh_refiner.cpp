// Longest-edge bisection (Rivara's LEPP) driven by the midpoint-error criterion.
// A FIFO of triangles to examine starts with every triangle; a triangle with an
// edge over the threshold is bisected (after the neighbours on its longest-edge
// propagation path, so each split cuts an edge that is the longest of every
// triangle on it), and every triangle a split touches is examined again. Edge
// verdicts are cached per half-edge (shared with the twin) until a split changes
// the edge, and S(v) per vertex, so each edge and vertex is warped once.
#include "twister/mesh/mesh_refiner.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>
#include <glm/geometric.hpp>
#include <utility>

#include "twister/base/assert.hpp"

// batch_edge runs once per region edge: inlined, a batch's count stays in a register.
#if defined(__GNUC__)
#define TWISTER_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define TWISTER_ALWAYS_INLINE inline
#endif

namespace twister::mesh {
namespace {

constexpr std::uint8_t kUnknown = 0;
constexpr std::uint8_t kWithin = 1;
constexpr std::uint8_t kOver = 2;
constexpr std::uint8_t kBatched = 3;  // in a float batch (settle_in_float only)
constexpr std::uint8_t kQueued = 1;
constexpr std::uint8_t kReported = 2;
constexpr std::uint8_t kPending = 4;  // refine_around: an original triangle still to visit
constexpr std::uint32_t kNoCorner = 0xffffffffu;

constexpr std::uint32_t next(std::uint32_t i) { return i == 2 ? 0 : i + 1; }
constexpr std::uint32_t prev(std::uint32_t i) { return i == 0 ? 2 : i - 1; }
bool real_twin(std::uint32_t g) { return g != kBoundary && g != kNonManifold; }
// |c| as bits, ordered as the magnitudes are, a NaN above every number: a running
// maximum of them has no chain of float compares and lets a NaN through (to settle
// nothing) where std::max would drop it.
std::uint32_t magnitude_bits(float c) { return std::bit_cast<std::uint32_t>(c) & 0x7fffffffu; }

}  // namespace

const char* refine_stop_name(RefineStop stop) {
  switch (stop) {
    case RefineStop::done:
      return "done";
    case RefineStop::vertex_capacity:
      return "vertex_capacity";
    case RefineStop::triangle_capacity:
      return "triangle_capacity";
  }
  return "unknown";
}

MeshRefiner::MeshRefiner(MeshRefinerStorage storage)
    : storage_(storage), adjacency_(storage.adjacency), queue_(storage.queue) {}

bool MeshRefiner::fits(const Mesh& mesh) const {
  const std::size_t v = mesh.vertex_capacity();
  const std::size_t t = mesh.triangle_capacity();
  return adjacency_.fits(mesh) && storage_.warped_x.size() >= v && storage_.warped_y.size() >= v &&
         storage_.warped_z.size() >= v && storage_.warped_stamp.size() >= v &&
         storage_.edge_state.size() >= 3 * t && storage_.triangle_flags.size() >= t &&
         storage_.queue.size() >= t && storage_.float_x.size() >= v &&
         storage_.float_y.size() >= v && storage_.float_z.size() >= v &&
         storage_.float_stamp.size() >= v;
}

double MeshRefiner::midpoint_error(glm::dvec3 a, glm::dvec3 b, const PointWarp& warp) {
  const glm::dvec3 chord_mid = 0.5 * (warp.warp(a) + warp.warp(b));
  return glm::length(chord_mid - warp.warp(0.5 * (a + b)));
}

Result<RefineResult> MeshRefiner::refine(Mesh& mesh, const PointWarp& warp, double threshold_m,
                                         RefineObserver* observer) {
  if (!fits(mesh)) return StatusCode::failed_precondition;
  if (!std::isfinite(threshold_m) || !(threshold_m > 0.0)) return StatusCode::invalid_argument;
  TWISTER_TRY(build_adjacency(mesh));
  region_.local = false;
  start(mesh, warp, threshold_m, observer);
  const auto vertices_before = static_cast<std::uint32_t>(mesh.vertex_count());
  for (std::uint32_t t = 0; t < triangles_before_; ++t) {
    storage_.triangle_flags[t] = 0;
    push(t);
  }
  run();
  for (std::uint32_t v = vertices_before; v < mesh.vertex_count(); ++v) (void)warped_of(v);
  keep_adjacency(mesh);
  mesh_ = nullptr;
  return result_;
}

Result<RefineResult> MeshRefiner::refine_around(Mesh& mesh, const PointWarp& warp,
                                                double threshold_m,
                                                std::span<const std::uint32_t> vertices,
                                                RefineObserver* observer, VertexImages images) {
  if (!fits(mesh)) return StatusCode::failed_precondition;
  if (!std::isfinite(threshold_m) || !(threshold_m > 0.0)) return StatusCode::invalid_argument;
  for (const std::uint32_t v : vertices) {
    if (v >= mesh.vertex_count()) return StatusCode::invalid_argument;
  }
  if (!adjacency_current(mesh)) TWISTER_TRY(build_adjacency(mesh));
  if (!adjacency_key_.manifold) return refine(mesh, warp, threshold_m, observer);
  region_.local = true;
  start(mesh, warp, threshold_m, observer);
  const auto vertices_before = static_cast<std::uint32_t>(mesh.vertex_count());
  // With every region edge within the threshold nothing can split: the visiting
  // order (and so the sort) matters only when something is left to the double criterion.
  if (!collect_and_settle(vertices, images)) {
    sort_region();
    run();
  }
  region_.local = false;
  for (std::uint32_t v = vertices_before; v < mesh.vertex_count(); ++v) (void)warped_of(v);
  keep_adjacency(mesh);
  mesh_ = nullptr;
  return result_;
}

// The FIFO loop (refine) or the emulation of its order (refine_around).
void MeshRefiner::run() {
  std::uint32_t t = 0;
  while (next_triangle(t)) {
    if (!has_offending_edge(t)) continue;
    const Split s = bisect(t);
    if (s == Split::no_room) break;
    if (s == Split::blocked) ++result_.blocked;
  }
}

// refine() pops the original triangles in index order, then what splits pushed. In
// refine_around the originals outside the region (never changed before their turn)
// would be popped without effect there, so only the region's (region_.pending) and those a
// split changed before their turn (region_.heap) are visited, in index order, then the FIFO.
bool MeshRefiner::next_triangle(std::uint32_t& t) {
  if (region_.pending_phase) {
    const bool from_heap =
        region_.heap_size > 0 && (region_.pending_pos == region_.pending.size() ||
                                  region_.heap[0] < region_.pending[region_.pending_pos]);
    if (from_heap) {
      std::pop_heap(region_.heap.begin(),
                    region_.heap.begin() + static_cast<std::ptrdiff_t>(region_.heap_size),
                    std::greater<>());
      t = region_.heap[--region_.heap_size];
    } else if (region_.pending_pos < region_.pending.size()) {
      t = region_.pending[region_.pending_pos++];
    } else {
      region_.pending_phase = false;
      region_.cursor = triangles_before_;
    }
    if (region_.pending_phase) {
      region_.cursor = t;
      touch(t);
      storage_.triangle_flags[t] &= static_cast<std::uint8_t>(~kPending);
      return true;
    }
  }
  if (queue_.empty()) return false;
  t = queue_.front();
  queue_.pop_front();
  storage_.triangle_flags[t] &= static_cast<std::uint8_t>(~kQueued);
  return true;
}

void MeshRefiner::start(Mesh& mesh, const PointWarp& warp, double threshold_m,
                        RefineObserver* observer) {
  mesh_ = &mesh;
  warp_ = &warp;
  observer_ = observer;
  threshold_m_ = threshold_m;
  result_ = RefineResult{};
  if (++generation_ == 1) {  // first call, or the stamps wrapped: none is valid
    for (std::uint32_t& s : storage_.warped_stamp) s = 0;
    for (std::uint32_t& s : storage_.float_stamp) s = 0;
    reset_triangle_stamps();
  }
  const std::size_t triangles = mesh.triangle_count();
  triangles_before_ = static_cast<std::uint32_t>(triangles);
  if (!region_.local) {
    for (std::size_t h = 0; h < 3 * triangles; ++h) storage_.edge_state[h] = kUnknown;
  }
  queue_.clear();
  region_.pending_phase = region_.local;
  region_.cursor = -1;
  region_.pending = {};
  region_.pending_pos = 0;
  region_.heap_size = 0;
}

glm::dvec3 MeshRefiner::rest(std::uint32_t v) const { return glm::dvec3(mesh_->position(v)); }

glm::dvec3 MeshRefiner::warped_of(std::uint32_t v) {
  if (storage_.warped_stamp[v] != generation_) {
    const glm::dvec3 s = warp_->warp(rest(v));
    storage_.warped_x[v] = s.x;
    storage_.warped_y[v] = s.y;
    storage_.warped_z[v] = s.z;
    storage_.warped_stamp[v] = generation_;
  }
  return {storage_.warped_x[v], storage_.warped_y[v], storage_.warped_z[v]};
}

glm::dvec3 MeshRefiner::warped(std::uint32_t v) const {
  TWISTER_ASSERT(v < storage_.warped_stamp.size() && storage_.warped_stamp[v] == generation_);
  return {storage_.warped_x[v], storage_.warped_y[v], storage_.warped_z[v]};
}

std::uint32_t MeshRefiner::edge_vertex(std::uint32_t h, std::uint32_t end) const {
  const std::uint32_t i = h % 3;
  return mesh_->triangle(h / 3)[end == 0 ? i : next(i)];
}

double MeshRefiner::length2(std::uint32_t h) const {
  const glm::dvec3 d = rest(edge_vertex(h, 1)) - rest(edge_vertex(h, 0));
  return glm::dot(d, d);
}

std::uint32_t MeshRefiner::longest(std::uint32_t t) const {
  std::uint32_t best = 3 * t;
  double best_length = length2(best);
  for (std::uint32_t h = 3 * t + 1; h < 3 * t + 3; ++h) {
    const double l = length2(h);
    if (l > best_length) {
      best = h;
      best_length = l;
    }
  }
  return best;
}

bool MeshRefiner::offending(std::uint32_t h) {
  touch(h / 3);
  std::uint8_t state = storage_.edge_state[h];
  if (state == kUnknown) {
    const std::uint32_t a = edge_vertex(h, 0);
    const std::uint32_t b = edge_vertex(h, 1);
    const glm::dvec3 chord_mid = 0.5 * (warped_of(a) + warped_of(b));
    const double error = glm::length(chord_mid - warp_->warp(0.5 * (rest(a) + rest(b))));
    state = error > threshold_m_ ? kOver : kWithin;
    storage_.edge_state[h] = state;
    const std::uint32_t g = adjacency_.twin(h);
    if (real_twin(g)) {
      touch(g / 3);
      storage_.edge_state[g] = state;
    }
  }
  return state == kOver;
}

bool MeshRefiner::has_offending_edge(std::uint32_t t) {
  bool any = false;
  for (std::uint32_t h = 3 * t; h < 3 * t + 3; ++h) any = offending(h) || any;
  return any;
}

// Rivara: follow the longest edges while the triangle across is longer still; the
// last edge is the longest of both its triangles (or on the boundary): split it.
// Repeat until t itself was split.
MeshRefiner::Split MeshRefiner::bisect(std::uint32_t t) {
  for (;;) {
    std::uint32_t current = t;
    std::uint32_t h = longest(t);
    double length = length2(h);
    std::uint32_t g = adjacency_.twin(h);
    while (real_twin(g)) {
      const std::uint32_t across = longest(g / 3);
      const double across_length = length2(across);
      if (across_length <= length) break;
      current = g / 3;
      h = across;
      length = across_length;
      g = adjacency_.twin(h);
    }
    if (g == kNonManifold) return Split::blocked;
    if (!room(g == kBoundary ? 1 : 2)) return Split::no_room;
    split(h);
    if (current == t) return Split::done;
  }
}

bool MeshRefiner::room(std::uint32_t triangles) {
  if (mesh_->vertex_count() >= mesh_->vertex_capacity()) {
    result_.stop = RefineStop::vertex_capacity;
    return false;
  }
  if (mesh_->triangle_count() + triangles > mesh_->triangle_capacity()) {
    result_.stop = RefineStop::triangle_capacity;
    return false;
  }
  return true;
}

void MeshRefiner::split(std::uint32_t h) {
  const glm::dvec3 mid = 0.5 * (rest(edge_vertex(h, 0)) + rest(edge_vertex(h, 1)));
  const Result<std::uint32_t> added = mesh_->add_vertex(glm::vec3(mid));
  TWISTER_ASSERT(added.ok());  // room() was checked
  const std::uint32_t m = *added;
  storage_.adjacency.vertex_offsets[m] = h / 3;  // m's corner
  const std::uint32_t a = edge_vertex(h, 0);
  const std::uint32_t g = adjacency_.twin(h);
  const std::uint32_t t_new = split_one(h, m);
  const std::uint32_t h_new = 3 * t_new + h % 3;  // (m, b); h is now (a, m)
  ++result_.edges_split;
  if (!real_twin(g)) {
    adjacency_.link(h, g);
    adjacency_.link(h_new, g);
    return;
  }
  // g starts at a when its triangle is oriented against h's (an inconsistent mesh).
  const bool same_start = edge_vertex(g, 0) == a;
  const std::uint32_t u_new = split_one(g, m);
  const std::uint32_t g_new = 3 * u_new + g % 3;  // g is now (p, m), g_new (m, q)
  adjacency_.link(h, same_start ? g : g_new);
  adjacency_.link(h_new, same_start ? g_new : g);
}

// Cuts triangle h/3 = (a, b, c) on edge h = (a, b) at m: it becomes (a, m, c) in
// place and (m, b, c) is appended (same orientation, same slots). Links everything
// but the two halves of h (the caller's); returns the new triangle.
std::uint32_t MeshRefiner::split_one(std::uint32_t h, std::uint32_t m) {
  const std::uint32_t t = h / 3;
  const std::uint32_t i = h % 3;
  touch(t);
  changing(t);
  std::array<std::uint32_t, 3> v = mesh_->triangle(t);
  std::array<std::uint32_t, 3> w = v;
  w[i] = m;
  const Result<std::uint32_t> added = mesh_->add_triangle(w[0], w[1], w[2]);
  TWISTER_ASSERT(added.ok());  // room() was checked
  const std::uint32_t n = *added;
  touch(n);
  // b leaves t for n: keep its corner on one of its triangles.
  std::uint32_t& corner_b = storage_.adjacency.vertex_offsets[v[next(i)]];
  if (corner_b == t) corner_b = n;
  v[next(i)] = m;
  mesh_->set_triangle(t, v);
  ++result_.triangles_added;
  const std::uint32_t outer = adjacency_.twin(3 * t + next(i));  // (b, c) moves to n
  std::span<std::uint8_t> state = storage_.edge_state;
  state[3 * n + next(i)] = state[3 * t + next(i)];
  state[3 * t + i] = state[3 * t + next(i)] = kUnknown;
  state[3 * n + i] = state[3 * n + prev(i)] = kUnknown;
  adjacency_.link(3 * n + next(i), outer);
  adjacency_.link(3 * t + next(i), 3 * n + prev(i));  // the median (m, c)
  storage_.triangle_flags[n] = 0;
  push(t);
  push(n);
  return n;
}

void MeshRefiner::changing(std::uint32_t t) {
  touch(t);
  if (t >= triangles_before_ || (storage_.triangle_flags[t] & kReported) != 0) return;
  storage_.triangle_flags[t] |= kReported;
  ++result_.triangles_changed;
  if (observer_ != nullptr) observer_->triangle_changing(t, mesh_->triangle(t));
}

void MeshRefiner::push(std::uint32_t t) {
  touch(t);
  std::uint8_t& flags = storage_.triangle_flags[t];
  if (region_.pending_phase && t<triangles_before_&& static_cast<std::int64_t>(t)> region_.cursor) {
    // refine() still holds t at its index in the FIFO: visit it there.
    if ((flags & kPending) != 0) return;
    flags |= kPending;
    region_.heap[region_.heap_size++] = t;
    std::push_heap(region_.heap.begin(),
                   region_.heap.begin() + static_cast<std::ptrdiff_t>(region_.heap_size),
                   std::greater<>());
    return;
  }
  if ((flags & kQueued) != 0) return;
  flags |= kQueued;
  // At most one entry per triangle (kQueued) and fits() saw room for every triangle.
  const Status queued = queue_.push(t);
  TWISTER_DEBUG_ASSERT(queued.ok());
}

// refine_around: a triangle's flags and edge verdicts are of this call once touched.
void MeshRefiner::touch(std::uint32_t t) {
  if (!region_.local || region_.stamps[t] == generation_) return;
  region_.stamps[t] = generation_;
  storage_.triangle_flags[t] = 0;
  storage_.edge_state[3 * std::size_t{t}] = kUnknown;
  storage_.edge_state[3 * std::size_t{t} + 1] = kUnknown;
  storage_.edge_state[3 * std::size_t{t} + 2] = kUnknown;
}

void MeshRefiner::reset_triangle_stamps() {
  for (std::uint32_t& s : region_.stamps) s = 0;
}

// Twins from scratch (O(triangles x valence)); then the vertex -> triangle table
// becomes one corner triangle per vertex, the rest of the scratch the stamps and
// lists of refine_around, and the mesh is checked for what local refinement needs.
Status MeshRefiner::build_adjacency(const Mesh& mesh) {
  adjacency_key_.mesh = nullptr;
  TWISTER_TRY(adjacency_.build(mesh));
  const std::size_t n = mesh.vertex_count();
  std::span<std::uint32_t> offsets = storage_.adjacency.vertex_offsets;
  std::span<std::uint32_t> incident = storage_.adjacency.incident;
  for (std::size_t v = 0; v < n; ++v) {
    offsets[v] = offsets[v] < offsets[v + 1] ? incident[offsets[v]] : kNoCorner;
  }
  const std::size_t capacity = mesh.triangle_capacity();
  region_.stamps = incident.first(capacity);
  reset_triangle_stamps();
  // Manifold: no edge on more than two triangles, and each vertex's triangles are one
  // fan around it (the fans of all vertices cover every corner once).
  const std::size_t triangles = mesh.triangle_count();
  adjacency_key_.manifold = true;
  for (std::size_t h = 0; h < 3 * triangles && adjacency_key_.manifold; ++h) {
    adjacency_key_.manifold = adjacency_.twin(static_cast<std::uint32_t>(h)) != kNonManifold;
  }
  if (adjacency_key_.manifold) {
    const Mesh* saved = mesh_;
    mesh_ = const_cast<Mesh*>(&mesh);  // read only: for_fan reads triangles
    std::size_t corners = 0;
    for (std::uint32_t v = 0; v < n && adjacency_key_.manifold; ++v) {
      const std::uint32_t k = for_fan(v, [](std::uint32_t) {});
      if (k == kNoCorner) adjacency_key_.manifold = false;
      corners += k;
    }
    mesh_ = const_cast<Mesh*>(saved);
    adjacency_key_.manifold = adjacency_key_.manifold && corners == 3 * triangles;
  }
  // Consistent winding: every edge runs one way in one triangle and the other way in
  // its twin. Splits keep it (each half keeps its triangle's orientation).
  const std::uint32_t* tv = mesh.triangle_indices().data();
  adjacency_key_.oriented = true;
  for (std::uint32_t h = 0; h < 3 * triangles && adjacency_key_.oriented; ++h) {
    const std::uint32_t g = adjacency_.twin(h);
    adjacency_key_.oriented = !real_twin(g) || tv[g] == tv[h % 3 == 2 ? h - 2 : h + 1];
  }
  return ok_status();
}

bool MeshRefiner::adjacency_current(const Mesh& mesh) const {
  return adjacency_key_.mesh == &mesh && adjacency_key_.version == mesh.topology_version() &&
         adjacency_key_.vertices == mesh.vertex_count();
}

void MeshRefiner::keep_adjacency(const Mesh& mesh) {
  adjacency_key_.mesh = &mesh;
  adjacency_key_.version = mesh.topology_version();
  adjacency_key_.vertices = mesh.vertex_count();
}

std::uint32_t MeshRefiner::slot(std::uint32_t t, std::uint32_t v) const {
  const std::uint32_t* tv = mesh_->triangle_indices().data() + 3 * std::size_t{t};
  return tv[0] == v ? 0 : tv[1] == v ? 1 : 2;
}

// Calls f(t) for every triangle around v (walking across the twins of the edges at
// v, both ways when the fan is open); returns how many, or kNoCorner when the walk
// meets a non-manifold edge or does not close within the mesh's triangle count.
template <typename F>
std::uint32_t MeshRefiner::for_fan(std::uint32_t v, F&& f) const {
  const std::uint32_t t0 = storage_.adjacency.vertex_offsets[v];
  if (t0 == kNoCorner) return 0;
  const auto limit = static_cast<std::uint32_t>(mesh_->triangle_count());
  const std::uint32_t j0 = slot(t0, v);
  std::uint32_t count = 0;
  f(t0);
  ++count;
  // Two ways out of t0 at v: edge (v, next) and edge (prev, v).
  for (const std::uint32_t first_exit : {3 * t0 + j0, 3 * t0 + prev(j0)}) {
    std::uint32_t exit = first_exit;
    for (;;) {
      const std::uint32_t g = adjacency_.twin(exit);
      if (g == kBoundary) break;
      if (g == kNonManifold) return kNoCorner;
      const std::uint32_t u = g / 3;
      if (u == t0) return count;  // closed fan: both ways done
      if (++count > limit) return kNoCorner;
      f(u);
      const std::uint32_t j = slot(u, v);
      exit = 3 * u + j == g ? 3 * u + prev(j) : 3 * u + j;
    }
  }
  return count;
}

// The manifold fan of v (adjacency_key_.manifold): tri(t, j) for each triangle (j: v's
// slot in it), edge(h, g) for each edge at v, once, after tri() of both its triangles
// (h a half-edge at v, g its twin or kBoundary), walking as for_fan does.
template <typename Tri, typename Edge>
void MeshRefiner::walk_fan(std::uint32_t v, Tri&& tri, Edge&& edge) const {
  const std::uint32_t t0 = storage_.adjacency.vertex_offsets[v];
  if (t0 == kNoCorner) return;
  const std::uint32_t j0 = slot(t0, v);
  tri(t0, j0);
  const bool oriented = adjacency_key_.oriented;
  // Way 0 leaves t0 by the edge from v, way 1 by the edge into v.
  for (const std::uint32_t way : {0u, 1u}) {
    std::uint32_t exit = way == 0 ? 3 * t0 + j0 : 3 * t0 + prev(j0);
    for (;;) {
      const std::uint32_t g = adjacency_.twin(exit);
      if (!real_twin(g)) {  // the boundary (a manifold fan has no other end)
        edge(exit, g);
        break;
      }
      const std::uint32_t u = g / 3;
      if (u == t0) {  // closed: every edge at v crossed once
        edge(exit, g);
        return;
      }
      // Consistent winding: g runs against exit, so v's slot in u follows from g
      // alone and the walk waits on one load per triangle, not two.
      std::uint32_t j = 0;
      if (oriented) {
        j = way == 0 ? next(g % 3) : g % 3;
      } else {
        j = slot(u, v);
      }
      tri(u, j);  // before the edge into it: an edge sees both its triangles entered
      edge(exit, g);
      exit = 3 * u + j == g ? 3 * u + prev(j) : 3 * u + j;
    }
  }
}

// The region: every triangle with a vertex in `vertices`, each flagged kPending, in
// the order the fans are walked (sort_region puts them in ascending index).
void MeshRefiner::collect_region(std::span<const std::uint32_t> vertices) {
  const std::size_t capacity = region_.stamps.size();
  std::span<std::uint32_t> list = storage_.adjacency.incident.subspan(capacity, capacity);
  std::size_t count = 0;
  for (const std::uint32_t v : vertices) {
    (void)for_fan(v, [&](std::uint32_t t) {
      if (enter_region(t)) list[count++] = t;
    });
  }
  set_region(list.first(count));
}

// Touches t and flags it kPending; false when it already was.
bool MeshRefiner::enter_region(std::uint32_t t) {
  touch(t);
  std::uint8_t& flags = storage_.triangle_flags[t];
  if ((flags & kPending) != 0) return false;
  flags |= kPending;
  return true;
}

// The region's list (in the scratch's second third; the last third is the heap's).
void MeshRefiner::set_region(std::span<std::uint32_t> list) {
  const std::size_t capacity = region_.stamps.size();
  region_.pending = list;
  region_.heap = storage_.adjacency.incident.subspan(2 * capacity, capacity);
  region_.pending_pos = 0;
  region_.heap_size = 0;
}

// A radix sort of the region's triangles over the scratch (the list and the heap's room).
void MeshRefiner::sort_region() {
  const std::size_t count = region_.pending.size();
  std::span<std::uint32_t> a = region_.pending;
  std::span<std::uint32_t> b = region_.heap;
  constexpr std::uint32_t kBits = 11;
  std::array<std::uint32_t, 1u << kBits> buckets{};
  for (std::uint32_t shift = 0; shift < 32 && (triangles_before_ >> shift) != 0; shift += kBits) {
    buckets.fill(0);
    for (std::size_t k = 0; k < count; ++k) ++buckets[(a[k] >> shift) & ((1u << kBits) - 1)];
    std::uint32_t sum = 0;
    for (std::uint32_t& c : buckets) {
      const std::uint32_t here = c;
      c = sum;
      sum += here;
    }
    for (std::size_t k = 0; k < count; ++k)
      b[buckets[(a[k] >> shift) & ((1u << kBits) - 1)]++] = a[k];
    std::swap(a, b);
  }
  region_.pending = a.first(count);
  region_.heap = b;
}

// The float filter: every edge of the region's triangles evaluated in single precision
// in batches (S at both ends and at the float midpoint); an edge whose float error is
// at most threshold - 2 delta - slack (delta = the warp's float_error_m bound, slack for
// computing the error itself) is within the threshold in double too, so its verdict is
// cached as refine() would have computed it. Every other edge is left to the double
// criterion (docs/refinement.md "The float filter").
struct MeshRefiner::FloatBatch {
  static constexpr std::size_t kSize = PointWarp::kFloatBatch;
  std::array<std::uint32_t, kSize> edges{};
  std::array<std::uint32_t, kSize> twins{};
  std::array<float, kSize> x{}, y{}, z{}, ox{}, oy{}, oz{};  // float midpoints, S of them
  std::array<double, kSize> cx{}, cy{}, cz{};                // (S(a) + S(b)) / 2 in float
  std::size_t n = 0;
  bool keep_verdicts = true;  // cache each edge's verdict (else only count them)
};

struct MeshRefiner::VertexBatch {
  static constexpr std::size_t kSize = PointWarp::kFloatBatch;
  std::array<std::uint32_t, kSize> vertices{};
  std::array<float, kSize> x{}, y{}, z{}, ox{}, oy{}, oz{};
  std::size_t n = 0;
  float extent = 0.0f;
  bool fast = true;
};

// S in float of a batch of vertices into the float cache (and the bound for them).
void MeshRefiner::warp_vertices(VertexBatch& b) {
  if (b.n == 0) return;
  b.fast = b.fast && warp_->warp_float(b.x.data(), b.y.data(), b.z.data(), b.ox.data(), b.oy.data(),
                                       b.oz.data(), b.n);
  if (b.fast) filter_.error = std::max(filter_.error, warp_->float_error_m(b.extent));
  for (std::size_t k = 0; k < b.n; ++k) {
    const std::uint32_t v = b.vertices[k];
    storage_.float_x[v] = b.ox[k];
    storage_.float_y[v] = b.oy[k];
    storage_.float_z[v] = b.oz[k];
  }
  b.n = 0;
  b.extent = 0.0f;
}

// The region and the float filter over it; true when every region edge was settled
// within the threshold. With the vertices' images given, one pass: the fans of
// `vertices` are walked once, each edge batched when it is first met, the other
// region vertices taken as fixed points. Otherwise the region first, then S in float
// at each of its vertices, then its edges.
bool MeshRefiner::collect_and_settle(std::span<const std::uint32_t> vertices, VertexImages images) {
  filter_ = FloatFilter{};
  const std::size_t n = mesh_->vertex_count();
  if (images.x.size() < n || images.y.size() < n || images.z.size() < n) {
    FloatBatch b;
    collect_region(vertices);
    if (!warp_region_vertices()) return false;  // the warp offers no float batch
    filter_.images = {storage_.float_x, storage_.float_y, storage_.float_z};
    for (const std::uint32_t t : region_.pending) batch_edges(t, b);
    settle_batch(b);
    return filter_.unsettled == 0;
  }
  stamp_images(vertices, images);
  if (settle_stroke_edges(vertices)) return true;  // the usual case: nothing else to do
  filter_.settled = 0;
  filter_.unsettled = 0;
  FloatBatch b;
  const std::size_t capacity = region_.stamps.size();
  std::span<std::uint32_t> list = storage_.adjacency.incident.subspan(capacity, capacity);
  std::size_t count = 0;
  const std::uint32_t* tv = mesh_->triangle_indices().data();
  for (const std::uint32_t v : vertices) {
    const EdgeEnd ev = edge_end(v, true);
    walk_fan(
        v,
        [&](std::uint32_t t, std::uint32_t j) {
          if (!enter_region(t)) return;
          list[count++] = t;
          // The edge across from v: batched here when neither end is the stroke's
          // (else it is an edge at that end, batched from its fan).
          const std::uint32_t h = 3 * t + next(j);
          if (!stroke_vertex(tv[h]) && !stroke_vertex(tv[3 * t + prev(j)])) batch_edges_of(h, b);
        },
        [&](std::uint32_t h, std::uint32_t g) {
          // An edge at v, met once in v's fan (both its triangles already entered):
          // batched from its lower end when both ends are the stroke's.
          const std::uint32_t a = tv[h];
          const std::uint32_t w = a == v ? tv[h % 3 == 2 ? h - 2 : h + 1] : a;
          const bool both = stroke_vertex(w);
          if (both && w < v) return;
          batch_edge(h, g, ev, edge_end(w, both), b);
        });
  }
  settle_batch(b);
  set_region(list.first(count));
  return filter_.unsettled == 0;
}

// The float filter over the stroke's fans with no bookkeeping (no region list, no
// triangle stamps or flags, no cached verdicts): true when every region edge is
// within the threshold, and then nothing can split and nothing else is needed. Stops
// at the first batch with an edge left to the double criterion (the caller then
// walks again with the bookkeeping). Each edge once, without marks: an edge at a
// stroke vertex from its lower stroke end, an edge with no stroke end from the
// triangle across from its stroke vertex (the lower of two such triangles).
bool MeshRefiner::settle_stroke_edges(std::span<const std::uint32_t> vertices) {
  const std::uint32_t* tv = mesh_->triangle_indices().data();
  FloatBatch b;
  b.keep_verdicts = false;
  for (const std::uint32_t v : vertices) {
    const EdgeEnd ev = edge_end(v, true);
    const auto at_v = [&](std::uint32_t h, std::uint32_t g, std::uint32_t w, bool w_stroke) {
      if (w_stroke && w < v) return;
      batch_edge(h, g, ev, edge_end(w, w_stroke), b);
    };
    const auto across = [&](std::uint32_t t, std::uint32_t h, std::uint32_t a, bool a_stroke,
                            std::uint32_t c, bool c_stroke) {
      if (a_stroke || c_stroke) return;
      const std::uint32_t g = adjacency_.twin(h);
      if (real_twin(g) && g / 3 < t && stroke_vertex(tv[g % 3 == 0 ? g + 2 : g - 1])) return;
      batch_edge(h, g, edge_end(a, false), edge_end(c, false), b);
    };
    if (adjacency_key_.oriented) {
      walk_ring(v, at_v, across);
    } else {
      walk_fan(
          v,
          [&](std::uint32_t t, std::uint32_t j) {
            const std::uint32_t h = 3 * t + next(j);
            const std::uint32_t a = tv[h];
            const std::uint32_t c = tv[3 * t + prev(j)];
            across(t, h, a, stroke_vertex(a), c, stroke_vertex(c));
          },
          [&](std::uint32_t h, std::uint32_t g) {
            const std::uint32_t a = tv[h];
            const std::uint32_t w = a == v ? tv[h % 3 == 2 ? h - 2 : h + 1] : a;
            at_v(h, g, w, stroke_vertex(w));
          });
    }
    if (filter_.unsettled != 0) return false;
  }
  settle_batch(b);
  return filter_.unsettled == 0;
}

// The fan of v on a consistently wound manifold, as the ring of v's neighbours:
// at_v(h, g, w, w_stroke) for each edge (v, w) (h the half-edge at v crossed, g its
// twin or kBoundary), across(t, h, a, a_stroke, c, c_stroke) for each triangle's edge
// (a, c) across from v. Each step loads one twin (the walk's only dependent load: v's
// slot in the next triangle follows from it) and one new neighbour, whose stroke flag
// serves both the edge to it and the two triangles' edges across.
template <typename AtV, typename Across>
void MeshRefiner::walk_ring(std::uint32_t v, AtV&& at_v, Across&& across) const {
  const std::uint32_t t0 = storage_.adjacency.vertex_offsets[v];
  if (t0 == kNoCorner) return;
  const std::uint32_t* tv = mesh_->triangle_indices().data();
  const std::uint32_t j0 = slot(t0, v);
  const std::uint32_t x0 = tv[3 * t0 + next(j0)];
  const std::uint32_t y0 = tv[3 * t0 + prev(j0)];
  const bool x0_stroke = stroke_vertex(x0);
  const bool y0_stroke = stroke_vertex(y0);
  across(t0, 3 * t0 + next(j0), x0, x0_stroke, y0, y0_stroke);
  // Out of t0 by the edge from v (v -> x): each next triangle is (v, x', x).
  std::uint32_t exit = 3 * t0 + j0;
  std::uint32_t w = x0;
  bool w_stroke = x0_stroke;
  for (;;) {
    const std::uint32_t g = adjacency_.twin(exit);
    const std::uint32_t u = g / 3;
    if (!real_twin(g) || u == t0) {
      at_v(exit, g, w, w_stroke);
      if (real_twin(g)) return;  // closed: every edge at v crossed once
      break;
    }
    const std::uint32_t j = next(g % 3);
    const std::uint32_t x = tv[3 * u + next(j)];
    const bool x_stroke = stroke_vertex(x);
    across(u, 3 * u + next(j), x, x_stroke, w, w_stroke);
    at_v(exit, g, w, w_stroke);
    exit = 3 * u + j;
    w = x;
    w_stroke = x_stroke;
  }
  // Open: back from t0 by the edge into v (y -> v): each next triangle is (v, y, y').
  exit = 3 * t0 + prev(j0);
  w = y0;
  w_stroke = y0_stroke;
  for (;;) {
    const std::uint32_t g = adjacency_.twin(exit);
    if (!real_twin(g) || g / 3 == t0) {
      at_v(exit, g, w, w_stroke);
      return;
    }
    const std::uint32_t u = g / 3;
    const std::uint32_t j = g % 3;
    const std::uint32_t y = tv[3 * u + prev(j)];
    const bool y_stroke = stroke_vertex(y);
    across(u, 3 * u + next(j), w, w_stroke, y, y_stroke);
    at_v(exit, g, w, w_stroke);
    exit = 3 * u + prev(j);
    w = y;
    w_stroke = y_stroke;
  }
}

// `vertices` stamped as the stroke's (their images given), and the bound for them.
void MeshRefiner::stamp_images(std::span<const std::uint32_t> vertices, VertexImages images) {
  const std::span<const float> px = std::as_const(*mesh_).x();
  const std::span<const float> py = std::as_const(*mesh_).y();
  const std::span<const float> pz = std::as_const(*mesh_).z();
  std::uint32_t extent = 0;
  for (const std::uint32_t v : vertices) {
    storage_.float_stamp[v] = generation_;
    extent =
        std::max({extent, magnitude_bits(px[v]), magnitude_bits(py[v]), magnitude_bits(pz[v])});
  }
  filter_.images = images;
  filter_.error = vertices.empty() ? 0.0 : warp_->float_error_m(std::bit_cast<float>(extent));
}

bool MeshRefiner::stroke_vertex(std::uint32_t v) const {
  return storage_.float_stamp[v] == generation_;
}

// S in float at every vertex of the region (stamped) by the warp's float batch.
bool MeshRefiner::warp_region_vertices() {
  const std::span<const std::uint32_t> indices = mesh_->triangle_indices();
  const std::span<const float> px = std::as_const(*mesh_).x();
  const std::span<const float> py = std::as_const(*mesh_).y();
  const std::span<const float> pz = std::as_const(*mesh_).z();
  VertexBatch vb;
  for (const std::uint32_t t : region_.pending) {
    for (std::size_t j = 3 * std::size_t{t}; j < 3 * std::size_t{t} + 3; ++j) {
      const std::uint32_t v = indices[j];
      if (storage_.float_stamp[v] == generation_) continue;
      storage_.float_stamp[v] = generation_;
      const std::size_t k = vb.n;
      vb.vertices[k] = v;
      vb.x[k] = px[v], vb.y[k] = py[v], vb.z[k] = pz[v];
      vb.extent = std::max({vb.extent, std::abs(px[v]), std::abs(py[v]), std::abs(pz[v])});
      if (++vb.n == VertexBatch::kSize) warp_vertices(vb);
    }
  }
  warp_vertices(vb);
  return vb.fast;
}

// Every edge of t not yet batched or settled (by t or its twin) into the batch.
void MeshRefiner::batch_edges(std::uint32_t t, FloatBatch& b) {
  for (std::uint32_t h = 3 * t; h < 3 * t + 3; ++h) batch_edges_of(h, b);
}

// Edge h into the batch unless it (or its twin) already is; marked so that the
// twin is not batched again (settle_batch writes the verdicts).
void MeshRefiner::batch_edges_of(std::uint32_t h, FloatBatch& b) {
  if (storage_.edge_state[h] != kUnknown) return;
  const std::uint32_t g = adjacency_.twin(h);
  storage_.edge_state[h] = kBatched;
  if (real_twin(g)) {
    touch(g / 3);
    storage_.edge_state[g] = kBatched;
  }
  const std::uint32_t* tv = mesh_->triangle_indices().data();
  const std::uint32_t va = tv[h];
  const std::uint32_t vb = tv[h % 3 == 2 ? h - 2 : h + 1];
  batch_edge(h, g, edge_end(va, stroke_vertex(va)), edge_end(vb, stroke_vertex(vb)), b);
}

// An edge's end: its rest position and its image (a stroke vertex's from the
// filter's images; any other end is a fixed point of the warp).
MeshRefiner::EdgeEnd MeshRefiner::edge_end(std::uint32_t v, bool stroke) const {
  const Mesh& m = *mesh_;
  const glm::vec3 p(m.x()[v], m.y()[v], m.z()[v]);
  const VertexImages& im = filter_.images;
  return {p, stroke ? glm::vec3(im.x[v], im.y[v], im.z[v]) : p};
}

// Edge h (twin g, both triangles touched) into the batch: its float midpoint and the
// mean of its ends' images; settled when full.
TWISTER_ALWAYS_INLINE void MeshRefiner::batch_edge(std::uint32_t h, std::uint32_t g,
                                                   const EdgeEnd& a, const EdgeEnd& e,
                                                   FloatBatch& b) {
  const glm::vec3 pm = (a.p + e.p) * 0.5f;
  const std::size_t k = b.n;
  b.edges[k] = h;
  b.twins[k] = g;
  b.x[k] = pm.x, b.y[k] = pm.y, b.z[k] = pm.z;
  b.cx[k] = 0.5 * (double{a.s.x} + double{e.s.x});
  b.cy[k] = 0.5 * (double{a.s.y} + double{e.s.y});
  b.cz[k] = 0.5 * (double{a.s.z} + double{e.s.z});
  if (++b.n == FloatBatch::kSize) settle_batch(b);
}

void MeshRefiner::settle_batch(FloatBatch& b) {
  if (b.n == 0) return;
  std::uint32_t extent_bits = 0;  // of the largest midpoint coordinate
  for (std::size_t k = 0; k < b.n; ++k) {
    extent_bits = std::max(
        {extent_bits, magnitude_bits(b.x[k]), magnitude_bits(b.y[k]), magnitude_bits(b.z[k])});
  }
  const auto batch_extent = std::bit_cast<float>(extent_bits);
  const bool fast = warp_->warp_float(b.x.data(), b.y.data(), b.z.data(), b.ox.data(), b.oy.data(),
                                      b.oz.data(), b.n);
  // |exact midpoint| <= |float midpoint| (1 + 2^-23) per coordinate.
  const double extent = (1.0 + 0x1p-23) * batch_extent;
  // |e_float - e_double| <= (delta_a + delta_b) / 2 + delta_m (fixed points: delta 0).
  const double delta = fast ? warp_->float_error_m(extent) : 0.0;
  const double limit = threshold_m_ - filter_.error - delta - 0x1p-40 * (1.0 + extent);
  const double limit2 = fast && limit > 0.0 ? limit * limit : -1.0;
  std::array<std::uint8_t, FloatBatch::kSize> within{};
  for (std::size_t k = 0; k < b.n; ++k) {
    const double dx = b.cx[k] - double{b.ox[k]};
    const double dy = b.cy[k] - double{b.oy[k]};
    const double dz = b.cz[k] - double{b.oz[k]};
    within[k] = dx * dx + dy * dy + dz * dz <= limit2 ? 1 : 0;
  }
  std::uint32_t settled = 0;
  for (std::size_t k = 0; k < b.n; ++k) settled += within[k];
  filter_.settled += settled;
  filter_.unsettled += static_cast<std::uint32_t>(b.n) - settled;
  for (std::size_t k = 0; k < b.n && b.keep_verdicts; ++k) {
    const std::uint8_t state = within[k] != 0 ? kWithin : kUnknown;
    storage_.edge_state[b.edges[k]] = state;
    if (real_twin(b.twins[k])) storage_.edge_state[b.twins[k]] = state;
  }
  b.n = 0;
}

}  // namespace twister::mesh
