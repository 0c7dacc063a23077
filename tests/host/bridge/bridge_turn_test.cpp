// The display of a stroke turned past 180 degrees (issue "a session", docs/unwrap.md):
// the link's live message carries the screw as the station computed it (angle up to
// 2 pi, negative cot(a/2)), the replica's CPU warp takes it the long way round too, and
// the vertex shader (math::fill_kernel_hand constants, GLSL sin/cos) draws what the CPU
// computes. Label interaction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numbers>
#include <vector>

#include "gl_context.hpp"
#include "mesh_renderer.hpp"
#include "scene_replica.hpp"
#include "twister/link/link_codec.hpp"
#include "twister/link/math_conversion.hpp"
#include "twister/math/screw.hpp"
#include "twister/math/warp_plan.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/meshio/mesh_generator.hpp"

namespace twister::bridge {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kW = 320;
constexpr int kH = 240;

MeshData sphere() {
  static mesh::MeshWithStorage<8192, 16384> m;
  EXPECT_TRUE(meshio::make_sphere(m, 48, 64, 0.1F).ok());
  MeshData d;
  d.x.assign(m.x().begin(), m.x().end());
  d.y.assign(m.y().begin(), m.y().end());
  d.z.assign(m.z().begin(), m.z().end());
  d.indices.assign(m.triangle_indices().begin(), m.triangle_indices().end());
  return d;
}

void load(SceneReplica& r, const MeshData& m) {
  link::LinkMessage b;
  b.type = link::MessageType::mesh_begin;
  b.mesh_begin = {true, 0, 1, static_cast<std::uint32_t>(m.vertex_count()),
                  static_cast<std::uint32_t>(m.triangle_count())};
  (void)r.apply(b);
  link::LinkMessage v;
  v.type = link::MessageType::vertices;
  for (std::uint32_t i = 0; i < m.vertex_count(); ++i) {
    v.vertices.items[v.vertices.count++] = {i, m.x[i], m.y[i], m.z[i]};
    if (v.vertices.count == link::kMaxVerticesPerChunk || i + 1 == m.vertex_count()) {
      (void)r.apply(v);
      v.vertices.count = 0;
    }
  }
  link::LinkMessage t;
  t.type = link::MessageType::triangles;
  for (std::uint32_t k = 0; k < m.triangle_count(); k += link::kMaxTrianglesPerChunk) {
    const auto n = std::min<std::size_t>(link::kMaxTrianglesPerChunk, m.triangle_count() - k);
    t.triangles.first = k;
    t.triangles.count = static_cast<std::uint16_t>(n);
    std::copy_n(m.indices.begin() + 3 * static_cast<std::ptrdiff_t>(k), 3 * n,
                t.triangles.indices.begin());
    (void)r.apply(t);
  }
  link::LinkMessage e;
  e.type = link::MessageType::mesh_end;
  e.mesh_end = {1, *mesh_checksum(m)};
  ASSERT_FALSE(r.apply(e));
  ASSERT_EQ(r.version(), 1u);
}

// A station-side one-hand stroke on `m` grabbing the sphere's -Y side and twisting
// by `turn` about the grab's y axis: the plan as the station's live stroke has it
// (long way round past pi), and the live message the station link sends for it.
struct Stroke {
  std::vector<std::uint32_t> idx;
  std::vector<float> w1, w2;
  std::unique_ptr<math::WarpPlan> plan;
  link::LinkMessage live;
};

std::unique_ptr<Stroke> twist(const MeshData& m, double turn) {
  auto s = std::make_unique<Stroke>();
  const std::size_t n = m.vertex_count();
  s->idx.resize(n);
  s->w1.resize(n);
  s->w2.resize(n);
  s->plan = std::make_unique<math::WarpPlan>(math::WarpPlanStorage{s->idx, s->w1, s->w2});
  const math::Frame start = math::identity_frame({0.0, -0.1, 0.0});
  const math::Frame end = math::frame_from_uv(
      {0.0, -0.13, 0.01}, {std::cos(turn), 0.0, -std::sin(turn)}, {0.0, 1.0, 0.0});
  const std::array<math::Frame, 1> s0{start};
  const std::array<math::Frame, 1> e0{end};
  EXPECT_TRUE(s->plan->build({m.x, m.y, m.z}, s0, 0.12, math::WarpMethod::twister).ok());
  EXPECT_TRUE(s->plan->update_turns(e0, turn > kPi ? 1 : 0).ok());
  link::LiveWarp& l = s->live.live_warp;
  s->live.type = link::MessageType::live_warp;
  l.mesh_version = 1;
  l.stroke = 1;
  l.active = true;
  l.hand_mask = 1;
  l.radius_m = 0.12;
  l.hands[0] = {link::to_wire(start), link::to_wire(end), link::to_wire(s->plan->screw(0))};
  return s;
}

TEST(BridgeTurn, TheLinkCarriesAScrewPast180Degrees) {
  const MeshData m = sphere();
  const auto s = twist(m, 1.5 * kPi);
  ASSERT_NEAR(s->plan->screw(0).angle, 1.5 * kPi, 1e-9);
  std::vector<std::byte> frame(link::kMaxFrameBytes);
  const auto n = link::encode_frame(s->live, frame);
  ASSERT_TRUE(n.ok());
  link::LinkDecoder decoder;
  link::LinkMessage got;
  bool decoded = false;
  for (std::size_t i = 0; i < *n; ++i) {
    if (const auto r = decoder.process(frame[i]); r.ok()) {
      got = **r;
      decoded = true;
    }
  }
  ASSERT_TRUE(decoded);
  const link::Screw& w = got.live_warp.hands[0].screw;
  EXPECT_EQ(w.angle, s->plan->screw(0).angle);
  EXPECT_EQ(w.cot_half, s->plan->screw(0).cot_half);
  EXPECT_LT(w.cot_half, 0.0);
  EXPECT_EQ(w.axis, s->plan->screw(0).axis);
  // The shader's constants from the wire equal the station's kernel constants.
  math::KernelHand station{};
  math::KernelHand display{};
  math::fill_kernel_hand(station, s->plan->screw(0), s->plan->start_frame(0), s->plan->end_frame(0),
                         math::WarpMethod::twister);
  math::fill_kernel_hand(display, link::to_screw(w), link::to_frame(got.live_warp.hands[0].start),
                         link::to_frame(got.live_warp.hands[0].end), math::WarpMethod::twister);
  EXPECT_EQ(display.half_angle, station.half_angle);
  EXPECT_GT(display.half_angle, kPi / 2);
  EXPECT_EQ(display.cot_half, station.cot_half);
  EXPECT_EQ(0,
            std::memcmp(display.axis_x_chord, station.axis_x_chord, sizeof station.axis_x_chord));
}

// The replica's CPU warp (used for previews and checks) is the station's live warp.
TEST(BridgeTurn, TheReplicasCpuWarpTurnsTheLongWayToo) {
  const MeshData m = sphere();
  for (const double turn : {0.8 * kPi, 1.5 * kPi, 1.8 * kPi}) {
    SceneReplica r;
    load(r, m);
    const auto s = twist(m, turn);
    (void)r.apply(s->live);
    ASSERT_TRUE(r.live().active);
    const MeshData cpu = r.cpu_warp();
    ASSERT_EQ(cpu.vertex_count(), m.vertex_count());
    std::vector<float> x = m.x, y = m.y, z = m.z;
    ASSERT_TRUE(s->plan->apply({m.x, m.y, m.z}, {x, y, z}).ok());
    double worst = 0.0;
    for (std::size_t i = 0; i < m.vertex_count(); ++i) {
      worst = std::max({worst, double{std::fabs(cpu.x[i] - x[i])},
                        double{std::fabs(cpu.y[i] - y[i])}, double{std::fabs(cpu.z[i] - z[i])}});
    }
    EXPECT_EQ(worst, 0.0) << turn;
  }
}

// Fraction of pixels whose channels differ by more than `tol`.
double differing(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, int tol) {
  std::size_t n = 0;
  for (std::size_t p = 0; p < a.size(); p += 4) {
    for (std::size_t c = 0; c < 3; ++c) {
      if (std::abs(int{a[p + c]} - int{b[p + c]}) > tol) {
        ++n;
        break;
      }
    }
  }
  return static_cast<double>(n) / static_cast<double>(a.size() / 4);
}

// The vertex shader's warp of a 270-degree twist equals core's CPU warp drawn as plain
// geometry, and differs clearly from the minimal (-90 degree) screw of the same poses.
TEST(BridgeTurn, TheShaderDrawsA270DegreeTwistAsTheCpuWarps) {
  auto context = make_offscreen_context(kW, kH);
  ASSERT_TRUE(context) << context.error().message;
  MeshRenderer renderer;
  ASSERT_TRUE(renderer.init(kW, kH, true, ViewConfig{}));
  SceneReplica r;
  const MeshData m = sphere();
  load(r, m);
  const auto s = twist(m, 1.5 * kPi);
  (void)r.apply(s->live);
  renderer.set_mesh(r.mesh(), false);
  renderer.set_weights(r.live().weight1, r.live().weight2);
  renderer.set_show_weights(true);
  renderer.set_live(&r.live().message);
  renderer.draw();
  const auto shader = renderer.read_rgba();

  renderer.set_mesh(r.cpu_warp(), true);
  renderer.set_weights(r.live().weight1, r.live().weight2);
  renderer.set_live(nullptr);
  renderer.draw();
  const auto cpu = renderer.read_rgba();

  link::LiveWarp minimal = s->live.live_warp;  // what a display folding the turn would draw
  minimal.hands[0].screw = link::to_wire(math::compute_screw(link::to_frame(minimal.hands[0].start),
                                                             link::to_frame(minimal.hands[0].end)));
  renderer.set_mesh(r.mesh(), true);
  renderer.set_live(&minimal);
  renderer.draw();
  const auto folded = renderer.read_rgba();
  const double same = differing(shader, cpu, 12);
  const double other = differing(shader, folded, 12);
  std::printf("270-degree twist: shader vs CPU %.3f%% of pixels, vs the minimal screw %.2f%%\n",
              100.0 * same, 100.0 * other);
  EXPECT_LT(same, 0.002);
  EXPECT_GT(other, 0.005);
}

}  // namespace
}  // namespace twister::bridge
