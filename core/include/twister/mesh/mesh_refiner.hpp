// MeshRefiner: adaptive refinement of a Mesh under a warp (docs/math.md §7, the paper's §6
// "adaptive surface subdivision"): an edge (A, B) is split while its midpoint error
// |(S(A) + S(B))/2 - S((A + B)/2)| exceeds the threshold (S evaluated in double by
// a PointWarp on rest positions), recursively, until every edge is within it.
//
// Conforming by construction: every split is a longest-edge bisection (Rivara's LEPP:
// a triangle with an edge over the threshold is bisected along its longest edge, after
// the neighbours along its longest-edge propagation path), and a split always cuts
// every triangle on the edge (one on the boundary, two inside), so the mesh has no
// T-junction after any split. Triangle shapes stay bounded (longest-edge bisection
// never makes an angle smaller than half the smallest one it started from).
// Edges shared by more than two triangles (or of a triangle that repeats a vertex)
// are never split; a triangle that needs one is counted as `blocked`.
//
// The mesh holds rest positions during refine(): a split appends the new vertex at
// the rest-pose midpoint (float of the double midpoint) and rewrites / appends
// triangles (the first triangle keeps its index and orientation). The caller then
// places every vertex where the warp takes it; warped(v) has S(v) for the vertices
// refine() added. At a capacity the refinement stops between two splits (the mesh
// stays conforming) and says which capacity. Deterministic: the same mesh, warp and
// threshold give the same bits (lengths and errors in double from the float
// positions, a FIFO order, ties to the lowest slot).
// Memory: caller-owned spans sized for the mesh's capacities (fits()); no
// allocation. Not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>

#include "twister/base/inline_ring.hpp"
#include "twister/base/result.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/mesh/point_warp.hpp"
#include "twister/mesh/triangle_adjacency.hpp"

namespace twister::mesh {

enum class RefineStop : std::uint8_t {
  done,               // every edge it could split is within the threshold
  vertex_capacity,    // the next split needed a vertex beyond the mesh's capacity
  triangle_capacity,  // the next split needed triangles beyond the mesh's capacity
};

const char* refine_stop_name(RefineStop stop);

struct RefineResult {
  RefineStop stop = RefineStop::done;
  std::uint32_t edges_split = 0;        // = vertices added
  std::uint32_t triangles_added = 0;    // appended
  std::uint32_t triangles_changed = 0;  // triangles that existed before, rewritten
  std::uint32_t blocked = 0;            // over the threshold, on an edge it may not split
};

// Told about each triangle that existed before refine() the first time it is
// rewritten (undo records it); appended triangles are not reported.
class RefineObserver {
 public:
  virtual ~RefineObserver() = default;
  void triangle_changing(std::uint32_t t, const std::array<std::uint32_t, 3>& before) {
    do_triangle_changing(t, before);
  }

 private:
  virtual void do_triangle_changing(std::uint32_t t,
                                    const std::array<std::uint32_t, 3>& before) = 0;
};

struct MeshRefinerStorage {
  TriangleAdjacencyStorage adjacency;
  std::span<double> warped_x;  // per vertex of capacity: S(rest)
  std::span<double> warped_y;
  std::span<double> warped_z;
  std::span<std::uint32_t> warped_stamp;   // per vertex: S valid when == generation
  std::span<std::uint8_t> edge_state;      // 3 per triangle of capacity
  std::span<std::uint8_t> triangle_flags;  // per triangle of capacity
  std::span<std::uint32_t> queue;          // per triangle of capacity
  // refine_around's float filter: per vertex of capacity, S in float and a stamp.
  std::span<float> float_x;
  std::span<float> float_y;
  std::span<float> float_z;
  std::span<std::uint32_t> float_stamp;
};

// Optional for refine_around: S in float at the rest position of every vertex it is
// given, indexed by vertex, computed by the warp's float batch or a kernel within the
// same float_error_m (a commit's live columns), so the float filter warps no vertex.
// Every vertex not given must be a fixed point of the warp (a stroke's weights are 0
// there). Empty: the refiner warps the region's vertices itself.
struct VertexImages {
  std::span<const float> x{};
  std::span<const float> y{};
  std::span<const float> z{};
};

// Bytes of MeshRefinerStorage per vertex and per triangle of capacity.
// (S cache and its stamp, the vertex table, S in float and its stamp; twins, incidence,
// edge states, flags, queue)
inline constexpr std::size_t kRefinerBytesPerVertex =
    3 * sizeof(double) + 2 * sizeof(std::uint32_t) + 3 * sizeof(float) + sizeof(std::uint32_t);
inline constexpr std::size_t kRefinerBytesPerTriangle =
    6 * sizeof(std::uint32_t) + 3 + 1 + sizeof(std::uint32_t);

class MeshRefiner {
 public:
  explicit MeshRefiner(MeshRefinerStorage storage);
  MeshRefiner(const MeshRefiner&) = delete;
  MeshRefiner& operator=(const MeshRefiner&) = delete;

