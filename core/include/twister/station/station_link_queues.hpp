// FrameQueues: the station link's outgoing byte stream. Two queues of encoded
// frames: urgent (hands, stroke, object, status, handshake; fixed 8 KiB) and bulk
// (mesh frames; caller storage sized at start-up). flush() hands them to the port
// as it accepts bytes, frames whole, the urgent queue first at every frame boundary,
// so on a slow line the hands keep their rate while a commit streams behind them.
// A bulk mark/rewind makes a commit all or nothing. No heap. Not thread-safe.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "twister/link/link_codec.hpp"
#include "twister/ports/link_port.hpp"

namespace twister::station {

class FrameQueues {
 public:
  static constexpr std::size_t kUrgentBytes = 8192;

  FrameQueues(ports::LinkPort& port, std::span<std::byte> bulk) : port_(port), bulk_(bulk) {}

  // Encodes `m` at the end of the urgent / bulk queue; false when it does not fit
  // (nothing queued).
  template <link::LinkBody M>
  bool urgent(const M& m) {
    return append(link::encode_frame(m, std::span<std::byte>(urgent_).subspan(urgent_size_)),
                  urgent_size_);
  }
  template <link::LinkBody M>
  bool bulk(const M& m) {
    return append(link::encode_frame(m, bulk_.subspan(bulk_size_)), bulk_size_);
  }
  // The bulk queue's end now, and a return to it (drops what was queued since).
  std::size_t bulk_mark() const { return bulk_size_; }
  void bulk_rewind(std::size_t mark);
  // The bytes queued since `mark` (valid until the next flush or bulk call).
  std::span<const std::byte> bulk_since(std::size_t mark) const {
    return std::span<const std::byte>(bulk_).subspan(mark, bulk_size_ - mark);
  }
  // Appends frames already encoded (a staged commit), all or nothing.
  bool bulk_bytes(std::span<const std::byte> frames);
  // Gives the bulk queue its storage (a spectator slot's, once at start); drops
  // everything queued.
  void set_bulk(std::span<std::byte> bulk) {
    bulk_ = bulk;
    clear();
  }
  std::size_t bulk_room() const { return bulk_.size() - bulk_size_; }
  std::size_t bulk_capacity() const { return bulk_.size(); }

  // Hands queued frames to the port, as many as it accepts now.
  void flush();
  // Drops everything queued (a torn frame is harmless: the next peer resyncs at 0x00).
  void clear();
  // Ends any frame the peer has half received (0x00), sends `bye` straight to the
  // port and drops the queues: the display is told why it goes.
  void interrupt_with(const link::Bye& bye);

  std::size_t pending_bytes() const { return bulk_size_ + urgent_size_; }
  std::size_t bulk_pending() const { return bulk_size_; }
  std::uint64_t send_errors() const { return send_errors_; }

 private:
  enum class Queue : std::uint8_t { none, urgent, bulk };
  static bool append(const Result<std::size_t>& written, std::size_t& size);

  ports::LinkPort& port_;
  std::span<std::byte> bulk_;
  std::size_t bulk_size_ = 0;
  std::array<std::byte, kUrgentBytes> urgent_{};
  std::size_t urgent_size_ = 0;
  Queue sending_ = Queue::none;  // the queue whose frame is partly handed to the port
  std::uint64_t send_errors_ = 0;
};

}  // namespace twister::station
