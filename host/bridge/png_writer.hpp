// PNG snapshots of the display (libpng, compression 1: ~12 ms for 800x600).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "twister/hal/expected.hpp"

namespace twister::bridge {

// Writes RGBA rows (top to bottom) as PNG, atomically (PosixFileSink) and under the
// programs' output rule: it may replace a PNG (a snapshot of an earlier run), never
// anything else (twister/hal/output_file.hpp). Errors io_error / failed_precondition
// naming the path.
hal::Expected<void> write_png(const std::string& path, int width, int height,
                              const std::vector<std::uint8_t>& rgba);

}  // namespace twister::bridge