  // The storage holds every vertex and triangle `mesh` can ever have.
  bool fits(const Mesh& mesh) const;

  // Refines `mesh` (rest positions) until every edge's midpoint error under `warp`
  // is at most `threshold_m`, or a capacity is reached (see RefineResult::stop).
  // `observer` (may be null) hears of each pre-existing triangle before it changes.
  // failed_precondition: the storage does not fit the mesh; invalid_argument: the
  // threshold is not a finite number > 0. Nothing changes on error.
  Result<RefineResult> refine(Mesh& mesh, const PointWarp& warp, double threshold_m,
                              RefineObserver* observer = nullptr);

  // The same refinement over the triangles that have a vertex in `vertices` (the
  // stroke's influenced vertices) and whatever their splits reach (the longest-edge
  // propagation paths): cost proportional to the region, not the mesh. The edge-
  // triangle adjacency persists between calls while the mesh's topology_version()
  // and vertex count are what the last call left (else it is rebuilt once, O(mesh)).
  // Order: the region's triangles in ascending index, a triangle a split changes
  // before its index is reached visited there, then a FIFO (exactly the order
  // refine() would use), so the result is bit-identical to refine() whenever every
  // edge over the threshold at the start has a triangle in the region
  // (docs/refinement.md "Local refinement"). A mesh with an edge shared by more than
  // two triangles or a vertex whose triangles are not one fan is refined by refine().
  // `images` (optional, see VertexImages): S in float of `vertices`.
  // Errors as refine().
  Result<RefineResult> refine_around(Mesh& mesh, const PointWarp& warp, double threshold_m,
                                     std::span<const std::uint32_t> vertices,
                                     RefineObserver* observer = nullptr, VertexImages images = {});

  // S of vertex v (rest position as of the last refine()); valid for every vertex
  // that refine() added (asserted).
  glm::dvec3 warped(std::uint32_t v) const;

  // The criterion: |(S(a) + S(b))/2 - S((a + b)/2)| in metres.
  static double midpoint_error(glm::dvec3 a, glm::dvec3 b, const PointWarp& warp);

 private:
  enum class Split : std::uint8_t { done, blocked, no_room };

  void start(Mesh& mesh, const PointWarp& warp, double threshold_m, RefineObserver* observer);
  glm::dvec3 rest(std::uint32_t v) const;
  glm::dvec3 warped_of(std::uint32_t v);
  std::uint32_t edge_vertex(std::uint32_t h, std::uint32_t end) const;
  double length2(std::uint32_t h) const;
  std::uint32_t longest(std::uint32_t t) const;
  bool offending(std::uint32_t h);
  bool has_offending_edge(std::uint32_t t);
  Split bisect(std::uint32_t t);
  bool room(std::uint32_t triangles);
  void split(std::uint32_t h);
  std::uint32_t split_one(std::uint32_t h, std::uint32_t m);
  void changing(std::uint32_t t);
  void push(std::uint32_t t);
  void run();
  // Persistent adjacency (refine_around).
  Status build_adjacency(const Mesh& mesh);
  bool adjacency_current(const Mesh& mesh) const;
  void keep_adjacency(const Mesh& mesh);
  std::uint32_t slot(std::uint32_t t, std::uint32_t v) const;
  template <typename F>
  std::uint32_t for_fan(std::uint32_t v, F&& f) const;
  void touch(std::uint32_t t);
  void reset_triangle_stamps();
  void collect_region(std::span<const std::uint32_t> vertices);
  bool enter_region(std::uint32_t t);
  void set_region(std::span<std::uint32_t> list);
  void sort_region();
  // The float filter (docs/refinement.md "The float filter").
  bool collect_and_settle(std::span<const std::uint32_t> vertices, VertexImages images);
  bool settle_stroke_edges(std::span<const std::uint32_t> vertices);
  void stamp_images(std::span<const std::uint32_t> vertices, VertexImages images);
  bool stroke_vertex(std::uint32_t v) const;
  bool warp_region_vertices();
  struct FloatBatch;
  void batch_edges(std::uint32_t t, FloatBatch& b);
  void batch_edges_of(std::uint32_t h, FloatBatch& b);
  struct EdgeEnd {
    glm::vec3 p;  // rest
    glm::vec3 s;  // image
  };
  EdgeEnd edge_end(std::uint32_t v, bool stroke) const;
  void batch_edge(std::uint32_t h, std::uint32_t g, const EdgeEnd& a, const EdgeEnd& e,
                  FloatBatch& b);
  template <typename Tri, typename Edge>
  void walk_fan(std::uint32_t v, Tri&& tri, Edge&& edge) const;
  template <typename AtV, typename Across>
  void walk_ring(std::uint32_t v, AtV&& at_v, Across&& across) const;
  void settle_batch(FloatBatch& b);
  struct VertexBatch;
  void warp_vertices(VertexBatch& b);
  bool next_triangle(std::uint32_t& t);

