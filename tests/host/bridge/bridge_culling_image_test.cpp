// Issue 24 (frame cost): back-face culling on the display. Which meshes are closed
// and consistently wound (surface_facing), and that culling never changes what the
// sculptor sees: a closed sphere draws the same picture culled as with both faces
// (at rest, wound either way, during a live stroke, plain and refined); an open grid
// seen from behind still draws; an eye inside the model draws both faces. The saving
// is counted (fragment shader invocations), not timed: bench/display_bench times it.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include <epoxy/gl.h>

#include "bridge_app.hpp"
#include "bridge_test_mesh.hpp"
#include "offscreen_renderer.hpp"
#include "scene_replica.hpp"
#include "surface_facing.hpp"
#include "twister/link/math_conversion.hpp"
#include "twister/mesh/mesh.hpp"
#include "twister/meshio/mesh_generator.hpp"

namespace twister::bridge {
namespace {

using test::differing;
using test::sphere_mesh;
using test::to_mesh_data;

constexpr int kW = 320;
constexpr int kH = 240;
constexpr std::array<int, 3> kBackground{33, 36, 43};  // the clear colour in 8 bits

MeshData grid_mesh(std::size_t n, float half) {
  static mesh::MeshWithStorage<4096, 8192> m;
  m.clear();
  EXPECT_TRUE(meshio::make_grid(m, n, half).ok());
  return to_mesh_data(m);
}

MeshData box_mesh(std::size_t n, float half) {
  static mesh::MeshWithStorage<4096, 8192> m;
  m.clear();
  EXPECT_TRUE(meshio::make_box(m, n, half).ok());
  return to_mesh_data(m);
}

MeshData cylinder_mesh() {
  static mesh::MeshWithStorage<4096, 8192> m;
  m.clear();
  EXPECT_TRUE(meshio::make_cylinder(m, 4, 24, 0.05F, 0.1F).ok());
  return to_mesh_data(m);
}

// Every triangle wound the other way.
MeshData reversed(MeshData m) {
  for (std::size_t t = 0; t + 3 <= m.indices.size(); t += 3) {
    std::swap(m.indices[t + 1], m.indices[t + 2]);
  }
  return m;
}

// `b`'s vertices and triangles after `a`'s, moved by `dx`.
MeshData joined(MeshData a, const MeshData& b, float dx) {
  const auto offset = static_cast<std::uint32_t>(a.vertex_count());
  for (std::size_t i = 0; i < b.vertex_count(); ++i) {
    a.x.push_back(b.x[i] + dx);
    a.y.push_back(b.y[i]);
    a.z.push_back(b.z[i]);
  }
  for (const std::uint32_t v : b.indices) a.indices.push_back(v + offset);
  return a;
}

std::size_t model_pixels(const std::vector<std::uint8_t>& img) {
  std::size_t n = 0;
  for (std::size_t p = 0; p < img.size(); p += 4) {
    n += std::abs(int{img[p]} - kBackground[0]) + std::abs(int{img[p + 1]} - kBackground[1]) +
             std::abs(int{img[p + 2]} - kBackground[2]) >
         3;
  }
  return n;
}

TEST(SurfaceFacing, ClosedOutwardMeshesShowTheirFrontFaces) {
  EXPECT_EQ(surface_facing(sphere_mesh(0.1F)), Facing::front);
  EXPECT_EQ(surface_facing(box_mesh(5, 0.1F)), Facing::front);
  EXPECT_EQ(surface_facing(cylinder_mesh()), Facing::front);
  // Two pieces, both outward (apart or overlapping).
  EXPECT_EQ(surface_facing(joined(sphere_mesh(0.1F), box_mesh(4, 0.05F), 0.3F)), Facing::front);
  EXPECT_EQ(surface_facing(joined(sphere_mesh(0.1F), sphere_mesh(0.1F), 0.05F)), Facing::front);
  // Far from the origin (the volume is taken about each piece's own corner).
  MeshData far = sphere_mesh(0.1F);
  for (float& x : far.x) x += 1000.0F;
  EXPECT_EQ(surface_facing(far), Facing::front);
}

TEST(SurfaceFacing, ClosedInwardMeshesShowTheirBackFaces) {
  EXPECT_EQ(surface_facing(reversed(sphere_mesh(0.1F))), Facing::back);
  EXPECT_EQ(surface_facing(reversed(box_mesh(3, 0.1F))), Facing::back);
}

TEST(SurfaceFacing, AnythingElseShowsBothSides) {
  EXPECT_EQ(surface_facing(MeshData{}), Facing::both_sides);
  EXPECT_EQ(surface_facing(grid_mesh(8, 0.1F)), Facing::both_sides);  // open
  MeshData holed = sphere_mesh(0.1F);
  holed.indices.erase(holed.indices.begin() + 300, holed.indices.begin() + 303);
  EXPECT_EQ(surface_facing(holed), Facing::both_sides);  // a hole
  MeshData flipped = sphere_mesh(0.1F);
  std::swap(flipped.indices[301], flipped.indices[302]);
  EXPECT_EQ(surface_facing(flipped), Facing::both_sides);  // one triangle wound the other way
  // One piece outward, one inward (an inside-out part of an import, or a cavity).
  EXPECT_EQ(surface_facing(joined(sphere_mesh(0.1F), reversed(sphere_mesh(0.05F)), 0.3F)),
            Facing::both_sides);
  // A triangle and its reverse: closed and consistent, but enclosing nothing.
  MeshData sheet;
  sheet.x = {0.0F, 0.1F, 0.0F};
  sheet.y = {0.0F, 0.0F, 0.1F};
  sheet.z = {0.0F, 0.0F, 0.0F};
  sheet.indices = {0, 1, 2, 0, 2, 1};
  EXPECT_EQ(surface_facing(sheet), Facing::both_sides);
  // An edge of three triangles (a fin on the sphere).
  MeshData fin = sphere_mesh(0.1F);
  fin.x.push_back(0.3F);
  fin.y.push_back(0.0F);
  fin.z.push_back(0.0F);
  fin.indices.insert(fin.indices.end(), {fin.indices[0], fin.indices[1],
                                         static_cast<std::uint32_t>(fin.vertex_count() - 1)});
  EXPECT_EQ(surface_facing(fin), Facing::both_sides);
  // A degenerate triangle.
  MeshData degenerate = sphere_mesh(0.1F);
  degenerate.indices[2] = degenerate.indices[1];
  EXPECT_EQ(surface_facing(degenerate), Facing::both_sides);
}

class Culling : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(test::open_offscreen(context_, renderer_, kW, kH)); }
  // The frame with culling allowed and with both faces; both pictures.
  std::array<std::vector<std::uint8_t>, 2> both_ways(const std::string& name) {
    std::array<std::vector<std::uint8_t>, 2> out;
    for (const bool allow : {true, false}) {
      renderer_.allow_face_culling(allow);
      renderer_.draw();
      out[allow ? 0 : 1] = renderer_.read_rgba();
    }
    renderer_.allow_face_culling(true);
    if (const char* dir = std::getenv("TWISTER_BRIDGE_TEST_PNG")) {
      (void)write_png(std::string(dir) + "/culling_" + name + ".png", kW, kH, out[0]);
      (void)write_png(std::string(dir) + "/culling_" + name + "_both.png", kW, kH, out[1]);
    }
    return out;
  }
  // Fragment shader invocations of one frame (0: the driver cannot count them).
  std::uint64_t fragments() {
    if (!epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query")) return 0;
    GLuint query = 0;
    glGenQueries(1, &query);
    renderer_.begin_frame();
    glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, query);
    renderer_.draw_mesh();
    glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
    renderer_.end_frame();
    GLuint64 n = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &n);
    glDeleteQueries(1, &query);
    return n;
  }
  std::unique_ptr<GlContext> context_;
  MeshRenderer renderer_;
};

