// Exit codes shared by the twister subcommands, returned as values: each subcommand's
// run function returns one, its CLI11 callback leaves it in the slot main() hands to
// every add_*_command, and main() returns it (no exceptions carry them).
#pragma once

#include <string>

#include "cli_log.hpp"

namespace twister::cli {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;   // the input was fine but the work failed (I/O, device)
constexpr int kExitBadInput = 2;  // bad options or malformed input; nothing was written

// Logs `message` as the running command's error and returns `code`, so a run function
// ends with `return fail(kExitBadInput, "...");`.
[[nodiscard]] inline int fail(int code, const std::string& message) {
  cli_log().error("", "%s", message.c_str());
  return code;
}

}  // namespace twister::cli
