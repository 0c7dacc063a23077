// Issue 26, image test under Mesa's software renderer (offscreen, as
// bridge_cues_image_test): with a symmetry group the display draws a ghost cursor at
// each image of each hand. The images are projected through the display's camera and
// the pixels there must show the ghost cursor colour; without the group they must not.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <map>
#include <optional>

#include "bridge_image_rig.hpp"
#include "symmetry_cues.hpp"
#include "twister/link/math_conversion.hpp"
#include "twister/math/symmetry.hpp"

namespace twister::bridge::test {
namespace {

constexpr float kSphereM = 0.1F;

bool ghost_like(std::array<int, 3> c, glm::vec4 want) {
  return std::abs(c[0] - int(255 * want.r)) + std::abs(c[1] - int(255 * want.g)) +
             std::abs(c[2] - int(255 * want.b)) <
         40;
}

class SymmetryCues : public DisplayRig {
 protected:
  void SetUp() override {
    DisplayRig::SetUp();
    if (HasFatalFailure()) return;
    load_mesh(app_->replica(), sphere_mesh(kSphereM));
    app_->step();
  }
  void send_status(const std::array<std::uint8_t, 4>& symmetry) {
    link::StatusReport m;
    m.tracker_state = 1;
    m.vertex_count = static_cast<std::uint32_t>(app_->replica().mesh().vertex_count());
    m.vertex_capacity = 100000;
    m.triangle_capacity = 200000;
    m.symmetry = symmetry;
    (void)app_->replica().apply(m);
  }
  // Hands at `p` (hand h present where given).
  void send_hands(std::array<std::optional<glm::dvec3>, 2> p) {
    link::Hands m;
    m.sequence = sequence_++;
    m.radius_m = 0.03F;
    for (std::size_t h = 0; h < 2; ++h) {
      if (!p[h]) continue;
      m.flags = static_cast<std::uint8_t>(m.flags | (link::kHandSample0 << h) |
                                          (link::kHandTracked0 << h));
      m.hands[h] = link::to_compact(math::identity_frame(*p[h]));
    }
    (void)app_->replica().apply(m);
  }
  std::uint16_t sequence_ = 0;
  // Ghost cursors drawn in `img` at the projected images (counted), of how many.
  std::pair<int, int> ghosts_seen(const Image& img, const math::SymmetrySpec& spec) {
    int seen = 0;
    int total = 0;
    for (const GhostCursor& g : ghost_cursors(app_->replica(), spec)) {
      const auto px = project_object(g.position);
      if (!px) continue;
      ++total;
      const glm::vec4 colour = g.hand == 0 ? kGhostHand0 : kGhostHand1;
      if (ghost_like(img.at(int(px->x), int(px->y)), colour)) ++seen;
    }
    return {seen, total};
  }
};

TEST_F(SymmetryCues, GhostCursorsAtTheSixFoldImagesOfTheHand) {
  const math::SymmetrySpec rot6{math::SymmetryKind::rotation, 0, 2, 6};
  send_hands({glm::dvec3{0.09, 0.05, 0.06}, std::nullopt});
  send_status({});
  const Image plain = frame();
  expect_live_frame(plain);
  EXPECT_EQ(ghosts_seen(plain, rot6).first, 0) << "ghost colour without a group";
  EXPECT_EQ(symmetry_hud_line(app_->replica()), "") << "no symmetry line without a group";
  send_status({2, 0, 2, 6});
  const Image ghosts = frame();
  expect_live_frame(ghosts);
  const auto [seen, total] = ghosts_seen(ghosts, rot6);
  EXPECT_EQ(total, 5);
  EXPECT_EQ(seen, total) << "ghost cursors missing at the hand's images";
}

TEST_F(SymmetryCues, GhostCursorsOfBothHandsInTwoMirrors) {
  const math::SymmetrySpec xy{math::SymmetryKind::mirrors, 3, 0, 0};
  send_status({1, 3, 0, 0});
  send_hands({glm::dvec3{0.08, 0.07, 0.07}, glm::dvec3{-0.03, 0.09, 0.08}});
  const Image img = frame();
  expect_live_frame(img);
  const auto [seen, total] = ghosts_seen(img, xy);
  EXPECT_EQ(total, 6);  // 3 images of each hand
  EXPECT_EQ(seen, total);
  EXPECT_EQ(symmetry_hud_line(app_->replica()), "symmetry: xy (next strokes)");
}

// A scodef stroke under C6 (docs/math.md §11.8) pulling one point of the sphere out and
// up: the preview (the replica's CPU warp, drawn) carries the pull to all six images
// of the grab, each vertex nearest an image moved by the image of the motion.
TEST_F(SymmetryCues, ScodefStrokeUnderSixFoldIsDrawnAtEveryImage) {
  const glm::dvec3 grab{0.0866, 0.05, 0.0};
  const glm::dvec3 pulled = grab + glm::dvec3{0.026, 0.015, 0.02};
  const std::array<math::Frame, 2> start{math::identity_frame(grab), math::Frame{}};
  const std::array<math::Frame, 2> end{math::identity_frame(pulled), math::Frame{}};
  LiveMessages live = make_live_messages(1, 1, math::WarpMethod::scodef, 0.08, 1, start, end);
  live.stroke.symmetry = {2, 0, 2, 6};
  send_status({2, 0, 2, 6});
  (void)app_->replica().apply(live.stroke);
  (void)app_->replica().apply(live.hands);
  const Image img = frame();
  expect_live_frame(img);
  ASSERT_TRUE(app_->replica().live().cpu_path());
  const MeshData warped = app_->replica().cpu_warp();
  const MeshData& rest = app_->replica().mesh();
  ASSERT_EQ(warped.vertex_count(), rest.vertex_count());
  math::SymmetryGroup g;
  ASSERT_TRUE(g.set_rotation(2, 6, false).ok());
  for (std::size_t k = 0; k < g.order(); ++k) {
    const glm::dvec3 image = g.element(k) * grab;
    std::size_t near = 0;
    double best = 1e9;
    for (std::size_t i = 0; i < rest.vertex_count(); ++i) {
      const double d = glm::length(glm::dvec3(rest.x[i], rest.y[i], rest.z[i]) - image);
      if (d < best) {
        best = d;
        near = i;
      }
    }
    const glm::dvec3 moved = glm::dvec3(warped.x[near], warped.y[near], warped.z[near]) -
                             glm::dvec3(rest.x[near], rest.y[near], rest.z[near]);
    const glm::dvec3 want = g.element(k) * (pulled - grab);
    EXPECT_GT(glm::dot(moved, want), 0.5 * glm::dot(want, want)) << "image " << k;
  }
}

// The live stroke under a group through BridgeApp: drawn by the symmetric program from
// the rest positions (no CPU positions uploaded under it), equal to the CPU warp.
TEST_F(SymmetryCues, LiveSymmetricStrokeIsWarpedInTheShader) {
  const std::array<math::Frame, 2> start{math::identity_frame({0.06, 0.05, 0.06}), math::Frame{}};
  const std::array<math::Frame, 2> end{
      math::frame_from_uv({0.08, 0.07, 0.09}, {1.0, 0.0, 0.0}, {0.0, 0.8, 0.6}), math::Frame{}};
  LiveMessages m = make_live_messages(1, 1, math::WarpMethod::twister, 0.05, 1, start, end);
  m.stroke.symmetry = {2, 0, 2, 6};
  (void)app_->replica().apply(m.stroke);
  (void)app_->replica().apply(m.hands);
  const Image img = frame();
  expect_live_frame(img);
  ASSERT_TRUE(app_->replica().live().active);
  EXPECT_TRUE(renderer_.warps_on_gpu(app_->replica().live()));
  const MeshRenderer::Surface s = renderer_.capture_live_surface();
  const MeshData cpu = app_->replica().cpu_warp();
  const MeshData& rest = app_->replica().mesh();
  std::map<std::array<float, 3>, std::uint32_t> at;
  for (std::uint32_t i = 0; i < rest.vertex_count(); ++i) at[{rest.x[i], rest.y[i], rest.z[i]}] = i;
  double worst = 0.0;
  double moved = 0.0;
  std::size_t unmatched = 0;
  for (std::size_t c = 0; c < s.rest.size(); ++c) {
    const auto it = at.find({s.rest[c].x, s.rest[c].y, s.rest[c].z});
    if (it == at.end()) {
      ++unmatched;
      continue;
    }
    const glm::dvec3 want(cpu.x[it->second], cpu.y[it->second], cpu.z[it->second]);
    worst = std::max(worst, glm::length(glm::dvec3(s.warped[c]) - want));
    moved = std::max(moved, glm::length(want - glm::dvec3(s.rest[c])));
  }
  EXPECT_EQ(unmatched, 0u) << "the drawn rest positions are not the mesh's";
  EXPECT_LT(worst, 1e-5 * 2.0 * kSphereM);
  EXPECT_GT(moved, 0.01);
}

}  // namespace
}  // namespace twister::bridge::test