TEST_F(Culling, AClosedSphereDrawsTheSamePictureCulled) {
  for (const bool inward : {false, true}) {
    const MeshData m = inward ? reversed(sphere_mesh(0.1F)) : sphere_mesh(0.1F);
    renderer_.set_mesh(m, false);
    EXPECT_TRUE(renderer_.culling_faces());
    for (const float azimuth : {0.0F, 200.0F, 300.0F}) {
      renderer_.camera().orbit(azimuth, 0.0F);
      const auto [culled, two_sided] = both_ways(inward ? "sphere_inward" : "sphere");
      EXPECT_GT(model_pixels(culled), std::size_t{kW * kH / 10});
      EXPECT_EQ(differing(culled, two_sided, 0), 0.0) << inward << " " << azimuth;
    }
    renderer_.allow_face_culling(false);
    const std::uint64_t all = fragments();
    renderer_.allow_face_culling(true);
    const std::uint64_t culled = fragments();
    std::printf("fragments shaded: %llu both faces, %llu culled\n",
                static_cast<unsigned long long>(all), static_cast<unsigned long long>(culled));
    if (all > 0) {
      EXPECT_LT(static_cast<double>(culled), 0.6 * static_cast<double>(all));
    }
  }
}

TEST_F(Culling, AnOpenGridSeenFromBehindStillDraws) {
  renderer_.set_mesh(grid_mesh(16, 0.1F), false);
  EXPECT_FALSE(renderer_.culling_faces());
  std::size_t seen[2] = {};
  for (const bool behind : {false, true}) {
    // The grid lies in z = 0; world up is -Z: look from above, then from below.
    renderer_.camera().reset();
    renderer_.camera().orbit(0.0F, behind ? -75.0F : 50.0F);
    const auto [culled, two_sided] = both_ways(behind ? "grid_behind" : "grid_front");
    EXPECT_EQ(differing(culled, two_sided, 0), 0.0);
    seen[behind ? 1 : 0] = model_pixels(culled);
  }
  EXPECT_GT(seen[0], std::size_t{kW * kH / 20});
  EXPECT_GT(seen[1], std::size_t{kW * kH / 20});
}

