// The `twister` CLI's log: hal::process_log() with the lines of a command-line tool,
// "twister <command>: message" (no level words: the exit code says it failed; tests
// and scripts match these lines). Each subcommand's callback starts its log first;
// its code then writes through cli_log() (errors = error, recoverable trouble such
// as a torn journal tail = warning, progress and counters = notice). Results go to
// stdout, never here.
#pragma once

#include <string>

#include "twister/hal/logger.hpp"

namespace twister::cli {

// The process's logger as main() configures it (program "twister", notice).
inline hal::Logger& cli_log() { return hal::process_log(); }

// Names the running subcommand in every line and sets the threshold.
inline hal::Logger& start_command_log(const char* command,
                                      hal::LogLevel threshold = hal::LogLevel::notice) {
  cli_log().configure({std::string("twister ") + command, threshold, hal::stderr_is_journal(), 2,
                       /*level_words=*/false});
  return cli_log();
}

}  // namespace twister::cli
