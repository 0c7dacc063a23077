// Symmetric strokes through the session (issue 26; docs/math.md §11): a mesh symmetric
// under G, random one- and two-hand strokes (grab points on vertices anywhere, and
// points near or on a mirror plane or the axis), committed through SculptSession:
//  - the committed mesh is symmetric under G (float mesh: 1e-5 of the scene size);
//  - the plan the commit used is symmetric in double (1e-6 of the scene size) and takes
//    every grab point and image to its end pose (1e-6);
//  - undo and redo are bit-exact, a replay of the journal is bit-identical;
//  - clutch chains stay symmetric; with refinement on the refined mesh is symmetric
//    (every vertex's image is a vertex);
//  - scodef (§11.8): the plan symmetric in double and every constraint point and image
//    at its target (1e-6), the commit exactly the rounded double warp, symmetric, undo
//    and redo exact, replay bit-identical; a trivial group is the old plan bit for bit.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "fakes/fake_storage.hpp"
#include "session_harness.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/journal/journal_writer.hpp"
#include "twister/math/symmetry.hpp"
#include "twister/meshio/mesh_buffer.hpp"
#include "twister/session/sculpt_session.hpp"

namespace twister::session {
namespace {

using test_support::kFreeze1;
using test_support::kGrab0;
using test_support::kGrab1;

constexpr std::size_t kCap = 6000;
using SymSession = SculptSessionWithStorage<kCap, kCap, 1 << 16, 32, 2 * kCap>;
using SymStorage = twister::test::FakeStorageWithStorage<1 << 20>;
constexpr double kScene = 2.0;  // the unit sphere's size

// A latitude-longitude unit sphere with its poles on `axis`, `lon` longitudes (angles
// 2 pi j / lon from the next axis towards the third) and `lat` rings, each quad cut
// into four triangles about its centre (so the triangulation too is symmetric):
// symmetric under the mirrors of every coordinate plane when lon % 4 == 0 and under
// n-fold rotations about `axis` (with the mirrors through it) when n divides lon.
void make_sphere(mesh::Mesh& m, int axis, int lon, int lat) {
  m.clear();
  const int b = (axis + 1) % 3;
  const int c = (axis + 2) % 3;
  auto put = [&](double phi, double th) {
    glm::dvec3 p(0.0);
    p[axis] = std::cos(phi);
    p[b] = std::sin(phi) * std::cos(th);
    p[c] = std::sin(phi) * std::sin(th);
    return *m.add_vertex(glm::vec3(p));
  };
  const double dphi = std::numbers::pi / (lat + 1);
  const double dth = 2.0 * std::numbers::pi / lon;
  const std::uint32_t north = put(0.0, 0.0);
  std::vector<std::uint32_t> ring;
  for (int i = 1; i <= lat; ++i) {
    for (int j = 0; j < lon; ++j) ring.push_back(put(dphi * i, dth * j));
  }
  const std::uint32_t south = put(std::numbers::pi, 0.0);
  const auto at = [&](int i, int j) {
    return ring[static_cast<std::size_t>((i - 1) * lon + ((j % lon) + lon) % lon)];
  };
  for (int j = 0; j < lon; ++j) {
    (void)m.add_triangle(north, at(1, j), at(1, j + 1));
    for (int i = 1; i < lat; ++i) {
      const std::uint32_t centre = put(dphi * (i + 0.5), dth * (j + 0.5));
      (void)m.add_triangle(centre, at(i, j), at(i + 1, j));
      (void)m.add_triangle(centre, at(i + 1, j), at(i + 1, j + 1));
      (void)m.add_triangle(centre, at(i + 1, j + 1), at(i, j + 1));
      (void)m.add_triangle(centre, at(i, j + 1), at(i, j));
    }
    (void)m.add_triangle(south, at(lat, j + 1), at(lat, j));
  }
}

struct SymStation {
  SymStation(const math::SymmetrySpec& spec, SculptSessionConfig config, int lon, int lat,
             bool with_journal = true)
      : buffer(kCap, 2 * kCap), writer(storage) {
    const int axis = spec.kind == math::SymmetryKind::rotation ||
                             spec.kind == math::SymmetryKind::rotation_mirror
                         ? spec.axis
                         : 2;
    make_sphere(buffer.mesh(), axis, lon, lat);
    if (with_journal) {
      EXPECT_TRUE(writer.open().ok());
    }
    config.symmetry = spec;
    session = std::make_unique<SymSession>(config, buffer.mesh(), with_journal ? &writer : nullptr);
  }
  mesh::Mesh& mesh() { return buffer.mesh(); }
  void button(std::uint8_t line, bool pressed) {
    EXPECT_TRUE(session->feed_button({line, pressed, now_us}).ok());
  }
  void hand(std::uint8_t h, const math::Frame& f) {
    EXPECT_TRUE(session->set_hand(h, true, f).ok());
  }
  SessionEvents tick() {
    now_us += 10'000;
    return session->step(now_us);
  }
  meshio::MeshBuffer buffer;
  SymStorage storage;
  journal::JournalWriter writer;
  std::unique_ptr<SymSession> session;
  ports::TimestampUs now_us = 0;
};

std::vector<glm::vec3> positions(const mesh::Mesh& m) {
  std::vector<glm::vec3> out(m.vertex_count());
  for (std::size_t v = 0; v < out.size(); ++v) out[v] = m.position(static_cast<std::uint32_t>(v));
  return out;
}

// Index of the vertex at q (sorted by x, a window search); -1: none within tol.
struct VertexFinder {
  explicit VertexFinder(const std::vector<glm::vec3>& p) : pts(p), order(p.size()) {
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return pts[a].x < pts[b].x; });
  }
  long find(glm::dvec3 q, double tol) const {
    auto lo = std::lower_bound(order.begin(), order.end(), q.x - tol,
                               [&](std::size_t i, double x) { return pts[i].x < x; });
    long best = -1;
    double best_d = tol;
    for (auto it = lo; it != order.end() && pts[*it].x <= q.x + tol; ++it) {
      const double d = glm::length(glm::dvec3(pts[*it]) - q);
      if (d <= best_d) {
        best_d = d;
        best = static_cast<long>(*it);
      }
    }
    return best;
  }
  const std::vector<glm::vec3>& pts;
  std::vector<std::size_t> order;
};

