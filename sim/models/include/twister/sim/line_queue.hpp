// LineQueue: the bytes on the simulated Fastrak's serial line, as chunks (a record,
// a reply, a burst of noise) that each finish transmitting at a `ready` time.
// Fixed capacity (kBytes bytes in kChunks chunks), no heap: the model queues into it
// and the reader takes bytes out of the front chunk once it is ready, partly if the
// reader's buffer is full. Not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "twister/ports/clock.hpp"

namespace twister::sim {

class LineQueue {
 public:
  static constexpr std::size_t kBytes = 32768;  // ~2.8 s of a 115200 baud line
  static constexpr std::size_t kChunks = 1024;
  static_assert((kBytes & (kBytes - 1)) == 0 && (kChunks & (kChunks - 1)) == 0,
                "ring sizes are powers of two");

  // Bytes that fit in the chunk being built (0 when every chunk slot is used).
  std::size_t room() const { return chunks_ == kChunks ? 0 : kBytes - bytes_ - building_; }
  // Appends a byte to the chunk being built; false (dropped) when there is no room.
  bool push(std::byte b) {
    if (room() == 0) return false;
    data_[(head_ + bytes_ + building_) & (kBytes - 1)] = b;
    ++building_;
    return true;
  }
  // Closes the chunk being built: its bytes are readable from `ready` on.
  void end_chunk(ports::TimestampUs ready) {
    if (chunks_ == kChunks) return;
    chunk_[(chunk_head_ + chunks_) & (kChunks - 1)] = {ready, building_};
    ++chunks_;
    bytes_ += building_;
    building_ = 0;
  }

  bool empty() const { return chunks_ == 0; }
  // The front chunk's ready time (only when !empty()).
  ports::TimestampUs front_ready() const { return chunk_[chunk_head_].ready; }
  // Bytes left in the front chunk (only when !empty()).
  std::size_t front_left() const { return chunk_[chunk_head_].size; }
  // Takes the next byte of the front chunk (only when front_left() > 0).
  std::byte take() {
    const std::byte b = data_[head_];
    head_ = (head_ + 1) & (kBytes - 1);
    --bytes_;
    --chunk_[chunk_head_].size;
    return b;
  }
  // Drops the front chunk (once front_left() is 0, or to discard it).
  void pop_front() {
    const std::size_t left = chunk_[chunk_head_].size;
    head_ = (head_ + left) & (kBytes - 1);
    bytes_ -= left;
    chunk_head_ = (chunk_head_ + 1) & (kChunks - 1);
    --chunks_;
  }
  void clear() { head_ = bytes_ = building_ = chunk_head_ = chunks_ = 0; }

 private:
  struct Chunk {
    ports::TimestampUs ready = 0;
    std::size_t size = 0;  // bytes not yet taken
  };
  std::array<std::byte, kBytes> data_{};
  std::size_t head_ = 0;      // first byte of the front chunk
  std::size_t bytes_ = 0;     // bytes in closed chunks
  std::size_t building_ = 0;  // bytes of the chunk being built
  std::array<Chunk, kChunks> chunk_{};
  std::size_t chunk_head_ = 0;
  std::size_t chunks_ = 0;
};

}  // namespace twister::sim
