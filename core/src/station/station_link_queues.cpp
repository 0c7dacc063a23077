// FrameQueues: urgent and bulk frames, flushed whole, urgent first.
#include "twister/station/station_link_queues.hpp"

#include <algorithm>
#include <cstring>

namespace twister::station {
namespace {

// Length of the frame at the start of `bytes` (up to and including its 0x00), or
// bytes.size() when it is not complete.
std::size_t frame_length(std::span<const std::byte> bytes) {
  const auto end = std::find(bytes.begin(), bytes.end(), std::byte{0});
  return end == bytes.end() ? bytes.size() : static_cast<std::size_t>(end - bytes.begin()) + 1;
}

}  // namespace

bool FrameQueues::append(const Result<std::size_t>& written, std::size_t& size) {
  if (!written.ok()) return false;
  size += *written;
  return true;
}

void FrameQueues::bulk_rewind(std::size_t mark) {
  if (mark < bulk_size_) bulk_size_ = mark;
}

bool FrameQueues::bulk_bytes(std::span<const std::byte> frames) {
  if (frames.size() > bulk_room()) return false;
  std::memcpy(bulk_.data() + bulk_size_, frames.data(), frames.size());
  bulk_size_ += frames.size();
  return true;
}

void FrameQueues::clear() {
  bulk_size_ = 0;
  urgent_size_ = 0;
  sending_ = Queue::none;
}

void FrameQueues::interrupt_with(const link::Bye& bye) {
  std::array<std::byte, 64> frame{};
  frame[0] = std::byte{0};
  if (const auto n = link::encode_frame(bye, std::span<std::byte>(frame).subspan(1)); n.ok()) {
    (void)port_.send(std::span<const std::byte>(frame).first(*n + 1));
  }
  clear();
}

void FrameQueues::flush() {
  // Frames leave whole; between two frames the urgent queue goes first.
  for (int round = 0; round < 64; ++round) {
    if (sending_ == Queue::none) {
      if (urgent_size_ > 0) {
        sending_ = Queue::urgent;
      } else if (bulk_size_ > 0) {
        sending_ = Queue::bulk;
      } else {
        return;
      }
    }
    const bool urgent = sending_ == Queue::urgent;
    std::byte* data = urgent ? urgent_.data() : bulk_.data();
    std::size_t& size = urgent ? urgent_size_ : bulk_size_;
    // Bulk frames go out together unless urgent ones wait; urgent ones always.
    const std::size_t take =
        urgent || urgent_size_ == 0 ? size : frame_length(std::span<const std::byte>(data, size));
    const Result<std::size_t> n = port_.send(std::span<const std::byte>(data, take));
    if (!n.ok()) {
      ++send_errors_;
      return;
    }
    if (*n == 0) return;
    const bool at_boundary = data[*n - 1] == std::byte{0};
    std::memmove(data, data + *n, size - *n);
    size -= *n;
    if (at_boundary) sending_ = Queue::none;
    if (*n < take) return;  // the port is full
  }
}

}  // namespace twister::station