  MeshRefinerStorage storage_;
  TriangleAdjacency adjacency_;
  std::uint32_t generation_ = 0;
  // One refine() call.
  Mesh* mesh_ = nullptr;
  const PointWarp* warp_ = nullptr;
  RefineObserver* observer_ = nullptr;
  double threshold_m_ = 0.0;
  std::uint32_t triangles_before_ = 0;
  SpanRing<std::uint32_t> queue_;  // triangles to look at (kQueued), over storage_.queue
  RefineResult result_{};
  // refine_around: the region's original triangles still to visit in index order
  // (sorted list + a min-heap of those a split changed before their turn), in the
  // adjacency's scratch after build (stamps, list, heap: one triangle capacity each).
  struct RegionOrder {
    bool local = false;
    bool pending_phase = false;
    std::int64_t cursor = -1;  // the original triangle visited last
    std::span<std::uint32_t> stamps;
    std::span<std::uint32_t> pending;
    std::size_t pending_pos = 0;
    std::span<std::uint32_t> heap;
    std::size_t heap_size = 0;
  } region_;
  // The adjacency (twins, a corner triangle per vertex) is current for this mesh.
  struct AdjacencyKey {
    const Mesh* mesh = nullptr;
    std::uint64_t version = 0;
    std::size_t vertices = 0;
    bool manifold = false;  // every edge has <= 2 triangles, every vertex one fan
    bool oriented = false;  // every edge runs against its twin (consistent winding)
  } adjacency_key_;
  // The float filter of the last refine_around.
  struct FloatFilter {
    VertexImages images;          // S in float at the stamped vertices
    double error = 0.0;           // bound on |S in float - S in double| there
    std::uint32_t settled = 0;    // edges found within the threshold in float
    std::uint32_t unsettled = 0;  // edges left to the double criterion
  } filter_;

 public:
  // Edges the last refine_around() found within the threshold by the float filter
  // alone (the rest of its verdicts were computed in double).
  std::uint32_t settled_in_float() const { return filter_.settled; }
};

namespace internal {
template <std::size_t kVertices, std::size_t kTriangles>
struct MeshRefinerArrays {
  std::array<std::uint32_t, 3 * kTriangles> twins{};
  std::array<std::uint32_t, kVertices + 1> vertex_offsets{};
  std::array<std::uint32_t, 3 * kTriangles> incident{};
  std::array<double, kVertices> warped_x{};
  std::array<double, kVertices> warped_y{};
  std::array<double, kVertices> warped_z{};
  std::array<std::uint32_t, kVertices> warped_stamp{};
  std::array<std::uint8_t, 3 * kTriangles> edge_state{};
  std::array<std::uint8_t, kTriangles> triangle_flags{};
  std::array<std::uint32_t, kTriangles> queue{};
  std::array<float, kVertices> float_x{};
  std::array<float, kVertices> float_y{};
  std::array<float, kVertices> float_z{};
  std::array<std::uint32_t, kVertices> float_stamp{};

  MeshRefinerStorage spans() {
    return {{twins, vertex_offsets, incident},
            warped_x,
            warped_y,
            warped_z,
            warped_stamp,
            edge_state,
            triangle_flags,
            queue,
            float_x,
            float_y,
            float_z,
            float_stamp};
  }
};
}  // namespace internal

// A refiner owning storage for meshes of up to kVertices / kTriangles. Large: place
// it in static storage or the start-up arena.
template <std::size_t kVertices, std::size_t kTriangles>
class MeshRefinerWithStorage : private internal::MeshRefinerArrays<kVertices, kTriangles>,
                               public MeshRefiner {
 public:
  MeshRefinerWithStorage() : MeshRefiner(this->spans()) {}
};

}  // namespace twister::mesh
