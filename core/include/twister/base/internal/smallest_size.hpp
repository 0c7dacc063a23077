// The smallest unsigned type that counts 0..N: the size member of the inline
// containers, so a small vector inside a message or record costs one byte, not eight.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>

namespace twister::internal {

template <std::size_t N>
using SmallestSize = std::conditional_t<
    (N <= std::numeric_limits<std::uint8_t>::max()), std::uint8_t,
    std::conditional_t<(N <= std::numeric_limits<std::uint16_t>::max()), std::uint16_t,
                       std::conditional_t<(N <= std::numeric_limits<std::uint32_t>::max()),
                                          std::uint32_t, std::size_t>>>;

}  // namespace twister::internal
