// Issue 24 (label display): a refined box keeps clean sharp edges. The box is
// refined as the commit of the paper's twist refines it (an irregular
// triangulation, denser near the turning hand) but left unwarped, so its faces are
// flat and its edges straight lines. Along a line on a face, a little inside a
// crease, the picture's luminance must vary smoothly (the lights and the view
// change slowly over a flat face): its largest second difference stays under
// kRoughness. Averaged normals (the crease angle at 180 degrees: every edge smooth)
// make the saw-tooth this catches, committed and live (a translation along the edge
// keeps it straight and the faces flat, drawn by the refined live program).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>

#include "bridge_test_mesh.hpp"
#include "mesh_renderer.hpp"
#include "offscreen_renderer.hpp"
#include "png_writer.hpp"
#include "refine_harness.hpp"
#include "scene_replica.hpp"
#include "twister/math/warp_plan.hpp"
#include "twister/mesh/mesh_refiner.hpp"
#include "twister/mesh/vertex_normals.hpp"
#include "twister/session/plan_warp.hpp"

namespace twister::bridge {
namespace {

using session::test_support::kRefineTriangles;
using session::test_support::kRefineVertices;

constexpr int kW = 480;
constexpr int kH = 360;
// The largest second difference of luminance (0..255) along a line 4 px apart.
constexpr double kRoughness = 3.0;

// A 1 m box refined by the 170-degree Figure 6 twist's criterion, positions at rest.
MeshData refined_box() {
  auto box = std::make_unique<meshio::MeshBuffer>(kRefineVertices, kRefineTriangles);
  EXPECT_TRUE(meshio::make_box(box->mesh(), 3, 0.5F).ok());
  const mesh::Mesh& m = box->mesh();
  auto plan = std::make_unique<math::WarpPlanWithStorage<kRefineVertices>>();
  const std::array<math::Frame, 2> start{math::identity_frame({0, 0, -0.5}),
                                         math::identity_frame({0, 0, 0.5})};
  EXPECT_TRUE(plan->build({m.x(), m.y(), m.z()}, start, 1.0, math::WarpMethod::twister).ok());
  const std::array<math::Frame, 2> end{
      start[0], session::test_support::z_turn({0, 0, 0.5}, 170.0 * std::numbers::pi / 180.0)};
  EXPECT_TRUE(plan->update(end).ok());
  auto refiner =
      std::make_unique<mesh::MeshRefinerWithStorage<kRefineVertices, kRefineTriangles>>();
  const session::PlanWarp warp(*plan);
  EXPECT_TRUE(refiner->refine(box->mesh(), warp, 0.002).ok());
  EXPECT_GT(m.vertex_count(), 1000u);
  return test::to_mesh_data(m);
}

class CreaseImage : public ::testing::Test {
 protected:
  void SetUp() override {
    ViewConfig view;
    view.azimuth_deg = 30.0F;  // three faces in view: +x, +y and the top (-z is up)
    view.elevation_deg = 30.0F;
    ASSERT_TRUE(test::open_offscreen(context_, renderer_, kW, kH, view));
    test::load_mesh(replica_, refined_box());
  }

  // Luminance roughness along the top face's +y edge (x from -0.4 to 0.4 m, the
  // edge of the turning hand's face), `inside` metres into the named face.
  double roughness(bool into_top, double inside) {
    renderer_.draw();
    const std::vector<std::uint8_t> rgba = renderer_.read_rgba();
    if (const char* dir = std::getenv("TWISTER_BRIDGE_TEST_PNG")) {
      static int n = 0;
      (void)write_png(std::string(dir) + "/crease_" + std::to_string(n++) + ".png", kW, kH, rgba);
    }
    std::vector<double> lum;
    for (double x = -0.4; x <= 0.4; x += 0.004) {
      // The top face is z = -0.5 (up is -z), the side face y = +0.5.
      const glm::vec3 p =
          into_top ? glm::vec3(x, 0.5 - inside, -0.5) : glm::vec3(x, 0.5, -0.5 + inside);
      const auto px = renderer_.camera().project(
          glm::vec3(renderer_.model_matrix() * glm::vec4(p, 1.0F)), kW, kH);
      if (!px) continue;
      const auto i = (static_cast<std::size_t>(std::lround(px->y)) * kW +
                      static_cast<std::size_t>(std::lround(px->x))) *
                     4;
      lum.push_back(0.299 * rgba[i] + 0.587 * rgba[i + 1] + 0.114 * rgba[i + 2]);
    }
    EXPECT_GT(lum.size(), 100u);
    double worst = 0.0;
    for (std::size_t i = 4; i + 4 < lum.size(); ++i) {
      worst = std::max(worst, std::fabs(lum[i] - 0.5 * (lum[i - 4] + lum[i + 4])));
    }
    return worst;
  }

