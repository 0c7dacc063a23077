// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320), as used by zlib and PNG.
// Check value: crc32("123456789") == 0xCBF43926.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace twister {

// CRC of `data`; pass a previous result as `crc` to continue over several spans.
std::uint32_t crc32(std::span<const std::byte> data, std::uint32_t crc = 0);

}  // namespace twister
