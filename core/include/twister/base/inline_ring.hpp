// Fixed-capacity FIFO rings (no heap, no exceptions), the one replacement for
// hand-written `head + count` rings with `% capacity`:
//   InlineRing<T, N>  owns its N slots (a std::array);
//   SpanRing<T>       runs over slots the caller hands in (a std::span sized at start-up,
//                     as core's storage is: see docs/architecture.md).
// push() refuses when full (resource_exhausted, nothing changes); push_overwrite()
// drops the oldest instead. Element i counts from the oldest (0 = front()). Reading or
// popping what is not there is a broken invariant, checked by TWISTER_DEBUG_ASSERT in
// debug builds and free in release. T must be default-constructible and assignable.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <iterator>
#include <span>
#include <type_traits>
#include <utility>

#include "twister/base/assert.hpp"
#include "twister/base/internal/smallest_size.hpp"
#include "twister/base/status.hpp"

namespace twister {
namespace internal {

// Forward iterator over a ring, oldest first.
template <typename Ring, typename T>
class RingIterator {
 public:
  using iterator_category = std::forward_iterator_tag;
  using value_type = std::remove_const_t<T>;
  using difference_type = std::ptrdiff_t;
  using pointer = T*;
  using reference = T&;

  constexpr RingIterator() = default;
  constexpr RingIterator(Ring* ring, std::size_t i) : ring_(ring), i_(i) {}
  constexpr T& operator*() const { return (*ring_)[i_]; }
  constexpr T* operator->() const { return &(*ring_)[i_]; }
  constexpr RingIterator& operator++() {
    ++i_;
    return *this;
  }
  constexpr RingIterator operator++(int) {
    RingIterator old = *this;
    ++i_;
    return old;
  }
  friend constexpr bool operator==(const RingIterator& a, const RingIterator& b) {
    return a.ring_ == b.ring_ && a.i_ == b.i_;
  }

 private:
  Ring* ring_ = nullptr;
  std::size_t i_ = 0;
};

// The ring over any contiguous Storage (std::array<T, N> or std::span<T>).
template <typename T, typename Storage, typename Size>
class RingCore {
 public:
  using value_type = T;
  using size_type = std::size_t;
  using iterator = RingIterator<RingCore, T>;
  using const_iterator = RingIterator<const RingCore, const T>;

  constexpr std::size_t size() const { return std::size_t{size_}; }
  constexpr std::size_t capacity() const { return slots_.size(); }
  constexpr bool empty() const { return size_ == 0; }
  constexpr bool full() const { return size() == capacity(); }

  // Adds at the back. resource_exhausted (nothing changes) when full.
  constexpr Status push(const T& value) {
    if (full()) return StatusCode::resource_exhausted;
    slots_[slot(size())] = value;
    ++size_;
    return ok_status();
  }
  // Adds at the back, dropping the oldest when full; true when one was dropped (with
  // no slots at all, `value` itself is dropped).
  constexpr bool push_overwrite(const T& value) {
    if (capacity() == 0) return true;
    if (!full()) {
      push(value).ignore();
      return false;
    }
    slots_[head_] = value;
    head_ = static_cast<Size>(slot(1));
    return true;
  }

  constexpr void pop_front() { drop_front(1); }
  // Drops the n oldest (asserted: n <= size()).
  constexpr void drop_front(std::size_t n) {
    TWISTER_DEBUG_ASSERT(n <= size());
    head_ = static_cast<Size>(n == size() ? 0 : slot(n));
    size_ = static_cast<Size>(size() - n);
  }
  // Moves the oldest min(size(), out.size()) elements into `out`, oldest first, and
  // drops them; returns how many.
  constexpr std::size_t pop_front_into(std::span<T> out) {
    const std::size_t n = std::min(out.size(), size());
    for (std::size_t i = 0; i < n; ++i) out[i] = std::move((*this)[i]);
    drop_front(n);
    return n;
  }
  constexpr void clear() {
    head_ = 0;
    size_ = 0;
  }

  // Element i from the oldest.
  constexpr T& operator[](std::size_t i) {
    TWISTER_DEBUG_ASSERT(i < size());
    return slots_[slot(i)];
  }
  constexpr const T& operator[](std::size_t i) const {
    TWISTER_DEBUG_ASSERT(i < size());
    return slots_[slot(i)];
  }
  constexpr T& front() { return (*this)[0]; }
  constexpr const T& front() const { return (*this)[0]; }
  constexpr T& back() { return (*this)[size() - 1]; }
  constexpr const T& back() const { return (*this)[size() - 1]; }

  constexpr iterator begin() { return {this, 0}; }
  constexpr iterator end() { return {this, size()}; }
  constexpr const_iterator begin() const { return {this, 0}; }
  constexpr const_iterator end() const { return {this, size()}; }

 protected:
  constexpr RingCore() = default;
  constexpr explicit RingCore(Storage slots) : slots_(slots) {}

 private:
  // Slot of element i (i <= capacity()): one compare instead of a modulo.
  constexpr std::size_t slot(std::size_t i) const {
    const std::size_t j = std::size_t{head_} + i;
    return j >= capacity() ? j - capacity() : j;
  }

  Storage slots_{};
  Size head_ = 0;  // slot of the oldest element
  Size size_ = 0;
};

}  // namespace internal

template <typename T, std::size_t N>
class InlineRing : public internal::RingCore<T, std::array<T, N>, internal::SmallestSize<N>> {
  static_assert(N > 0, "an InlineRing holds at least one element");

 public:
  constexpr InlineRing() = default;
  static constexpr std::size_t max_size() { return N; }
};

// A ring over the caller's slots, which must outlive it. A copy shares the slots with
// the original: keep one of them in use.
template <typename T>
class SpanRing : public internal::RingCore<T, std::span<T>, std::size_t> {
 public:
  constexpr SpanRing() = default;  // no slots: push() refuses, push_overwrite() drops
  constexpr explicit SpanRing(std::span<T> slots)
      : internal::RingCore<T, std::span<T>, std::size_t>(slots) {}
};

}  // namespace twister
