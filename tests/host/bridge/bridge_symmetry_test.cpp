// Issue 26, the display's live warp under a symmetry group: the replica builds the
// stroke's plan under the group the stroke message carries and draws every image of
// every hand (SceneReplica::cpu_warp, the station's own symmetrised warp), so the live
// preview at the end of a symmetric stroke is the mesh the station then commits.
#include <gtest/gtest.h>

#include <cmath>

#include "bridge_link_rig.hpp"

namespace twister::bridge::test_support {
namespace {

using math::SymmetryKind;
using math::SymmetrySpec;

session::SculptSessionConfig symmetric_config(const SymmetrySpec& group, math::WarpMethod method) {
  session::SculptSessionConfig c = session::test_support::test_config();
  c.method = method;
  c.interaction.initial_radius_m = 0.45f;
  c.symmetry = group;
  return c;
}

// One stroke of hand 0 from (0.35, 0.15, 0) lifting and turning; returns the largest
// |preview - commit| over the vertices, and checks the stroke was symmetric on both ends.
double preview_error(const SymmetrySpec& group,
                     math::WarpMethod method = math::WarpMethod::twister) {
  ports::NullLogSink log;
  BridgeLinkRig rig(log, symmetric_config(group, method));
  rig.run();
  const glm::dvec3 grab{0.35, 0.15, 0.0};
  rig.station.hand(0, math::identity_frame(grab));
  rig.station.button(kGrab0, true);
  (void)rig.station.tick();
  rig.run(2);
  for (int k = 1; k <= 4; ++k) {
    rig.station.hand(0, z_turn(grab + glm::dvec3{0.02 * k, 0.0, 0.06 * k}, 0.25 * k));
    (void)rig.station.tick();
    rig.run(2);
  }
  EXPECT_TRUE(rig.bridge.replica().live().active);
  EXPECT_EQ(rig.bridge.replica().live().symmetry, group);
  EXPECT_TRUE(rig.bridge.replica().live().cpu_path());
  const MeshData preview = rig.bridge.replica().cpu_warp();
  rig.station.button(kGrab0, false);
  (void)rig.station.tick();
  rig.run(10);
  const mesh::Mesh& committed = rig.station.session->mesh();
  EXPECT_EQ(rig.bridge.replica().checksum(), committed.checksum()) << "display did not follow";
  EXPECT_EQ(preview.vertex_count(), committed.vertex_count());
  if (preview.vertex_count() != committed.vertex_count()) return 1e9;
  double worst = 0.0;
  double moved = 0.0;
  for (std::uint32_t i = 0; i < committed.vertex_count(); ++i) {
    const glm::vec3 c = committed.position(i);
    const glm::dvec3 d{preview.x[i] - c.x, preview.y[i] - c.y, preview.z[i] - c.z};
    worst = std::max(worst, std::sqrt(glm::dot(d, d)));
    moved = std::max(moved, static_cast<double>(std::abs(c.z)));
  }
  EXPECT_GT(moved, 0.1) << "the stroke lifted nothing";
  return worst;
}

TEST(BridgeSymmetry, LivePreviewOfASixFoldStrokeIsTheCommit) {
  EXPECT_LT(preview_error({SymmetryKind::rotation, 0, 2, 6}), 1e-5);
}

TEST(BridgeSymmetry, LivePreviewOfAMirroredStrokeIsTheCommit) {
  EXPECT_LT(preview_error({SymmetryKind::mirrors, math::kMirrorX, 0, 0}), 1e-5);
}

// scodef under a group (docs/math.md §11.8): the replica's plan is the station's, per
// vertex in double, so the preview is the commit.
TEST(BridgeSymmetry, LivePreviewOfASixFoldScodefStrokeIsTheCommit) {
  EXPECT_LT(preview_error({SymmetryKind::rotation, 0, 2, 6}, math::WarpMethod::scodef), 1e-5);
}

TEST(BridgeSymmetry, LivePreviewOfAMirroredScodefStrokeIsTheCommit) {
  EXPECT_LT(preview_error({SymmetryKind::mirrors, math::kMirrorX, 0, 0}, math::WarpMethod::scodef),
            1e-5);
}

TEST(BridgeSymmetry, PlainStrokesStayOnTheShader) {
  LiveState s;
  EXPECT_FALSE(s.cpu_path());
  s.symmetry = {SymmetryKind::mirrors, math::kMirrorY, 0, 0};
  EXPECT_TRUE(s.cpu_path());
}

}  // namespace
}  // namespace twister::bridge::test_support
