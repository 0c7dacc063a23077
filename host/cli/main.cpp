// `twister`: command-line tools for the station's math, tracker and journal.
// Each subcommand lives in its own <name>_command.cpp and registers itself here.
#include <CLI/CLI.hpp>

#include <cstdio>

#include "cli_exit.hpp"
#include "fastrak_dump_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"twister: tools for the Twister sculpting station"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "twister 0.1.0");
  // Subcommands (one line each):
  twister::cli::add_fastrak_dump_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help / --version exit 0; every usage error exits 2 (bad options).
    const int rc = app.exit(e);
    return rc == 0 ? 0 : twister::cli::kExitBadInput;
  } catch (const twister::cli::Exit& e) {
    return e.code;
  }
  return 0;
}
