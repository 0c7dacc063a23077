// A thumbnail of a model for the visitor's archive and the attract screen: a small CPU
// z-buffer raster (no GL: the station has no display), upright (`up`, the model's up
// in its own frame, as in mesh_export.hpp), seen from a three-quarter view slightly
// above, framed to the bounding box, a key light with a soft fill and rim on a warm
// clay colour over a quiet background gradient. PNG through libpng.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "twister/hal/expected.hpp"
#include "twister/mesh/mesh.hpp"

namespace twister::meshio {

struct ThumbnailImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // rows top to bottom
  std::size_t covered_pixels = 0;  // pixels the model covers
};

// Renders `mesh` into a size x size image (size 16..4096). invalid_argument: size out
// of range, `up` zero or not finite, no triangles.
hal::Expected<ThumbnailImage> render_thumbnail(const mesh::Mesh& mesh, glm::vec3 up, int size);

// Renders and writes a PNG (atomic; never replaces a file this process did not
// create, or with `force` a PNG: mesh_export.hpp's rule). Errors as render_thumbnail,
// failed_precondition (target refused), io_error; messages name the path.
hal::Expected<void> render_thumbnail_png(const mesh::Mesh& mesh, glm::vec3 up, int size,
                                         const std::string& path, bool force = false);

// PNG bytes of RGBA rows (libpng, 8-bit RGBA). false on a libpng error.
bool encode_png(std::string& out, int width, int height, const std::vector<std::uint8_t>& rgba,
                int compression_level = 6);

}  // namespace twister::meshio
