// `twister mesh sphere --center`: the generated sphere is translated as a whole (the
// bridge demo places its sphere in front of the simulated transmitter this way).
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <string>

#include "cli_test_support.hpp"
#include "twister/meshio/obj_file.hpp"

namespace {

int run(const std::string& args) {
  return twister::host_test::run_command(std::string(TWISTER_CLI) + " " + args + " 2>&1").exit_code;
}

TEST(MeshCommand, SphereCenterTranslatesEveryVertex) {
  const twister::host_test::ScratchDir dir("twister_mesh_test");
  const auto at_origin = dir / "0.obj";
  const auto moved = dir / "c.obj";
  ASSERT_EQ(run("mesh sphere -n 8 --segments 12 --size 0.3 --out " + at_origin.string()), 0);
  ASSERT_EQ(run("mesh sphere -n 8 --segments 12 --size 0.3 --center 0.55 -0.2 0.1 --out " +
                moved.string()),
            0);
  const auto a = twister::meshio::load_obj(at_origin);
  const auto b = twister::meshio::load_obj(moved);
  ASSERT_TRUE(a) << a.error().message;
  ASSERT_TRUE(b) << b.error().message;
  const auto& ma = a->buffer->mesh();
  const auto& mb = b->buffer->mesh();
  ASSERT_EQ(ma.vertex_count(), mb.vertex_count());
  ASSERT_EQ(ma.triangle_count(), mb.triangle_count());
  for (std::uint32_t i = 0; i < ma.vertex_count(); ++i) {
    const glm::vec3 d = mb.position(i) - ma.position(i);
    EXPECT_NEAR(d.x, 0.55f, 1e-5f);
    EXPECT_NEAR(d.y, -0.2f, 1e-5f);
    EXPECT_NEAR(d.z, 0.1f, 1e-5f);
    EXPECT_NEAR(glm::length(ma.position(i)), 0.3f, 1e-5f);
  }
  // Not three numbers: bad input.
  EXPECT_EQ(run("mesh sphere --center 1 2 --out " + moved.string()), 2);
  EXPECT_EQ(run("mesh sphere --center 1 x 3 --out " + moved.string()), 2);
}

}  // namespace
