// The byte layout of a session checkpoint (session_checkpoint.hpp), shared by its
// writer and reader (private to core/src/input).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/result.hpp"
#include "twister/checkpoint/session_checkpoint.hpp"
#include "twister/session/undo_history.hpp"

namespace twister::checkpoint::format {

inline constexpr std::size_t kMaxElementBytes =
    std::max({kCheckpointHeaderBytes, kCheckpointEntryBytes, kCheckpointChangeBytes,
              kCheckpointTriangleBytes, kCheckpointTriangleChangeBytes});

void encode_header(const CheckpointHeader& header, std::span<std::byte> out);
// data_loss: wrong magic or version (version 1 included).
Result<CheckpointHeader> decode_header(std::span<const std::byte> in);

void encode_entry(const session::UndoEntry& entry, std::span<std::byte> out);
// false: a non-finite or non-orthonormal pose, a bad flag or padding byte, or an
// entry without topology whose topology fields are not zero.
bool decode_entry(std::span<const std::byte> in, session::UndoEntry& entry);

void encode_change(const session::VertexChange& change, std::span<std::byte> out);
// false: a non-finite position.
bool decode_change(std::span<const std::byte> in, session::VertexChange& change);

void encode_triangle(const std::array<std::uint32_t, 3>& triangle, std::span<std::byte> out);
std::array<std::uint32_t, 3> decode_triangle(std::span<const std::byte> in);

void encode_triangle_change(const session::TriangleChange& change, std::span<std::byte> out);
session::TriangleChange decode_triangle_change(std::span<const std::byte> in);

}  // namespace twister::checkpoint::format
