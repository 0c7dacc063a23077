// PNG snapshots of the display (libpng, compression 1: ~12 ms for 800x600).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "twister/hal/expected.hpp"

namespace twister::bridge {

// Writes RGBA rows (top to bottom) as PNG. Error io_error naming the path when it
// cannot be written.
hal::Expected<void> write_png(const std::string& path, int width, int height,
                              const std::vector<std::uint8_t>& rgba);

}  // namespace twister::bridge
