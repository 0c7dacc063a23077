#include "png_writer.hpp"

#include "twister/hal/posix_file_sink.hpp"
#include "twister/meshio/thumbnail.hpp"

namespace twister::bridge {

hal::Expected<void> write_png(const std::string& path, int width, int height,
                              const std::vector<std::uint8_t>& rgba) {
  std::string bytes;
  // libpng through meshio's encoder; compression 1: ~12 ms for 800x600.
  if (!meshio::encode_png(bytes, width, height, rgba, 1)) {
    return hal::make_error(StatusCode::io_error, "cannot write " + path + " (libpng)");
  }
  // A snapshot may replace a PNG (an earlier run's), nothing else (output_file.hpp).
  return hal::write_output_file(path, bytes, {hal::OutputKind::png, true});
}

}  // namespace twister::bridge