// image[g][v]: the vertex at g p_v in the rest mesh.
std::vector<std::vector<long>> vertex_images(const math::SymmetryGroup& group,
                                             const std::vector<glm::vec3>& rest) {
  VertexFinder find(rest);
  std::vector<std::vector<long>> image(group.order(), std::vector<long>(rest.size()));
  for (std::size_t g = 0; g < group.order(); ++g) {
    for (std::size_t v = 0; v < rest.size(); ++v) {
      image[g][v] = find.find(group.element(g) * glm::dvec3(rest[v]), 1e-5);
    }
  }
  return image;
}

// The largest |F(g v) - g F(v)| over the mesh.
double asymmetry(const math::SymmetryGroup& group, const std::vector<std::vector<long>>& image,
                 const std::vector<glm::vec3>& now) {
  double worst = 0.0;
  for (std::size_t g = 1; g < group.order(); ++g) {
    for (std::size_t v = 0; v < now.size() && v < image[g].size(); ++v) {
      if (image[g][v] < 0) return 1e9;
      const glm::dvec3 a(now[static_cast<std::size_t>(image[g][v])]);
      const double e = glm::length(a - group.element(g) * glm::dvec3(now[v]));
      worst = std::max(worst, e);
    }
  }
  return worst;
}

// Distance from q to the triangle abc.
double point_triangle(glm::dvec3 q, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double nn = glm::dot(n, n);
  if (nn > 0.0) {
    const glm::dvec3 p = q - n * (glm::dot(q - a, n) / nn);
    const bool inside = glm::dot(glm::cross(b - a, p - a), n) >= 0.0 &&
                        glm::dot(glm::cross(c - b, p - b), n) >= 0.0 &&
                        glm::dot(glm::cross(a - c, p - c), n) >= 0.0;
    if (inside) return glm::length(q - p);
  }
  auto seg = [&](glm::dvec3 u, glm::dvec3 v) {
    const glm::dvec3 d = v - u;
    const double dd = glm::dot(d, d);
    const double t = dd > 0.0 ? std::clamp(glm::dot(q - u, d) / dd, 0.0, 1.0) : 0.0;
    return glm::length(q - (u + t * d));
  };
  return std::min({seg(a, b), seg(b, c), seg(c, a)});
}

