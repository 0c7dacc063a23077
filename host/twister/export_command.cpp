#include "export_command.hpp"

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli_exit_code.hpp"
#include "cli_log.hpp"
#include "journal_replay.hpp"
#include "model_session.hpp"
#include "twister/hal/output_file.hpp"
#include "twister/meshio/mesh_export.hpp"
#include "twister/meshio/thumbnail.hpp"

namespace twister::cli {
namespace {

namespace fs = std::filesystem;

struct Options {
  std::string journal;
  std::string base;  // default: base.obj beside the journal
  std::string out_dir;
  std::string name;  // file stem; default the journal's
  bool glb = false;
  bool stl = false;
  bool thumbnail = false;
  std::vector<float> up{0.0F, 0.0F, 1.0F};
  int size = 512;
  bool force = false;
  bool strict = false;
  ReplaySettings replay;
};

struct Target {
  std::string path;
  hal::OutputKind kind;
};

std::vector<Target> targets(const Options& o) {
  const std::string stem = (fs::path(o.out_dir) / o.name).string();
  std::vector<Target> t;
  if (o.glb) t.push_back({stem + ".glb", hal::OutputKind::glb});
  if (o.stl) t.push_back({stem + ".stl", hal::OutputKind::stl});
  if (o.thumbnail) t.push_back({stem + ".png", hal::OutputKind::png});
  return t;
}

// Before any work: the base model, the folder, and every output (never an input,
// never a file that is there unless --force and of its kind).
int check_inputs(Options& o) {
  if (o.base.empty()) {
    const fs::path beside = fs::path(o.journal).parent_path() / "base.obj";
    std::error_code ec;
    if (!fs::is_regular_file(beside, ec)) {
      return fail(kExitBadInput,
                  "no base model: pass --base MODEL.obj (the station.mesh the "
                  "journal was recorded on), or put it beside the journal as " +
                      beside.string());
    }
    o.base = beside.string();
  }
  if (o.name.empty()) o.name = fs::path(o.journal).stem().string();
  if (o.name.empty()) return fail(kExitBadInput, "--name: cannot be empty");
  std::error_code ec;
  if (!fs::is_directory(o.out_dir, ec)) {
    if (fs::exists(o.out_dir, ec)) return fail(kExitBadInput, o.out_dir + " is not a folder");
    if (!fs::create_directory(o.out_dir, ec)) {
      return fail(kExitBadInput, "cannot create the folder " + o.out_dir + ": " + ec.message());
    }
  }
  for (const Target& t : targets(o)) {
    for (const std::string* input : {&o.journal, &o.base}) {
      if (hal::same_file(t.path, *input)) {
        return fail(kExitBadInput, t.path + " is the input " + *input + "; it is not replaced");
      }
    }
    if (auto free = hal::check_output_path(t.path, {t.kind, o.force}); !free) {
      return fail(kExitBadInput, free.error().message);
    }
  }
  return kExitOk;
}

void print_report(const meshio::ExportReport& r) {
  std::printf("wrote %s: %zu triangles, %.6g x %.6g x %.6g %s, %zu bytes\n", r.path.c_str(),
              r.check.triangles, r.size.x, r.size.y, r.size.z, r.units, r.bytes);
}

int write_outputs(const Options& o, const mesh::Mesh& mesh) {
  meshio::ExportOptions e;
  e.up = glm::vec3(o.up[0], o.up[1], o.up[2]);
  e.force = o.force;
  bool open = false;
  for (const Target& t : targets(o)) {
    if (t.kind == hal::OutputKind::png) {
      if (auto png = meshio::render_thumbnail_png(mesh, e.up, o.size, t.path, o.force); !png) {
        return fail(png.error().status.code() == StatusCode::invalid_argument ? kExitBadInput
                                                                              : kExitFailure,
                    png.error().message);
      }
      std::printf("wrote %s: %d x %d thumbnail\n", t.path.c_str(), o.size, o.size);
      continue;
    }
    auto report = t.kind == hal::OutputKind::stl ? meshio::write_stl(t.path, mesh, e)
                                                 : meshio::write_glb(t.path, mesh, e);
    if (!report) {
      return fail(report.error().status.code() == StatusCode::invalid_argument ? kExitBadInput
                                                                               : kExitFailure,
                  report.error().message);
    }
    print_report(*report);
    if (t.kind == hal::OutputKind::stl) {
      std::printf("check %s\n", meshio::describe(report->check).c_str());
      open = !report->check.watertight();
      if (open) {
        cli_log().warning("", "%s is not a watertight solid (%s); a slicer may need to repair it",
                          t.path.c_str(), meshio::describe(report->check).c_str());
      }
    }
  }
  return o.strict && open ? kExitFailure : kExitOk;
}

int run_export(Options& o) {
  if (!o.glb && !o.stl && !o.thumbnail) o.glb = o.stl = o.thumbnail = true;
  if (o.up[0] == 0.0F && o.up[1] == 0.0F && o.up[2] == 0.0F) {
    return fail(kExitBadInput, "--up: expected a non-zero direction, got 0 0 0");
  }
  if (const int refused = check_inputs(o); refused != kExitOk) return refused;
  const ReplayedModel replayed = open_and_replay(o.journal, o.base, o.replay);
  if (replayed.replay.exit_code != kExitOk) return replayed.replay.exit_code;
  const mesh::Mesh& mesh = replayed.model->mesh();
  std::printf("replayed %zu records onto %s: %zu vertices %zu triangles\n", replayed.replay.applied,
              o.base.c_str(), mesh.vertex_count(), mesh.triangle_count());
  return write_outputs(o, mesh);
}

}  // namespace

void add_export_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "export",
      "Replay a journal onto its base model and write what a visitor takes home: binary glTF "
      "(metres, +Y up, a clay material), binary STL (millimetres, +Z up; checked closed and "
      "manifold first, the counts printed) and a PNG thumbnail, upright and centred on the "
      "origin; without --glb/--stl/--thumbnail all three");
  cmd->add_option("journal", options->journal, "Journal file written by twister-station")
      ->required();
  cmd->add_option("--base", options->base,
                  "The model the journal was recorded on (OBJ, the station's station.mesh; "
                  "default: base.obj beside the journal)");
  cmd->add_option("--out", options->out_dir,
                  "Folder for the files (created if missing, one level); nothing in it is "
                  "replaced without --force")
      ->required();
  cmd->add_option("--name", options->name,
                  "File name stem (default: the journal's, e.g. "
                  "visitor.journal -> visitor.glb)");
  cmd->add_flag("--glb", options->glb, "Write NAME.glb (binary glTF 2.0, metres, +Y up)");
  cmd->add_flag("--stl", options->stl, "Write NAME.stl (binary STL, millimetres, +Z up)");
  cmd->add_flag("--thumbnail", options->thumbnail, "Write NAME.png (a thumbnail, --size pixels)");
  cmd->add_option("--up", options->up,
                  "The model's up in its own frame (default 0 0 1: a calibrated work frame's "
                  "+Z; 0 0 -1 for an uncalibrated station, the transmitter frame)")
      ->expected(3);
  cmd->add_option("--size", options->size, "Thumbnail size in pixels (16..4096, default 512)")
      ->check(CLI::Range(16, 4096));
  cmd->add_flag("--force", options->force,
                "Replace existing files of the same kind (never a journal, checkpoint, a file "
                "a running station holds, or another kind of file)");
  cmd->add_flag("--strict", options->strict,
                "Exit 1 when the STL is not a watertight solid (open, non-manifold or "
                "degenerate); the files are written either way");
  add_replay_options(*cmd, options->replay);
  cmd->callback([options, &exit_code] {
    start_command_log("export",
                      options->replay.quiet ? hal::LogLevel::warning : hal::LogLevel::notice);
    exit_code = run_export(*options);
  });
}

}  // namespace twister::cli
