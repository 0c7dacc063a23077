// A listening transport over in-memory wires for the station link's tests: the
// admitted peer's wire, a newcomer's wire (ports::LinkNewcomers) and up to
// kSlots spectators' wires (ports::LinkSpectators). Each wire's a_to_b direction
// carries the station's bytes; `capacity` on a wire bounds the bytes in flight (a
// display that stops reading fills it).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "fakes/memory_wire.hpp"
#include "twister/ports/link_newcomers.hpp"
#include "twister/ports/link_port.hpp"
#include "twister/ports/link_spectators.hpp"

namespace twister::test {

class FakeListener final : public ports::LinkPort,
                           public ports::LinkNewcomers,
                           public ports::LinkSpectators {
 public:
  static constexpr std::size_t kSlots = 8;

  void connect(MemoryWire& wire) {
    newcomer_ = &wire;
    ++id_;
  }
  MemoryWire* peer() const { return peer_; }
  MemoryWire* spectator(std::size_t slot) const { return spectators_[slot]; }

 private:
  static Result<std::size_t> put(MemoryWire* w, std::span<const std::byte> src) {
    if (w == nullptr || !w->up) return StatusCode::unavailable;
    std::size_t n = 0;
    while (n < src.size() && w->a_to_b.size() < w->capacity && w->a_to_b.push(src[n])) ++n;
    return n;
  }
  static Result<std::size_t> get(MemoryWire* w, std::span<std::byte> dest) {
    if (w == nullptr || !w->up) return StatusCode::unavailable;
    std::size_t n = 0;
    while (n < dest.size() && !w->b_to_a.empty()) dest[n++] = w->b_to_a.pop();
    return n;
  }
  Result<std::size_t> do_send(std::span<const std::byte> src) override { return put(peer_, src); }
  Result<std::size_t> do_receive(std::span<std::byte> dest) override { return get(peer_, dest); }
  std::uint64_t do_newcomer_id() override { return id_; }
  Result<std::size_t> do_send_newcomer(std::span<const std::byte> src) override {
    return put(newcomer_, src);
  }
  Result<std::size_t> do_receive_newcomer(std::span<std::byte> dest) override {
    return get(newcomer_, dest);
  }
  void do_admit_newcomer() override {
    peer_ = newcomer_;  // the old peer's wire keeps what was sent before (its bye)
    newcomer_ = nullptr;
  }
  void do_refuse_newcomer() override {
    if (newcomer_ != nullptr) newcomer_->up = false;
    newcomer_ = nullptr;
  }
  std::size_t do_spectator_capacity() const override { return kSlots; }
  Status do_admit_spectator(std::size_t slot) override {
    if (slot >= kSlots) return StatusCode::out_of_range;
    if (newcomer_ == nullptr) return StatusCode::unavailable;
    spectators_[slot] = newcomer_;
    newcomer_ = nullptr;
    return ok_status();
  }
  Result<std::size_t> do_send_spectator(std::size_t slot, std::span<const std::byte> src) override {
    return slot < kSlots ? put(spectators_[slot], src) : StatusCode::unavailable;
  }
  Result<std::size_t> do_receive_spectator(std::size_t slot, std::span<std::byte> dest) override {
    return slot < kSlots ? get(spectators_[slot], dest) : StatusCode::unavailable;
  }
  void do_close_spectator(std::size_t slot) override {
    if (slot >= kSlots || spectators_[slot] == nullptr) return;
    spectators_[slot]->up = false;
    spectators_[slot] = nullptr;
  }

  MemoryWire* peer_ = nullptr;
  MemoryWire* newcomer_ = nullptr;
  std::array<MemoryWire*, kSlots> spectators_{};
  std::uint64_t id_ = 0;
};

}  // namespace twister::test
