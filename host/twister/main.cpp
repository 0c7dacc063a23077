// `twister`: command-line tools for the station's math, tracker, journal and meshes.
// Each subcommand lives in its own <name>_command.cpp and registers itself here.
#include <CLI/CLI.hpp>
#include <exception>

#include "calibrate_command.hpp"
#include "cli_exit_code.hpp"
#include "cli_log.hpp"
#include "export_command.hpp"
#include "fastrak_dump_command.hpp"
#include "figure8_command.hpp"
#include "journal_command.hpp"
#include "mesh_command.hpp"
#include "replay_command.hpp"
#include "warp_command.hpp"

namespace {

int run(int argc, char** argv) {
  CLI::App app{"twister: tools for the Twister sculpting station"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "twister 0.1.0");
  // Subcommands (one line each); the one that runs leaves its exit code here.
  int exit_code = twister::cli::kExitOk;
  twister::cli::add_warp_command(app, exit_code);
  twister::cli::add_figure8_command(app, exit_code);
  twister::cli::add_fastrak_dump_command(app, exit_code);
  twister::cli::add_replay_command(app, exit_code);
  twister::cli::add_mesh_command(app, exit_code);
  twister::cli::add_journal_command(app, exit_code);
  twister::cli::add_calibrate_command(app, exit_code);
  twister::cli::add_export_command(app, exit_code);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help / --version exit 0; every usage error exits 2 (bad options).
    const int rc = app.exit(e);
    return rc == 0 ? twister::cli::kExitOk : twister::cli::kExitBadInput;
  }
  return exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  twister::cli::cli_log().configure(
      {"twister", twister::hal::LogLevel::notice, twister::hal::stderr_is_journal(), 2, false});
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    twister::cli::cli_log().error("", "%s", e.what());
    return twister::cli::kExitFailure;
  }
}
