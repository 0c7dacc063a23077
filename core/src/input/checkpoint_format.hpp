// The byte layout of a session checkpoint (session_checkpoint.hpp), shared by its
// writer and reader (private to core/src/input).
#pragma once

#include <cstddef>
#include <span>

#include "twister/base/result.hpp"
#include "twister/input/session_checkpoint.hpp"
#include "twister/input/undo_history.hpp"

namespace twister::input::checkpoint_format {

inline constexpr std::size_t kMaxElementBytes = kCheckpointEntryBytes;
static_assert(kCheckpointHeaderBytes <= kMaxElementBytes);

void encode_header(const CheckpointHeader& header, std::span<std::byte> out);
// data_loss: wrong magic or version.
Result<CheckpointHeader> decode_header(std::span<const std::byte> in);

void encode_entry(const UndoEntry& entry, std::span<std::byte> out);
// false: a non-finite or non-orthonormal pose, or a bad flag byte.
bool decode_entry(std::span<const std::byte> in, UndoEntry& entry);

void encode_change(const VertexChange& change, std::span<std::byte> out);
// false: a non-finite position.
bool decode_change(std::span<const std::byte> in, VertexChange& change);

}  // namespace twister::input::checkpoint_format