// The largest distance from an image of a vertex to the mesh's surface (refined meshes:
// their vertices lie on the symmetric warped surface, the triangles are its chords).
// Only the vertices that differ from `rest` (moved or added) are checked.
double surface_asymmetry(const math::SymmetryGroup& group, const mesh::Mesh& m,
                         const std::vector<glm::vec3>& rest = {}) {
  constexpr double kReach = 0.05;  // beyond what is asserted: the bounding boxes prune
  struct Tri {
    glm::dvec3 a, b, c, lo, hi;
  };
  std::vector<Tri> tris(m.triangle_count());
  for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
    const auto v = m.triangle(t);
    Tri& x = tris[t];
    x.a = glm::dvec3(m.position(v[0]));
    x.b = glm::dvec3(m.position(v[1]));
    x.c = glm::dvec3(m.position(v[2]));
    x.lo = glm::min(x.a, glm::min(x.b, x.c)) - kReach;
    x.hi = glm::max(x.a, glm::max(x.b, x.c)) + kReach;
  }
  double worst = 0.0;
  for (std::size_t g = 1; g < group.order(); ++g) {
    for (std::uint32_t v = 0; v < m.vertex_count(); ++v) {
      if (v < rest.size() && rest[v] == m.position(v)) continue;
      const glm::dvec3 q = group.element(g) * glm::dvec3(m.position(v));
      double best = kReach;
      for (const Tri& x : tris) {
        if (q.x < x.lo.x || q.y < x.lo.y || q.z < x.lo.z || q.x > x.hi.x || q.y > x.hi.y ||
            q.z > x.hi.z) {
          continue;
        }
        best = std::min(best, point_triangle(q, x.a, x.b, x.c));
        if (best == 0.0) break;
      }
      worst = std::max(worst, best);
    }
  }
  return worst;
}

// A group of every kind: mirror planes (1..7), Cn or Cnv about x, y or z, n = 2..12.
rc::Gen<math::SymmetrySpec> gen_spec() {
  return rc::gen::apply(
      [](int kind, int planes, int axis, int n) {
        if (kind == 0) {
          return math::SymmetrySpec{math::SymmetryKind::mirrors, static_cast<std::uint8_t>(planes),
                                    0, 0};
        }
        return math::SymmetrySpec{
            kind == 1 ? math::SymmetryKind::rotation : math::SymmetryKind::rotation_mirror, 0,
            static_cast<std::uint8_t>(axis), static_cast<std::uint8_t>(n)};
      },
      rc::gen::inRange(0, 3), rc::gen::inRange(1, 8), rc::gen::inRange(0, 3),
      rc::gen::inRange(2, 13));
}

// Longitudes for `spec`: a multiple of the rotation order, about 24 (a multiple of 4
// for the mirrors).
int longitudes(const math::SymmetrySpec& spec) {
  if (spec.kind == math::SymmetryKind::mirrors) return 24;
  const int n = spec.order;
  return n * ((24 + n - 1) / n);
}

glm::dvec3 unit(glm::dvec3 v) {
  const double l = glm::length(v);
  return l > 1e-9 ? v / l : glm::dvec3(0, 0, 1);
}

// A frame at `origin` turned by `angle` about `axis`.
math::Frame turned(glm::dvec3 origin, glm::dvec3 axis, double angle) {
  const glm::dvec3 a = unit(axis);
  auto rot = [&](glm::dvec3 v) {
    return v * std::cos(angle) + glm::cross(a, v) * std::sin(angle) +
           a * glm::dot(a, v) * (1.0 - std::cos(angle));
  };
  return math::frame_from_uv(origin, rot({1, 0, 0}), rot({0, 1, 0}));
}

struct HandStroke {
  glm::dvec3 grab{};
  long vertex = -1;  // the grab is on this vertex
  glm::dvec3 axis0{}, axis1{};
  double angle0 = 0.0, angle1 = 0.0;
  glm::dvec3 move{};
};

// A grab point: a vertex anywhere, or a point near (or on) a mirror plane or the axis.
HandStroke gen_hand(const math::SymmetrySpec& spec, const mesh::Mesh& m, double radius) {
  HandStroke h;
  const int where = *rc::gen::inRange(0, 3);
  if (where == 0) {
    h.vertex = *rc::gen::inRange<long>(0, static_cast<long>(m.vertex_count()));
    h.grab = glm::dvec3(m.position(static_cast<std::uint32_t>(h.vertex)));
  } else {
    h.grab = glm::dvec3(*rc::gen::inRange(-900, 901), *rc::gen::inRange(-900, 901),
                        *rc::gen::inRange(-900, 901)) /
             1000.0;
    static constexpr double kNear[] = {0.0, 1e-4, 1e-3, 1e-2, 0.1, 0.3};
    const double d = kNear[*rc::gen::inRange(0, 6)] * radius;
    if (spec.kind == math::SymmetryKind::mirrors) {
      int c = *rc::gen::inRange(0, 3);
      while ((spec.mirrors & (1 << c)) == 0) c = (c + 1) % 3;
      h.grab[c] = d;
    } else {
      const int a = spec.axis;
      glm::dvec3 off = h.grab;
      off[a] = 0.0;
      const double l = glm::length(off);
      if (l > 0.0) off *= d / l;
      h.grab = off;
      h.grab[a] = *rc::gen::inRange(-900, 901) / 1000.0;
    }
  }
  auto vec = [] {
    return glm::dvec3(*rc::gen::inRange(-100, 101), *rc::gen::inRange(-100, 101),
                      *rc::gen::inRange(-100, 101)) /
           100.0;
  };
  h.axis0 = vec();
  h.axis1 = vec();
  h.angle0 = *rc::gen::inRange(-300, 301) / 100.0;
  h.angle1 = *rc::gen::inRange(-250, 251) / 100.0;
  h.move = vec() * 0.4;
  return h;
}

