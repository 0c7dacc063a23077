// Exit codes shared by the twister subcommands, and the way a subcommand's callback
// ends the program with one of them.
#pragma once

namespace twister::cli {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;   // the input was fine but the work failed (I/O, device)
constexpr int kExitBadInput = 2;  // bad options or malformed input; nothing was written

// Thrown from a subcommand callback to end the program with `code`.
struct Exit {
  int code;
};

}  // namespace twister::cli
