// WarpMethod: which space warp a grab applies (docs/math.md §4-§6).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace twister::math {

enum class WarpMethod : std::uint8_t {
  twister,  // decayed minimal screw (the paper's operator)
  rottran,  // decayed rotation about the grab point, then decayed translation
  scodef,   // Borrel-Rappoport simple constrained deformation, 3 constraints per hand
};

// "twister" | "rottran" | "scodef".
constexpr std::string_view warp_method_name(WarpMethod method) {
  switch (method) {
    case WarpMethod::twister:
      return "twister";
    case WarpMethod::rottran:
      return "rottran";
    case WarpMethod::scodef:
      return "scodef";
  }
  return "unknown";
}

// Inverse of warp_method_name; nullopt for any other text.
constexpr std::optional<WarpMethod> parse_warp_method(std::string_view name) {
  if (name == "twister") return WarpMethod::twister;
  if (name == "rottran") return WarpMethod::rottran;
  if (name == "scodef") return WarpMethod::scodef;
  return std::nullopt;
}

}  // namespace twister::math