math::Frame pose_at(const HandStroke& h, double f) {
  const math::Frame start = turned(h.grab, h.axis0, h.angle0);
  if (f == 0.0) return start;
  // The turn about axis1 applied after the start orientation, by f of angle1.
  const glm::dvec3 a = unit(h.axis1);
  const double t = f * h.angle1;
  auto rot = [&](glm::dvec3 v) {
    return v * std::cos(t) + glm::cross(a, v) * std::sin(t) +
           a * glm::dot(a, v) * (1.0 - std::cos(t));
  };
  return math::frame_from_uv(h.grab + f * h.move, rot(start.u), rot(start.v));
}

// The checks of §11 on the open plan (double): equivariance at random points and near
// every grab point, and every grab point and image at its end pose.
void check_plan(const math::WarpPlan& plan, const math::SymmetryGroup& group) {
  RC_ASSERT(plan.symmetric());
  const math::SymmetricWarp& sw = *plan.symmetric_warp();
  for (std::size_t h = 0; h < plan.hand_count(); ++h) {
    const glm::dvec3 o = sw.start_frame(h).origin;
    const glm::dvec3 move = plan.end_frame(h).origin - plan.start_frame(h).origin;
    glm::dmat3 proj(0.0);
    std::size_t stab = 0;
    for (std::size_t g = 0; g < group.order(); ++g) {
      // The group's own test for "the grab point is its own image" (SymmetricWarp::build).
      if (glm::length(group.element(g) * o - o) <= math::kCoincidentGrabFraction * plan.radius()) {
        proj += group.element(g);
        ++stab;
      }
    }
    RC_ASSERT(stab == sw.stabiliser_size(h));
    proj /= static_cast<double>(stab);
    const glm::dvec3 end = o + proj * move;
    for (std::size_t g = 0; g < group.order(); ++g) {
      const glm::dmat3& e = group.element(g);
      const double err = glm::length(plan.warp_point(e * o) - e * end);
      RC_ASSERT(err <= 1e-6 * kScene);
    }
  }
  for (int i = 0; i < 24; ++i) {
    glm::dvec3 p(*rc::gen::inRange(-1200, 1201), *rc::gen::inRange(-1200, 1201),
                 *rc::gen::inRange(-1200, 1201));
    p /= 1000.0;
    if (i % 2 == 1) {  // near a grab point
      const std::size_t k = static_cast<std::size_t>(i) % sw.grab_point_count();
      p = sw.grab_point(k) + p * 0.05 * plan.radius();
    }
    const glm::dvec3 fp = plan.warp_point(p);
    for (std::size_t g = 1; g < group.order(); ++g) {
      const glm::dmat3& e = group.element(g);
      RC_ASSERT(glm::length(plan.warp_point(e * p) - e * fp) <= 1e-6 * kScene);
    }
  }
}

struct StrokeShape {
  math::SymmetrySpec spec;
  math::WarpMethod method = math::WarpMethod::twister;
  double radius = 1.0;
  bool refine = false;
};

SculptSessionConfig config_for(const StrokeShape& shape) {
  SculptSessionConfig c = test_support::test_config();
  c.method = shape.method;
  c.interaction.initial_radius_m = static_cast<float>(shape.radius);
  c.interaction.radius_min_m = 0.01f;
  c.refine.enabled = shape.refine;
  c.refine.threshold_m = 0.02;
  return c;
}

