// `twister calibrate`: the work frame from three stylus touches (origin, a point on the
// model's +X axis, a point in its +Y half-plane), printed as the station config's
// [tracker.calibration.work_frame] table. The touches come from a recorded pose file
// (`twister fastrak-dump` output: the stylus resting at each point in turn) or are
// given as --point X,Y,Z three times (transmitter frame, metres).
#pragma once

#include <CLI/CLI.hpp>

namespace twister::cli {

void add_calibrate_command(CLI::App& app, int& exit_code);

}  // namespace twister::cli
