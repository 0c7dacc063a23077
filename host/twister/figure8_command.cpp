#include "figure8_command.hpp"

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli_exit_code.hpp"
#include "cli_log.hpp"
#include "figure8_experiment.hpp"
#include "figure8_plot.hpp"
#include "twister/hal/output_file.hpp"

namespace twister::cli {

namespace {

struct Figure8Options {
  std::string svg;
  std::string png;
  bool force = false;  // replace an existing SVG / PNG
};

constexpr math::WarpMethod kMethods[] = {math::WarpMethod::twister, math::WarpMethod::rottran,
                                         math::WarpMethod::scodef};

// The table of one experiment on stdout, and its curves; nothing when a curve fails
// (the failure logged).
std::optional<std::vector<Figure8Curve>> run_table(const Figure8Setup& setup) {
  std::printf(
      "# %zu points from x = -1 to 1, grabs at x = -0.5 and 0.5, r = %g, both hands "
      "move by (0, %g, 0); hand 1 turns +angle about z, hand 2 -angle\n",
      setup.points, setup.radius, setup.lift);
  std::printf("# cell: self-intersections / sharpest turn between segments (degrees)\n");
  std::printf("%6s", "angle");
  for (const auto m : kMethods)
    std::printf("  %-16s", std::string(math::warp_method_name(m)).c_str());
  std::printf("\n");
  std::vector<Figure8Curve> curves;
  for (const int angle : figure8_angles()) {
    std::printf("%6d", angle);
    for (const auto m : kMethods) {
      Figure8Curve c;
      if (const Status s = run_figure8_curve(setup, angle, m, c); !s.ok()) {
        cli_log().error("", "%s at %d degrees failed: %s",
                        std::string(math::warp_method_name(m)).c_str(), angle, s.name());
        return std::nullopt;
      }
      char cell[32];
      std::snprintf(cell, sizeof cell, "%zu / %.1f", c.intersections, c.sharpest_turn_deg);
      std::printf("  %-16s", cell);
      curves.push_back(std::move(c));
    }
    std::printf("\n");
  }
  return curves;
}

std::string panel_heading(const char* label, const Figure8Setup& s) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s: r = %g, both hands move by (0, %g, 0)", label, s.radius,
                s.lift);
  return buf;
}

int run_figure8(const Figure8Options& opt) {
  // The output rule before the work (twister/hal/output_file.hpp).
  const std::pair<const std::string*, hal::OutputKind> outputs[] = {
      {&opt.svg, hal::OutputKind::svg}, {&opt.png, hal::OutputKind::png}};
  for (const auto& [path, kind] : outputs) {
    if (path->empty()) continue;
    if (auto free = hal::check_output_path(*path, {kind, opt.force}); !free) {
      return fail(kExitFailure, free.error().message);
    }
  }
  // Both experiments of docs/math.md §9: the paper-like one and the small displacement.
  const Figure8Setup paper_like{};
  const Figure8Setup small{2001, 1.0, 0.3};
  Figure8Picture picture{
      "Figure 8: a straight line bent by two hands, three warp methods (docs/math.md \u00a79)",
      "2001 points from x = \u22121 to 1, grabbed at x = \u22120.5 and +0.5; hand 1 turns by "
      "+angle about z, hand 2 by \u2212angle. Cell: self-intersections, sharpest turn between "
      "segments. One scale per panel.",
      {}};
  picture.panels.push_back(Figure8Panel{
      panel_heading("A. Large displacement, the balls touch", paper_like), paper_like, {}});
  picture.panels.push_back(Figure8Panel{panel_heading("B. Small displacement", small), small, {}});
  auto paper_like_curves = run_table(paper_like);
  if (!paper_like_curves) return kExitFailure;
  picture.panels[0].curves = std::move(*paper_like_curves);
  std::printf("\n");
  auto small_curves = run_table(small);
  if (!small_curves) return kExitFailure;
  picture.panels[1].curves = std::move(*small_curves);
  if (!opt.svg.empty()) {
    if (auto written = write_figure8_svg(opt.svg, picture, opt.force); !written) {
      return fail(kExitFailure, written.error().message);
    }
  }
  if (!opt.png.empty()) {
    if (auto written = write_figure8_png(opt.png, picture, opt.force); !written) {
      return fail(kExitFailure, written.error().message);
    }
  }
  return kExitOk;
}

}  // namespace

void add_figure8_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "figure8", "Run the Figure 8 comparison of the warp methods (docs/math.md §9)");
  auto opt = std::make_shared<Figure8Options>();
  cmd->add_option("--svg", opt->svg, "write the grid of curves as SVG");
  cmd->add_option("--png", opt->png, "write the grid of curves as PNG");
  cmd->add_flag("--force", opt->force,
                "replace an existing SVG / PNG (never another kind of file)");
  cmd->callback([opt, &exit_code] {
    start_command_log("figure8");
    exit_code = run_figure8(*opt);
  });
}

}  // namespace twister::cli