// The smallest distance between two distinct grab points (images included), over the
// radius: below ~1e-2 the warp between them is steep (§11.4) and amplifies the float
// mesh's own asymmetry (a rotated float vertex is off its exact image by ~1e-7).
double separation(const math::WarpPlan& plan) {
  const math::SymmetricWarp& sw = *plan.symmetric_warp();
  double least = 1.0;
  for (std::size_t k = 0; k < sw.grab_point_count(); ++k) {
    for (std::size_t j = 0; j < k; ++j) {
      least = std::min(least, glm::length(sw.grab_point(k) - sw.grab_point(j)) / plan.radius());
    }
  }
  return least;
}

struct StrokeResult {
  bool done = false;
  double separation = 1.0;
  std::vector<glm::vec3> expected;  // one step, no chain: the commit's positions
};

// Grabs with `hands` (1 or 2), moves them to their end poses in three steps, checks the
// plan, releases: one commit. With `chain`, hand 1 (two hands) freezes half way, moves
// back, unfreezes and goes on (a clutch chain). Returns false when refused.
StrokeResult stroke(SymStation& s, const math::SymmetryGroup& group,
                    const std::vector<HandStroke>& hands, bool chain) {
  StrokeResult out;
  for (std::size_t h = 0; h < hands.size(); ++h)
    s.hand(static_cast<std::uint8_t>(h), pose_at(hands[h], 0.0));
  s.button(kGrab0, true);
  if (hands.size() == 2) s.button(kGrab1, true);
  const SessionEvents grabbed = s.tick();
  if (test_support::has_event(grabbed, SessionEventKind::refused)) return out;
  RC_ASSERT(s.session->live().active);
  for (int k = 1; k <= 3; ++k) {
    for (std::size_t h = 0; h < hands.size(); ++h) {
      s.hand(static_cast<std::uint8_t>(h), pose_at(hands[h], k / 3.0));
    }
    if (chain && k == 2) {
      s.button(kFreeze1, true);
      s.tick();
      s.hand(1, pose_at(hands[1], 0.0));  // the clutch: this motion does not warp
      s.tick();
      s.button(kFreeze1, false);
    }
    s.tick();
    const math::WarpPlan& plan = *s.session->live().plan;
    if (k == 1) out.separation = separation(plan);
    if (!chain) check_plan(plan, group);
    if (!chain && k == 3) {
      // What the commit writes, to float precision: F(rest) of the double warp.
      out.expected = positions(s.mesh());
      for (const std::uint32_t v : plan.indices()) {
        out.expected[v] = glm::vec3(plan.warp_point(glm::dvec3(out.expected[v])));
      }
    }
  }
  s.button(kGrab0, false);
  if (hands.size() == 2) s.button(kGrab1, false);
  const SessionEvents released = s.tick();
  RC_ASSERT(test_support::has_event(released, SessionEventKind::committed));
  RC_ASSERT(!s.session->live().active);
  out.done = true;
  return out;
}

