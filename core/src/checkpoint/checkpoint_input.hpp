// Reading a session checkpoint (private to core/src/input): sequential reads through
// a caller-owned window with the CRC of everything taken, and the history's sections
// (checkpoint_history.cpp), shared by verify and restore (checkpoint_reader.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/base/result.hpp"
#include "twister/checkpoint/session_checkpoint.hpp"
#include "twister/ports/storage.hpp"
#include "twister/session/sculpt_session.hpp"

namespace twister::checkpoint::format {

class Input {
 public:
  // Reads `storage` from `offset` on through `window` (at least kMaxElementBytes).
  Input(ports::Storage& storage, std::span<std::byte> window, std::uint64_t offset = 0)
      : storage_(storage), window_(window), offset_(offset) {}
  Input(const Input&) = delete;
  Input& operator=(const Input&) = delete;

  // The next `n` bytes (n <= the window). false: storage failure or the end.
  bool take(std::size_t n, std::span<const std::byte>& out);
  // CRC-32 of every byte taken.
  std::uint32_t crc() const { return crc_; }

 private:
  ports::Storage& storage_;
  std::span<std::byte> window_;
  std::size_t pos_ = 0;
  std::size_t size_ = 0;
  std::uint64_t offset_ = 0;  // file offset of window_[pos_]
  std::uint32_t crc_ = 0;
};

// File offset of the undo entries.
std::uint64_t entries_offset(const CheckpointHeader& header);

// Checks (and with `target`, writes into its history's storage) the entries, vertex
// changes and triangle changes that `in` stands at. The header fits the session
// (capacities, counts within them). data_loss: a value or the structure is wrong.
Status walk_history(Input& in, ports::Storage& storage, const CheckpointHeader& header,
                    session::SculptSession* target);

}  // namespace twister::checkpoint::format
