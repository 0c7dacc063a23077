#include "mesh_command.hpp"

#include <cmath>
#include <cstdio>
#include <glm/vec3.hpp>
#include <memory>
#include <string>
#include <vector>

#include "cli_exit.hpp"
#include "cli_log.hpp"
#include "twister/meshio/mesh_generator.hpp"
#include "twister/meshio/obj_file.hpp"

namespace twister::cli {
namespace {

struct Options {
  std::string shape;
  std::string out;
  std::size_t n = 33;                             // grid: vertices per side; sphere: rings
  std::size_t segments = 32;                      // sphere only
  float size_m = 1.0f;                            // grid: half size; sphere: radius
  std::vector<float> center_m{0.0f, 0.0f, 0.0f};  // translation of the whole mesh
};

// CLI11's number checks let "nan" and "inf" through: every size must be finite.
void check_finite(const Options& o) {
  bool finite = std::isfinite(o.size_m);
  for (const float c : o.center_m) finite = finite && std::isfinite(c);
  if (!finite) {
    cli_log().error("", "--size and --center must be finite numbers");
    throw Exit{kExitBadInput};
  }
}

void run_mesh(const Options& o) {
  check_finite(o);
  const bool grid = o.shape == "grid";
  const std::size_t vertices =
      grid ? meshio::grid_vertices(o.n) : meshio::sphere_vertices(o.n, o.segments);
  const std::size_t triangles =
      grid ? meshio::grid_triangles(o.n) : meshio::sphere_triangles(o.n, o.segments);
  meshio::MeshBuffer buffer(vertices, triangles);
  const Status s = grid ? meshio::make_grid(buffer.mesh(), o.n, o.size_m)
                        : meshio::make_sphere(buffer.mesh(), o.n, o.segments, o.size_m);
  if (!s.ok()) {
    cli_log().error("", "cannot make that %s: %s", o.shape.c_str(), s.name());
    throw Exit{kExitBadInput};
  }
  // Placed where a scene needs it (e.g. in front of the simulated transmitter).
  const glm::vec3 center(o.center_m[0], o.center_m[1], o.center_m[2]);
  for (std::uint32_t i = 0; i < buffer.mesh().vertex_count(); ++i) {
    buffer.mesh().set_position(i, buffer.mesh().position(i) + center);
  }
  if (auto saved = meshio::save_obj(o.out, buffer.mesh()); !saved) {
    cli_log().error("", "%s", saved.error().message.c_str());
    throw Exit{kExitFailure};
  }
  std::printf("%s: %zu vertices, %zu triangles\n", o.out.c_str(), buffer.mesh().vertex_count(),
              buffer.mesh().triangle_count());
}

}  // namespace

void add_mesh_command(CLI::App& app) {
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand("mesh", "Write a procedural grid or sphere mesh as OBJ");
  cmd->add_option("shape", options->shape, "grid | sphere")
      ->required()
      ->check(CLI::IsMember({"grid", "sphere"}));
  cmd->add_option("--out", options->out, "Output OBJ file")->required();
  cmd->add_option("-n", options->n, "grid: vertices per side (>= 2); sphere: rings (>= 2)")
      ->check(CLI::Range(std::size_t{2}, std::size_t{4096}));
  cmd->add_option("--segments", options->segments, "sphere: segments (>= 3)")
      ->check(CLI::Range(std::size_t{3}, std::size_t{4096}));
  cmd->add_option("--size", options->size_m, "grid half size / sphere radius (m)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--center", options->center_m, "centre of the mesh: X Y Z (m, default 0 0 0)")
      ->expected(3)
      ->check(CLI::Number);
  cmd->callback([options] {
    start_command_log("mesh");
    run_mesh(*options);
  });
}

}  // namespace twister::cli