RC_GTEST_PROP(SymmetricSession, StrokesStaySymmetricExactAndReplay, ()) {
  StrokeShape shape;
  shape.spec = *gen_spec();
  shape.method = *rc::gen::element(math::WarpMethod::twister, math::WarpMethod::rottran);
  shape.radius = *rc::gen::element(0.3, 0.6, 1.0);
  const bool chain = *rc::gen::inRange(0, 4) == 0;
  const std::size_t hand_count = chain ? 2 : *rc::gen::inRange<std::size_t>(1, 3);
  SymStation s(shape.spec, config_for(shape), longitudes(shape.spec), 11);
  math::SymmetryGroup group;
  RC_ASSERT(group.set(shape.spec).ok());
  const std::vector<glm::vec3> rest = positions(s.mesh());
  const auto image = vertex_images(group, rest);
  RC_ASSERT(asymmetry(group, image, rest) <= 1e-6 * kScene);
  std::vector<HandStroke> hands;
  for (std::size_t h = 0; h < hand_count; ++h)
    hands.push_back(gen_hand(shape.spec, s.mesh(), shape.radius));
  RC_LOG() << "kind " << int(shape.spec.kind) << " mirrors " << int(shape.spec.mirrors) << " axis "
           << int(shape.spec.axis) << " order " << int(shape.spec.order) << " method "
           << int(shape.method) << " chain " << chain << " radius " << shape.radius << "\n";
  for (const HandStroke& h : hands) {
    RC_LOG() << "grab " << h.grab.x << " " << h.grab.y << " " << h.grab.z << " vertex " << h.vertex
             << "\n";
  }
  const StrokeResult done = stroke(s, group, hands, chain);
  if (!done.done) {
    // Refused only when the hands are within the machine's 1 cm of each other, or one
    // sits on an image of the other (§11.4).
    bool coincide = hands.size() == 2 && glm::length(hands[0].grab - hands[1].grab) < 0.011;
    for (std::size_t g = 0; g < group.order() && hands.size() == 2; ++g) {
      coincide = coincide || glm::length(group.element(g) * hands[0].grab - hands[1].grab) <= 1e-6;
    }
    RC_ASSERT(coincide);
    return;
  }
  const std::vector<glm::vec3> after = positions(s.mesh());
  // The commit wrote the warp of the rest positions (one step) by the float path
  // (docs/math.md §11.7): within 1e-5 of the scene size of the double warp.
  if (!chain) {
    double worst = 0.0;
    for (std::size_t i = 0; i < after.size(); ++i) {
      worst = std::max(worst, static_cast<double>(glm::length(after[i] - done.expected[i])));
    }
    RC_ASSERT(worst <= 1e-5 * kScene);
  }
  // The float mesh: exactly symmetric for mirrors (negation is exact in float); for
  // rotations its ~1e-7 asymmetry is amplified where grab points are close (steep warp).
  const bool mirrors = shape.spec.kind == math::SymmetryKind::mirrors;
  RC_TAG(mirrors || done.separation >= 1e-2 ? "float mesh checked" : "steep: double checks only");
  if (mirrors || done.separation >= 1e-2) {
    RC_ASSERT(asymmetry(group, image, after) <= 1e-5 * kScene);
  }
  // A grab on a vertex (off the fixed sets): the vertex reaches the hand's end point.
  for (std::size_t h = 0; h < hands.size() && !chain; ++h) {
    if (hands[h].vertex < 0) continue;
    bool fixed = false;
    for (std::size_t g = 1; g < group.order(); ++g) {
      fixed = fixed || glm::length(group.element(g) * hands[h].grab - hands[h].grab) < 1e-6;
    }
    if (fixed) continue;
    const glm::dvec3 target = pose_at(hands[h], 1.0).origin;
    RC_ASSERT(glm::length(glm::dvec3(after[static_cast<std::size_t>(hands[h].vertex)]) - target) <=
              1e-6 * kScene);
  }
  // Undo and redo (every commit of the stroke: a chain has one per step): bit-exact.
  const std::size_t commits = s.session->state().undo_depth;
  RC_ASSERT(commits == (chain ? 3u : 1u));
  for (std::size_t i = 0; i < commits; ++i) RC_ASSERT(s.session->undo().ok());
  RC_ASSERT(positions(s.mesh()) == rest);
  for (std::size_t i = 0; i < commits; ++i) RC_ASSERT(s.session->redo().ok());
  RC_ASSERT(positions(s.mesh()) == after);
  // The journal replays to the same bits, whatever the replaying session's symmetry.
  SymStation r(shape.spec, config_for(shape), longitudes(shape.spec), 11, false);
  RC_ASSERT(r.session->set_symmetry({}).ok());
  journal::JournalReader reader(s.storage);
  RC_ASSERT(reader.open().ok());
  const auto n = r.session->replay(reader);
  RC_ASSERT(n.ok());
  RC_ASSERT(positions(r.mesh()) == after);
}

RC_GTEST_PROP(SymmetricSession, RefinedMeshStaysSymmetric, ()) {
  StrokeShape shape;
  shape.spec = *gen_spec();
  shape.method = *rc::gen::element(math::WarpMethod::twister, math::WarpMethod::rottran);
  shape.radius = *rc::gen::element(0.6, 1.0);
  shape.refine = true;
  SymStation s(shape.spec, config_for(shape), longitudes(shape.spec), 11);
  math::SymmetryGroup group;
  RC_ASSERT(group.set(shape.spec).ok());
  const std::vector<glm::vec3> rest = positions(s.mesh());
  RC_ASSERT(asymmetry(group, vertex_images(group, rest), rest) <= 1e-6 * kScene);
  std::vector<HandStroke> hands{gen_hand(shape.spec, s.mesh(), shape.radius)};
  hands[0].vertex = -1;
  const StrokeResult done = stroke(s, group, hands, false);
  if (!done.done) RC_FAIL("one hand refused");
  const std::vector<glm::vec3> after = positions(s.mesh());
  const std::size_t rest_count = 2 + 11 * static_cast<std::size_t>(longitudes(shape.spec)) +
                                 10 * static_cast<std::size_t>(longitudes(shape.spec));
  RC_TAG(after.size() > rest_count ? "refined" : "unrefined");
  // The refined vertices are F(rest midpoint) with F equivariant: every vertex's image
  // lies on the refined surface to within the refinement's chord error (a split on one
  // side need not be mirrored on the other: longest-edge ties of a mirrored triangle).
  if (shape.spec.kind == math::SymmetryKind::mirrors || done.separation >= 1e-2) {
    const double off = surface_asymmetry(group, s.mesh(), rest);
    RC_TAG(off <= 1e-5   ? "images on the surface within 1e-5"
           : off <= 0.02 ? "within 0.02 (threshold)"
                         : "within 0.04");
    RC_ASSERT(off <= 2.0 * 0.02);
  }
  // Replayed with refinement off in its configuration: the record's threshold rules.
  SymStation r(shape.spec, config_for(shape), longitudes(shape.spec), 11, false);
  journal::JournalReader reader(s.storage);
  RC_ASSERT(reader.open().ok());
  RC_ASSERT(r.session->replay(reader).ok());
  RC_ASSERT(positions(r.mesh()) == after);
}

