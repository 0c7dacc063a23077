#include "replay_command.hpp"

#include <cinttypes>
#include <cstdio>
#include <glm/mat3x3.hpp>
#include <memory>
#include <string>

#include "cli_exit_code.hpp"
#include "cli_log.hpp"
#include "journal_replay.hpp"
#include "model_session.hpp"
#include "twister/hal/output_file.hpp"
#include "twister/meshio/obj_file.hpp"
#include "twister/session/commit_refinement.hpp"
#include "twister/session/sculpt_session.hpp"

namespace twister::cli {
namespace {

struct Options {
  std::string journal;
  std::string mesh_in;
  std::string mesh_out;
  ReplaySettings replay;
  bool world = false;
  bool force = false;  // --force: replace an existing OBJ (never anything else)
};

// Object frame -> world: p_world = origin + [U V W] p.
void to_world(mesh::Mesh& m, const math::Frame& pose) {
  const glm::dmat3 r(pose.u, pose.v, pose.w);
  for (std::uint32_t i = 0; i < m.vertex_count(); ++i) {
    m.set_position(i, glm::vec3(pose.origin + r * glm::dvec3(m.position(i))));
  }
}

// Refined commits: what they added, and a warning when the capacity stopped one (the
// station's was larger, or the result differs from the station's).
void report_refinement(const session::RefineStatus& r, const Options& o) {
  if (r.refined_commits == 0) return;
  std::printf("refined %llu commits, %llu vertices added\n",
              static_cast<unsigned long long>(r.refined_commits),
              static_cast<unsigned long long>(r.vertices_added));
  if (r.capacity_stops > 0) {
    cli_log().warning(
        "",
        "refinement stopped at this mesh's capacity in %llu commits (--spare-vertices "
        "%zu); the station's result differs unless it had the same spare capacity",
        static_cast<unsigned long long>(r.capacity_stops), o.replay.spare_vertices);
  }
}

// Before any work: the output may not be an input, and must pass the output rule
// (never a journal, checkpoint, locked file such as a running station's journal or
// base model; an existing OBJ only with --force). kExitOk when it may be written.
int check_output(const Options& o) {
  for (const std::string* input : {&o.journal, &o.mesh_in}) {
    if (hal::same_file(o.mesh_out, *input)) {
      return fail(kExitBadInput, o.mesh_out + " is the input " + *input + "; it is not replaced");
    }
  }
  if (auto free = hal::check_output_path(o.mesh_out, {hal::OutputKind::obj, o.force}); !free) {
    return fail(kExitBadInput, free.error().message);
  }
  return kExitOk;
}

int run_replay(const Options& o) {
  if (const int refused = check_output(o); refused != kExitOk) return refused;
  const ReplayedModel replayed = open_and_replay(o.journal, o.mesh_in, o.replay);
  if (replayed.replay.exit_code != kExitOk) return replayed.replay.exit_code;
  mesh::Mesh& mesh = replayed.model->mesh();
  session::SculptSession& session = replayed.model->session();
  const std::size_t applied = replayed.replay.applied;
  if (o.world) to_world(mesh, session.object_pose());
  if (auto saved = meshio::save_obj(o.mesh_out, mesh, o.force); !saved) {
    return fail(kExitFailure, saved.error().message);
  }
  const session::ReplayStats& st = session.replay_stats();
  const math::Frame& pose = session.object_pose();
  std::printf("replayed %zu records (strokes %zu, moves %zu, undos %zu, redos %zu)\n", applied,
              st.strokes, st.moves, st.undos, st.redos);
  report_refinement(session.state().refine, o);
  std::printf("mesh %zu vertices %zu triangles checksum %016" PRIx64 "\n", mesh.vertex_count(),
              mesh.triangle_count(), mesh.checksum());
  std::printf("object origin %.9g %.9g %.9g u %.9g %.9g %.9g v %.9g %.9g %.9g\n", pose.origin.x,
              pose.origin.y, pose.origin.z, pose.u.x, pose.u.y, pose.u.z, pose.v.x, pose.v.y,
              pose.v.z);
  return kExitOk;
}

}  // namespace

void add_replay_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "replay", "Apply a station's stroke journal to a mesh (same or finer) and write the result");
  cmd->add_option("journal", options->journal, "Journal file written by twister-station")
      ->required();
  cmd->add_option("--mesh", options->mesh_in, "Initial mesh (OBJ)")->required();
  cmd->add_option("--out", options->mesh_out, "Output mesh (OBJ)")->required();
  add_replay_options(*cmd, options->replay);
  cmd->add_flag("--force", options->force,
                "Replace an existing OBJ at --out (never a journal, checkpoint, a file a "
                "running station holds, or another kind of file)");
  cmd->add_flag("--world", options->world, "Write world coordinates (apply the object pose)");
  cmd->callback([options, &exit_code] {
    start_command_log("replay",
                      options->replay.quiet ? hal::LogLevel::warning : hal::LogLevel::notice);
    exit_code = run_replay(*options);
  });
}

}  // namespace twister::cli
