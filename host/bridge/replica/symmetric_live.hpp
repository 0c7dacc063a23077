// What the display's vertex shader needs to draw a symmetric live stroke (docs/math.md
// §11.2, §11.7; issue 26), built by the replica from its plan: per grab, the weights the
// plan's float path uses (math::SymmetricFloat::visit_weights: kept or computed as
// apply() computes them), only the non-zero ones, one entry per (vertex, image of a hand)
// with the weight's gradient (for the warped normal); per hands update the kernel form of
// every image's screw (g S_h g^-1, math::SymmetricFloat::image_hand) and its share 1/|G_h|.
// The shader sums, per vertex, share * displacement(image, p, weight) over its entries:
// the float path's sum, term by term.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "twister/math/symmetric_kernel.hpp"

namespace twister::bridge {

// One image's kernel constants as the shader's uniform block holds them (std140: five
// vec4): axis + half angle, mid + cot of the half angle, chord + share, axis x chord,
// shift.
struct SymmetricImageGpu {
  float axis[3];
  float half;
  float mid[3];
  float cot;
  float chord[3];
  float share;
  float axc[3];
  float pad0;
  float shift[3];
  float pad1;
};
static_assert(sizeof(SymmetricImageGpu) == 80, "five std140 vec4");

// The most (vertex, image) entries a stroke may have on the GPU: beyond, the display
// keeps the CPU path (each entry 17 bytes; first entries held exactly as floats).
inline constexpr std::size_t kMaxSymmetricEntries = std::size_t{1} << 23;

struct SymmetricLive {
  // The entries are built for the open stroke (a symmetric twister or rottran stroke
  // whose plan runs the float path, within kMaxSymmetricEntries): the shader can draw it.
  bool ready = false;
  // Per mesh vertex: its first entry and its entry count (floats: a vertex attribute).
  std::vector<float> spans;
  // Per entry: the weight (> 0) and its gradient at the rest position (x y z).
  std::vector<float> entries;
  // Per entry: its image (index into images).
  std::vector<std::uint8_t> entry_image;
  // New (unique in the process) whenever spans/entries are rebuilt: the renderer uploads
  // them once.
  std::uint64_t version = 0;
  // The images' kernel constants for the current hands, in the plan's image order.
  std::array<SymmetricImageGpu, math::SymmetricFloat::kMaxImages> images{};
  std::size_t image_count = 0;  // 0: the hands could not be followed (not drawable)
  std::size_t entry_count() const { return entry_image.size(); }
};

}  // namespace twister::bridge