// scodef's constraint points O + e a (a = U, V, W) of every hand and their images at
// their targets g.(1/|S|) sum_s s.(O' + R s^T e a) (§11.8; S the grab point's
// stabiliser, trivial off the fixed sets), and the plan symmetric (check_plan's probes).
void check_scodef_plan(const math::WarpPlan& plan, const math::SymmetryGroup& group) {
  RC_ASSERT(plan.symmetric());
  const math::SymmetricWarp& sw = *plan.symmetric_warp();
  const double e = math::kScodefEpsilonFraction * plan.radius();
  for (std::size_t h = 0; h < plan.hand_count(); ++h) {
    const math::Frame& a = plan.start_frame(h);
    const math::Frame& b = plan.end_frame(h);
    const glm::dvec3 o = sw.start_frame(h).origin;
    const glm::dvec3 end = b.origin + (o - a.origin);
    const glm::dmat3 turn = glm::dmat3(b.u, b.v, b.w) * glm::transpose(glm::dmat3(a.u, a.v, a.w));
    for (const glm::dvec3& axis : {a.u, a.v, a.w}) {
      glm::dvec3 target(0.0);
      int stab = 0;
      for (std::size_t g = 0; g < group.order(); ++g) {
        const glm::dmat3& s = group.element(g);
        if (glm::length(s * o - o) > math::kCoincidentGrabFraction * plan.radius()) continue;
        target += s * (end + turn * (glm::transpose(s) * (e * axis)));
        ++stab;
      }
      target /= static_cast<double>(stab);
      for (std::size_t g = 0; g < group.order(); ++g) {
        const glm::dmat3& m = group.element(g);
        RC_ASSERT(glm::length(plan.warp_point(m * (o + e * axis)) - m * target) <= 1e-6 * kScene);
      }
    }
  }
  for (int i = 0; i < 24; ++i) {
    glm::dvec3 p(*rc::gen::inRange(-1200, 1201), *rc::gen::inRange(-1200, 1201),
                 *rc::gen::inRange(-1200, 1201));
    p /= 1000.0;
    if (i % 2 == 1)
      p = sw.grab_point(static_cast<std::size_t>(i) % sw.grab_point_count()) + p * 0.1;
    const glm::dvec3 fp = plan.warp_point(p);
    for (std::size_t g = 1; g < group.order(); ++g) {
      const glm::dmat3& m = group.element(g);
      RC_ASSERT(glm::length(plan.warp_point(m * p) - m * fp) <= 1e-6 * kScene);
    }
  }
}