  // A live translation along +x: the box's +y and top faces stay flat and their edge
  // straight (each point moves along x), drawn by the refined program.
  void live_translation() {
    const std::array<math::Frame, 2> start{math::identity_frame({0.0, 0.5, -0.5}), {}};
    const std::array<math::Frame, 2> end{math::identity_frame({0.12, 0.5, -0.5}), {}};
    LiveMessages live = make_live_messages(1, 1, math::WarpMethod::twister, 0.8, 1, start, end);
    live.stroke.refine_threshold_m = 0.002F;
    (void)replica_.apply(live.stroke);
    (void)replica_.apply(live.hands);
    ASSERT_TRUE(replica_.live().active);
    renderer_.set_weights(replica_.live().weight1, replica_.live().weight2);
    renderer_.set_gradients(replica_.live().gradient1, replica_.live().gradient2);
    renderer_.set_live(&replica_.live());
    ASSERT_TRUE(renderer_.refining_live());
  }

  std::unique_ptr<GlContext> context_;
  MeshRenderer renderer_;
  SceneReplica replica_;
};

TEST_F(CreaseImage, ARefinedBoxsEdgeShowsNoSawTooth) {
  renderer_.set_mesh(replica_.mesh(), replica_.shading(), false);
  const double top = roughness(true, 0.01);
  const double side = roughness(false, 0.01);
  // The same box with every edge smooth (averaged normals, as before issue 24).
  renderer_.set_mesh(replica_.mesh(), shade_with_creases(replica_.mesh(), 180.0F), true);
  const double top_smooth = roughness(true, 0.01);
  const double side_smooth = roughness(false, 0.01);
  std::printf("committed: roughness top %.2f side %.2f (averaged normals: %.2f, %.2f)\n", top, side,
              top_smooth, side_smooth);
  EXPECT_LT(top, kRoughness);
  EXPECT_LT(side, kRoughness);
  EXPECT_GT(std::max(top_smooth, side_smooth), 2 * kRoughness) << "the test would not see it";
}

TEST_F(CreaseImage, TheLivePreviewOfARefinedBoxShowsNoSawTooth) {
  renderer_.set_mesh(replica_.mesh(), replica_.shading(), false);
  live_translation();
  const double top = roughness(true, 0.01);
  const double side = roughness(false, 0.01);
  renderer_.set_mesh(replica_.mesh(), shade_with_creases(replica_.mesh(), 180.0F), true);
  live_translation();
  const double top_smooth = roughness(true, 0.01);
  const double side_smooth = roughness(false, 0.01);
  std::printf("live: roughness top %.2f side %.2f (averaged normals: %.2f, %.2f)\n", top, side,
              top_smooth, side_smooth);
  EXPECT_LT(top, kRoughness);
  EXPECT_LT(side, kRoughness);
  EXPECT_GT(std::max(top_smooth, side_smooth), 2 * kRoughness) << "the test would not see it";
}

TEST_F(CreaseImage, ABoxCornerIsThreeDrawnVerticesAndASphereStaysOne) {
  const ShadedMesh box = shade_with_creases(replica_.mesh(), kDefaultCreaseAngleDeg);
  EXPECT_GT(box.vertex_count(), replica_.mesh().vertex_count());
  const MeshData sphere = test::sphere_mesh(0.1F);
  const ShadedMesh smooth = shade_with_creases(sphere, kDefaultCreaseAngleDeg);
  EXPECT_TRUE(smooth.identity());
  // A mesh without creases keeps the station's own normals (core's function).
  mesh::MeshWithStorage<8192, 16384> core;
  for (std::size_t i = 0; i < sphere.vertex_count(); ++i) {
    ASSERT_TRUE(core.add_vertex({sphere.x[i], sphere.y[i], sphere.z[i]}).ok());
  }
  for (std::size_t t = 0; t < sphere.triangle_count(); ++t) {
    ASSERT_TRUE(core.add_triangle(sphere.indices[3 * t], sphere.indices[3 * t + 1],
                                  sphere.indices[3 * t + 2])
                    .ok());
  }
  std::vector<float> x(sphere.vertex_count()), y(x.size()), z(x.size());
  ASSERT_TRUE(mesh::compute_vertex_normals(core, {x, y, z}).ok());
  for (std::size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(smooth.normals[3 * i], x[i]);
    EXPECT_EQ(smooth.normals[3 * i + 1], y[i]);
    EXPECT_EQ(smooth.normals[3 * i + 2], z[i]);
  }
}

}  // namespace
}  // namespace twister::bridge
