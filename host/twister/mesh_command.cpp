#include "mesh_command.hpp"

#include <cmath>
#include <cstdio>
#include <glm/vec3.hpp>
#include <memory>
#include <string>
#include <vector>

#include "cli_exit_code.hpp"
#include "cli_log.hpp"
#include "twister/hal/output_file.hpp"
#include "twister/meshio/mesh_generator.hpp"
#include "twister/meshio/obj_file.hpp"

namespace twister::cli {
namespace {

struct Options {
  std::string shape;
  std::string out;
  std::size_t n = 33;  // grid/plane: vertices per side; box: per edge; sphere, cylinder: rings
  std::size_t segments = 32;                      // sphere, cylinder: around the axis
  float size_m = 1.0f;                            // half size (grid, box) or radius
  float half_height_m = 0.0f;                     // cylinder; 0: the radius
  std::vector<float> center_m{0.0f, 0.0f, 0.0f};  // translation of the whole mesh
  bool force = false;                             // replace an existing OBJ
};

// CLI11's number checks let "nan" and "inf" through: every size must be finite.
bool all_finite(const Options& o) {
  bool finite = std::isfinite(o.size_m) && std::isfinite(o.half_height_m);
  for (const float c : o.center_m) finite = finite && std::isfinite(c);
  return finite;
}

struct Counts {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
};

Counts counts_of(const Options& o) {
  if (o.shape == "box") return {meshio::box_vertices(o.n), meshio::box_triangles(o.n)};
  if (o.shape == "cylinder") {
    return {meshio::cylinder_vertices(o.n, o.segments),
            meshio::cylinder_triangles(o.n, o.segments)};
  }
  if (o.shape == "sphere") {
    return {meshio::sphere_vertices(o.n, o.segments), meshio::sphere_triangles(o.n, o.segments)};
  }
  return {meshio::grid_vertices(o.n), meshio::grid_triangles(o.n)};  // grid, plane
}

Status generate(const Options& o, mesh::Mesh& m) {
  if (o.shape == "box") return meshio::make_box(m, o.n, o.size_m);
  if (o.shape == "cylinder") {
    const float half_height = o.half_height_m > 0.0f ? o.half_height_m : o.size_m;
    return meshio::make_cylinder(m, o.n, o.segments, o.size_m, half_height);
  }
  if (o.shape == "sphere") return meshio::make_sphere(m, o.n, o.segments, o.size_m);
  return meshio::make_grid(m, o.n, o.size_m);
}

int run_mesh(const Options& o) {
  if (!all_finite(o)) {
    return fail(kExitBadInput, "--size, --half-height and --center must be finite numbers");
  }
  // Before any work: the output rule (twister/hal/output_file.hpp).
  if (auto free = hal::check_output_path(o.out, {hal::OutputKind::obj, o.force}); !free) {
    return fail(kExitBadInput, free.error().message);
  }
  const Counts c = counts_of(o);
  meshio::MeshBuffer buffer(c.vertices, c.triangles);
  const Status s = generate(o, buffer.mesh());
  if (!s.ok()) {
    return fail(kExitBadInput, "cannot make that " + o.shape + ": " + s.name());
  }
  // Placed where a scene needs it (e.g. in front of the simulated transmitter).
  const glm::vec3 center(o.center_m[0], o.center_m[1], o.center_m[2]);
  for (std::uint32_t i = 0; i < buffer.mesh().vertex_count(); ++i) {
    buffer.mesh().set_position(i, buffer.mesh().position(i) + center);
  }
  if (auto saved = meshio::save_obj(o.out, buffer.mesh(), o.force); !saved) {
    return fail(kExitFailure, saved.error().message);
  }
  std::printf("%s: %zu vertices, %zu triangles\n", o.out.c_str(), buffer.mesh().vertex_count(),
              buffer.mesh().triangle_count());
  return kExitOk;
}

}  // namespace

void add_mesh_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "mesh", "Write a procedural mesh as OBJ: a plane (grid), box, cylinder or sphere");
  cmd->add_option("shape", options->shape, "plane | grid (the same) | box | cylinder | sphere")
      ->required()
      ->check(CLI::IsMember({"grid", "plane", "box", "cylinder", "sphere"}));
  cmd->add_option("--out", options->out, "Output OBJ file")->required();
  cmd->add_flag("--force", options->force,
                "Replace an existing OBJ at --out (never a journal, checkpoint, a file a "
                "running station holds, or another kind of file)");
  cmd->add_option("-n", options->n,
                  "resolution: plane vertices per side, box vertices per edge, sphere rings "
                  "(all >= 2); cylinder bands along the height (>= 1)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{4096}));
  cmd->add_option("--segments", options->segments, "sphere, cylinder: segments around (>= 3)")
      ->check(CLI::Range(std::size_t{3}, std::size_t{4096}));
  cmd->add_option("--size", options->size_m,
                  "plane and box half size / sphere and cylinder radius (m)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--half-height", options->half_height_m,
                  "cylinder: half its height (m; default the radius)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--center", options->center_m, "centre of the mesh: X Y Z (m, default 0 0 0)")
      ->expected(3)
      ->check(CLI::Number);
  cmd->callback([options, &exit_code] {
    start_command_log("mesh");
    exit_code = run_mesh(*options);
  });
}

}  // namespace twister::cli
