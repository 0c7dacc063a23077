#include "warp_command.hpp"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "cli_exit_code.hpp"
#include "cli_log.hpp"
#include "twister/math/symmetry.hpp"
#include "twister/math/warp_plan.hpp"
#include "warp_case.hpp"

namespace twister::cli {

namespace {

[[nodiscard]] int bad_input(const std::string& source, int line, const std::string& message) {
  return fail(kExitBadInput, source + ":" + std::to_string(line) + ": " + message);
}

// Under a symmetry (docs/math.md §11) the points are warped in double by
// math::SymmetricWarp (there is no float kernel per image yet).
int run_symmetric_warp(const std::string& source, const WarpCase& c) {
  static math::SymmetricWarp warp;  // about 5 KiB: not on the stack
  const Status built = warp.build(c.symmetry, c.start, c.radius, c.method);
  if (built.code() == StatusCode::failed_precondition) {
    return bad_input(source, c.hand_lines.back(),
                     "the scodef constraint system is singular (constraint points of the hands "
                     "or of their images coincide or crowd together)");
  }
  if (const Status s = built; !s.ok()) {
    return bad_input(source, c.hand_lines.back(),
                     std::string("cannot build the symmetric warp: ") + s.name());
  }
  if (const Status s = warp.update(c.end); !s.ok()) {
    return bad_input(source, c.hand_lines.back(),
                     std::string("cannot update the warp: ") + s.name());
  }
  for (const glm::dvec3& p : c.points) {
    const glm::dvec3 q = warp.warp_point(p);
    std::printf("%.9g %.9g %.9g\n", q.x, q.y, q.z);
  }
  return kExitOk;
}

int run_warp(const std::string& path) {
  std::string text;
  if (path == "-") {
    text.assign(std::istreambuf_iterator<char>(std::cin), {});
  } else {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
      return fail(kExitBadInput, "cannot open '" + path + "'");
    }
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string source = path == "-" ? "<stdin>" : path;
  auto parsed = parse_warp_case(text);
  if (auto* err = std::get_if<WarpCaseError>(&parsed)) {
    return bad_input(source, err->line, err->message);
  }
  const WarpCase& c = std::get<WarpCase>(parsed);
  if (!c.symmetry.trivial()) return run_symmetric_warp(source, c);

  // The station's path: float SoA columns, a plan built once, update, apply.
  const std::size_t n = c.points.size();
  std::vector<float> x(n), y(n), z(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = static_cast<float>(c.points[i].x);
    y[i] = static_cast<float>(c.points[i].y);
    z[i] = static_cast<float>(c.points[i].z);
  }
  std::vector<float> ox = x, oy = y, oz = z;
  std::vector<std::uint32_t> indices(n);
  std::vector<float> w1(n), w2(n);
  math::WarpPlan plan(math::WarpPlanStorage{indices, w1, w2});
  const math::ConstVertexColumns rest(x, y, z);
  const Status built = plan.build(rest, c.start, c.radius, c.method);
  if (built.code() == StatusCode::failed_precondition) {
    return bad_input(source, c.hand_lines.back(),
                     "the scodef constraint system is singular (constraint points of the two "
                     "hands coincide)");
  }
  if (!built.ok()) {
    return bad_input(source, c.hand_lines.back(),
                     std::string("cannot build the warp: ") + built.name());
  }
  if (const Status s = plan.update(c.end); !s.ok()) {
    return bad_input(source, c.hand_lines.back(),
                     std::string("cannot update the warp: ") + s.name());
  }
  if (const Status s = plan.apply(rest, math::VertexColumns{ox, oy, oz}); !s.ok()) {
    return fail(kExitFailure, std::string("apply failed: ") + s.name());
  }
  for (std::size_t i = 0; i < n; ++i) {
    std::printf("%.9g %.9g %.9g\n", static_cast<double>(ox[i]), static_cast<double>(oy[i]),
                static_cast<double>(oz[i]));
  }
  return kExitOk;
}

}  // namespace

void add_warp_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("warp", "Warp the points of a case file (docs/math.md §10)");
  auto path = std::make_shared<std::string>();
  cmd->add_option("case", *path, "case file, or - for stdin")->required();
  cmd->callback([path, &exit_code] {
    start_command_log("warp");
    exit_code = run_warp(*path);
  });
}

}  // namespace twister::cli
