// Issue 26, the display's live warp under a symmetry group in the vertex shader (Mesa
// llvmpipe, offscreen): the symmetric program's warped positions, read back by
// transform feedback, equal the replica's CPU float path (SceneReplica::cpu_warp, the
// station's own update and apply) vertex by vertex within 1e-5 of the scene size (the
// mesh's bounding-box diagonal), for mirrors (a grab on the plane too: the 1/|G_h| share),
// rot6 and rot6 + mirror, one and two hands, twister and rottran; and the pictures of
// both paths agree.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <string>

#include "bridge_test_mesh.hpp"
#include "gl_context.hpp"
#include "mesh_renderer.hpp"
#include "offscreen_renderer.hpp"
#include "png_writer.hpp"
#include "scene_replica.hpp"
#include "twister/math/screw.hpp"

namespace twister::bridge {
namespace {

using math::SymmetryKind;
using math::SymmetrySpec;

constexpr int kW = 320;
constexpr int kH = 240;
constexpr float kSphereM = 0.3F;  // the spork's starting sphere

struct Stroke {
  SymmetrySpec group;
  math::WarpMethod method = math::WarpMethod::twister;
  std::uint8_t hands = 1;  // hand mask
  glm::dvec3 grab0{0.17, 0.22, 0.08};
  glm::dvec3 grab1{-0.05, -0.25, 0.15};
  double radius = 0.2;
};

// Hand h's end pose: moved out and turned about a tilted axis.
math::Frame end_pose(glm::dvec3 grab, std::size_t h) {
  const double a = h == 0 ? 0.7 : -0.5;
  const glm::dvec3 u = glm::normalize(glm::dvec3{std::cos(a), std::sin(a), 0.3});
  const glm::dvec3 w0 = glm::normalize(glm::cross(u, glm::dvec3{0.2, -0.3, 1.0}));
  const glm::dvec3 v = glm::cross(w0, u);
  return math::frame_from_uv(grab + glm::dvec3{0.04, h == 0 ? -0.03 : 0.05, 0.06}, u, v);
}

class BridgeSymmetryShader : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(test::open_offscreen(context_, renderer_, kW, kH));
    ASSERT_TRUE(renderer_.has_symmetric_shader()) << "the symmetric program did not build";
    mesh_ = test::sphere_mesh(kSphereM, 64, 120);
    test::load_mesh(replica_, mesh_);
    glm::vec3 lo(1e30F), hi(-1e30F);
    for (std::size_t i = 0; i < mesh_.vertex_count(); ++i) {
      const glm::vec3 p(mesh_.x[i], mesh_.y[i], mesh_.z[i]);
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    scene_ = glm::length(hi - lo);
  }
  void begin(const Stroke& s) {
    std::array<math::Frame, 2> start{};
    std::array<math::Frame, 2> end{};
    std::size_t k = 0;
    for (std::size_t h = 0; h < 2; ++h) {
      if ((s.hands & (1u << h)) == 0) continue;
      const glm::dvec3 g = h == 0 ? s.grab0 : s.grab1;
      start[k] = math::identity_frame(g);
      end[k++] = end_pose(g, h);
    }
    LiveMessages m = make_live_messages(1, ++stroke_, s.method, s.radius, s.hands, start, end);
    m.stroke.symmetry = {static_cast<std::uint8_t>(s.group.kind), s.group.mirrors, s.group.axis,
                         s.group.order};
    (void)replica_.apply(m.stroke);
    (void)replica_.apply(m.hands);
    ASSERT_TRUE(replica_.live().active);
    ASSERT_EQ(replica_.live().symmetry, s.group);
  }
  // The shader's warp against cpu_warp at every vertex (by rest position): the largest
  // distance over the scene size; how far the stroke moved anything, likewise.
  // `new_mesh` false: the renderer keeps the mesh of the last stroke (a stroke cancelled,
  // the next one on the same mesh: only the entries change).
  std::pair<double, double> compare(bool new_mesh = true) {
    renderer_.allow_symmetric_shader(true);
    if (new_mesh) renderer_.set_mesh(replica_.mesh(), false);
    renderer_.set_weights(replica_.live().weight1, replica_.live().weight2);
    EXPECT_TRUE(renderer_.warps_on_gpu(replica_.live()));
    renderer_.set_live(&replica_.live());
    const MeshRenderer::Surface s = renderer_.capture_live_surface();
    const MeshData cpu = replica_.cpu_warp();
    EXPECT_EQ(cpu.vertex_count(), mesh_.vertex_count());
    std::map<std::array<float, 3>, std::uint32_t> at;
    for (std::uint32_t i = 0; i < mesh_.vertex_count(); ++i) {
      at[{mesh_.x[i], mesh_.y[i], mesh_.z[i]}] = i;
    }
    double worst = 0.0;
    double moved = 0.0;
    std::size_t unmatched = 0;
    for (std::size_t c = 0; c < s.rest.size(); ++c) {
      const auto it = at.find({s.rest[c].x, s.rest[c].y, s.rest[c].z});
      if (it == at.end()) {
        ++unmatched;
        continue;
      }
      const std::uint32_t v = it->second;
      const glm::dvec3 want(cpu.x[v], cpu.y[v], cpu.z[v]);
      worst = std::max(worst, glm::length(glm::dvec3(s.warped[c]) - want));
      moved = std::max(moved, glm::length(want - glm::dvec3(s.rest[c])));
    }
    EXPECT_EQ(unmatched, 0u);
    std::printf("shader vs cpu_warp: worst %.3g, largest move %.3g (of the scene size)\n",
                worst / scene_, moved / scene_);
    EXPECT_EQ(s.rest.size(), 3 * mesh_.triangle_count());
    return {worst / scene_, moved / scene_};
  }
  // The picture of the CPU path (positions uploaded, as twister-bridge drew every
  // symmetric stroke before) and of the shader; the fraction of pixels that differ.
  double pictures(const std::string& name) {
    renderer_.set_show_weights(true);
    renderer_.allow_symmetric_shader(false);
    renderer_.set_mesh(replica_.mesh(), false);
    renderer_.set_weights(replica_.live().weight1, replica_.live().weight2);
    EXPECT_FALSE(renderer_.warps_on_gpu(replica_.live()));
    renderer_.set_positions(replica_.cpu_warp());
    renderer_.set_live(&replica_.live());
    renderer_.draw();
    const auto cpu = renderer_.read_rgba();
    renderer_.allow_symmetric_shader(true);
    renderer_.set_mesh(replica_.mesh(), true);
    renderer_.set_weights(replica_.live().weight1, replica_.live().weight2);
    renderer_.set_live(&replica_.live());
    renderer_.draw();
    const auto gpu = renderer_.read_rgba();
    if (const char* dir = std::getenv("TWISTER_BRIDGE_TEST_PNG")) {
      (void)write_png(std::string(dir) + "/symmetry_" + name + "_cpu.png", kW, kH, cpu);
      (void)write_png(std::string(dir) + "/symmetry_" + name + "_shader.png", kW, kH, gpu);
    }
    return test::differing(cpu, gpu, 24);
  }
  std::unique_ptr<GlContext> context_;
  MeshRenderer renderer_;
  SceneReplica replica_;
  MeshData mesh_;
  double scene_ = 1.0;
  std::uint32_t stroke_ = 0;
};

constexpr double kTolerance = 1e-5;  // of the scene size

TEST_F(BridgeSymmetryShader, MirrorOneHand) {
  begin({{SymmetryKind::mirrors, math::kMirrorX, 0, 0}});
  const auto [worst, moved] = compare();
  EXPECT_LT(worst, kTolerance);
  EXPECT_GT(moved, 0.05);
}

TEST_F(BridgeSymmetryShader, ThreeMirrorsTwoHands) {
  begin({{SymmetryKind::mirrors, math::kMirrorX | math::kMirrorY | math::kMirrorZ, 0, 0},
         math::WarpMethod::twister,
         3});
  const auto [worst, moved] = compare();
  EXPECT_LT(worst, kTolerance);
  EXPECT_GT(moved, 0.05);
}

// A grab on the plane x = 0: its two images share the grab point and each carries half
// of its motion (the 1/|G_h| share of docs/math.md §11.4).
TEST_F(BridgeSymmetryShader, GrabOnTheMirrorPlaneSharesItsMotion) {
  Stroke s{{SymmetryKind::mirrors, math::kMirrorX, 0, 0}};
  s.grab0 = {0.0, 0.2, 0.22};
  begin(s);
  const auto [worst, moved] = compare();
  EXPECT_LT(worst, kTolerance);
  EXPECT_GT(moved, 0.02);
}

TEST_F(BridgeSymmetryShader, SixFoldOneAndTwoHands) {
  for (const std::uint8_t hands : {std::uint8_t{1}, std::uint8_t{3}}) {
    begin({{SymmetryKind::rotation, 0, 2, 6}, math::WarpMethod::twister, hands});
    const auto [worst, moved] = compare();
    EXPECT_LT(worst, kTolerance) << "hands " << int{hands};
    EXPECT_GT(moved, 0.05);
  }
}

TEST_F(BridgeSymmetryShader, SixFoldWithMirrorTwoHandsBothMethods) {
  for (const math::WarpMethod m : {math::WarpMethod::twister, math::WarpMethod::rottran}) {
    begin({{SymmetryKind::rotation_mirror, 0, 2, 6}, m, 3});
    const auto [worst, moved] = compare();
    EXPECT_LT(worst, kTolerance) << "method " << int(m);
    EXPECT_GT(moved, 0.05);
  }
}

// A second stroke on the same mesh, the renderer keeping it: the new stroke's entries
// replace the old ones.
TEST_F(BridgeSymmetryShader, NextStrokeOnTheSameMeshUploadsItsEntries) {
  begin({{SymmetryKind::rotation, 0, 2, 6}, math::WarpMethod::twister, 1});
  EXPECT_LT(compare().first, kTolerance);
  Stroke other{{SymmetryKind::mirrors, math::kMirrorY, 0, 0}};
  other.grab0 = {-0.2, 0.1, -0.2};
  begin(other);
  const auto [worst, moved] = compare(false);
  EXPECT_LT(worst, kTolerance);
  EXPECT_GT(moved, 0.05);
}

// Rot6 + mirror about z with a grab on the axis: the stabiliser is the whole group (12).
TEST_F(BridgeSymmetryShader, GrabOnTheAxis) {
  Stroke s{{SymmetryKind::rotation_mirror, 0, 2, 6}};
  s.grab0 = {0.0, 0.0, 0.3};
  begin(s);
  const auto [worst, moved] = compare();
  EXPECT_LT(worst, kTolerance);
  EXPECT_GT(moved, 0.02);
}

TEST_F(BridgeSymmetryShader, PicturesOfBothPathsAgree) {
  begin({{SymmetryKind::rotation, 0, 2, 6}, math::WarpMethod::twister, 1});
  EXPECT_LT(pictures("rot6"), 0.01);
  begin({{SymmetryKind::rotation_mirror, 0, 2, 6}, math::WarpMethod::twister, 3});
  EXPECT_LT(pictures("rot6m_two"), 0.01);
  begin({{SymmetryKind::mirrors, math::kMirrorX, 0, 0}, math::WarpMethod::twister, 3});
  EXPECT_LT(pictures("mirror_two"), 0.01);
}

// scodef and a plain stroke never take the symmetric program.
TEST_F(BridgeSymmetryShader, OnlyGroupsTakeTheSymmetricProgram) {
  LiveState plain;
  EXPECT_TRUE(renderer_.warps_on_gpu(plain));
  LiveState scodef;
  scodef.method = math::WarpMethod::scodef;
  EXPECT_FALSE(renderer_.warps_on_gpu(scodef));
  LiveState unready;
  unready.symmetry = {SymmetryKind::mirrors, math::kMirrorX, 0, 0};
  EXPECT_FALSE(renderer_.warps_on_gpu(unready));
}

}  // namespace
}  // namespace twister::bridge