// scodef under every kind of group (§11.8) through the session: one or two hands
// anywhere, near or on a plane or the axis; refused only as singular.
RC_GTEST_PROP(SymmetricSession, ScodefStrokesStaySymmetricExactAndReplay, ()) {
  StrokeShape shape;
  shape.spec = *gen_spec();
  shape.method = math::WarpMethod::scodef;
  shape.radius = *rc::gen::element(0.3, 0.6, 1.0);
  const std::size_t hand_count = *rc::gen::inRange<std::size_t>(1, 3);
  SymStation s(shape.spec, config_for(shape), longitudes(shape.spec), 11);
  math::SymmetryGroup group;
  RC_ASSERT(group.set(shape.spec).ok());
  const std::vector<glm::vec3> rest = positions(s.mesh());
  const auto image = vertex_images(group, rest);
  std::vector<HandStroke> hands;
  for (std::size_t h = 0; h < hand_count; ++h)
    hands.push_back(gen_hand(shape.spec, s.mesh(), shape.radius));
  for (std::size_t h = 0; h < hands.size(); ++h)
    s.hand(static_cast<std::uint8_t>(h), pose_at(hands[h], 0.0));
  s.button(kGrab0, true);
  if (hands.size() == 2) s.button(kGrab1, true);
  if (test_support::has_event(s.tick(), SessionEventKind::refused)) {
    RC_TAG("refused (singular, or hands on each other's images)");
    return;
  }
  std::vector<glm::vec3> expected;
  for (int k = 1; k <= 3; ++k) {
    for (std::size_t h = 0; h < hands.size(); ++h)
      s.hand(static_cast<std::uint8_t>(h), pose_at(hands[h], k / 3.0));
    s.tick();
    const math::WarpPlan& plan = *s.session->live().plan;
    check_scodef_plan(plan, group);
    expected = rest;
    for (const std::uint32_t v : plan.indices())
      expected[v] = glm::vec3(plan.warp_point(glm::dvec3(rest[v])));
  }
  s.button(kGrab0, false);
  if (hands.size() == 2) s.button(kGrab1, false);
  RC_ASSERT(test_support::has_event(s.tick(), SessionEventKind::committed));
  const std::vector<glm::vec3> after = positions(s.mesh());
  RC_ASSERT(after == expected);  // per vertex in double, rounded: exactly
  const double off = asymmetry(group, image, after);
  RC_TAG(off <= 1e-5 * kScene ? "float mesh symmetric to 1e-5" : "steep: double checks only");
  RC_LOG() << "asymmetry " << off << "\n";
  if (shape.spec.kind == math::SymmetryKind::mirrors) RC_ASSERT(off <= 1e-5 * kScene);
  RC_ASSERT(s.session->undo().ok());
  RC_ASSERT(positions(s.mesh()) == rest);
  RC_ASSERT(s.session->redo().ok());
  RC_ASSERT(positions(s.mesh()) == after);
  SymStation r(shape.spec, config_for(shape), longitudes(shape.spec), 11, false);
  RC_ASSERT(r.session->set_symmetry({}).ok());
  journal::JournalReader reader(s.storage);
  RC_ASSERT(reader.open().ok());
  RC_ASSERT(r.session->replay(reader).ok());
  RC_ASSERT(positions(r.mesh()) == after);
}

TEST(SymmetricSession, TheStateAndTheRecordCarryTheGroup) {
  StrokeShape shape;
  shape.spec = {math::SymmetryKind::rotation_mirror, 0, 1, 6};
  SymStation s(shape.spec, config_for(shape), 24, 11);
  EXPECT_EQ(s.session->state().symmetry.next, shape.spec);
  s.hand(0, math::identity_frame({0.5, 0.2, 0.1}));
  s.button(kGrab0, true);
  s.tick();
  EXPECT_EQ(s.session->state().symmetry.stroke, shape.spec);
  s.hand(0, math::identity_frame({0.6, 0.3, 0.1}));
  s.tick();
  s.button(kGrab0, false);
  s.tick();
  journal::JournalReader reader(s.storage);
  ASSERT_TRUE(reader.open().ok());
  const auto rec = reader.next();
  ASSERT_TRUE(rec.ok());
  const journal::StrokeRecord& st = rec->stroke;
  EXPECT_EQ(st.symmetry, (journal::StrokeSymmetry{3, 0, 1, 6}));
}

// The trivial group is the plan without symmetry, bit for bit (the e2e checksums rely on it).
TEST(SymmetricSession, NoneIsTheOldPlanBitForBit) {
  StrokeShape shape;
  SymStation a(math::SymmetrySpec{}, config_for(shape), 24, 11);
  SymStation b(math::SymmetrySpec{}, config_for(shape), 24, 11);
  b.session->set_symmetry({math::SymmetryKind::mirrors, math::kMirrorX, 0, 0}).ignore();
  b.session->set_symmetry({}).ignore();
  for (SymStation* s : {&a, &b}) {
    s->hand(0, math::identity_frame({0.5, 0.2, 0.1}));
    s->button(kGrab0, true);
    s->tick();
    s->hand(0, turned({0.7, 0.3, 0.1}, {0, 1, 1}, 0.7));
    s->tick();
    s->button(kGrab0, false);
    s->tick();
    EXPECT_FALSE(s->session->live().active);
  }
  EXPECT_EQ(positions(a.mesh()), positions(b.mesh()));
  EXPECT_NE(positions(a.mesh()), positions(SymStation({}, config_for(shape), 24, 11).mesh()));
}

}  // namespace
}  // namespace twister::session