TEST_F(Culling, AnEyeInsideTheModelDrawsBothFaces) {
  renderer_.set_mesh(sphere_mesh(0.1F), false);
  EXPECT_TRUE(renderer_.culling_faces());
  renderer_.camera().zoom(8.0F);  // the eye 0.05 m from the centre of a 0.1 m sphere
  EXPECT_FALSE(renderer_.culling_faces());
  const auto [culled, two_sided] = both_ways("inside");
  EXPECT_EQ(differing(culled, two_sided, 0), 0.0);
  EXPECT_GT(model_pixels(culled), std::size_t{kW * kH / 2});  // the inside wall
}

TEST_F(Culling, ALiveStrokeDrawsTheSamePictureCulled) {
  SceneReplica r;
  test::load_mesh(r, sphere_mesh(0.1F));
  const std::array<math::Frame, 2> start{math::identity_frame({0.0, -0.1, 0.0}),
                                         math::identity_frame({0.0, 0.1, 0.0})};
  const auto turned = [](glm::dvec3 o, double a) {
    return math::frame_from_uv(o, {1.0, 0.0, 0.0}, {0.0, std::cos(a), std::sin(a)});
  };
  const std::array<math::Frame, 2> end{turned({0.02, -0.15, -0.03}, 0.9),
                                       turned({0.02, 0.14, -0.03}, -0.7)};
  LiveMessages live = make_live_messages(1, 1, math::WarpMethod::twister, 0.08, 3, start, end);
  live.stroke.refine_threshold_m = 0.0005F;
  (void)r.apply(live.stroke);
  (void)r.apply(live.hands);
  ASSERT_TRUE(r.live().active);
  renderer_.set_mesh(r.mesh(), r.shading(), false);
  renderer_.set_weights(r.live().weight1, r.live().weight2);
  renderer_.set_gradients(r.live().gradient1, r.live().gradient2);
  renderer_.set_show_weights(true);
  renderer_.set_live(&r.live());
  EXPECT_TRUE(renderer_.culling_faces());
  for (const bool refine : {false, true}) {
    renderer_.allow_live_refinement(refine);
    if (refine && !renderer_.can_refine_live()) continue;
    EXPECT_EQ(renderer_.refining_live(), refine);
    const auto [culled, two_sided] = both_ways(refine ? "live_refined" : "live");
    EXPECT_EQ(differing(culled, two_sided, 0), 0.0) << refine;
  }
}

}  // namespace
}  // namespace twister::bridge
