// InlineVector<T, N>: a vector of at most N elements stored inline (no heap, no
// exceptions), the one replacement for hand-written `std::array + count` pairs.
// Adding to a full vector does nothing and returns resource_exhausted; indexing,
// front/back and pop_back on too few elements are broken invariants, checked by
// TWISTER_DEBUG_ASSERT in debug builds and free in release.
//
// T must be default-constructible and copy- or move-assignable: the N slots always
// exist (a std::array), slots past size() hold values that are not part of the vector.
// Everything is constexpr, so small vectors can be built at compile time.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <initializer_list>
#include <span>
#include <utility>

#include "twister/base/assert.hpp"
#include "twister/base/internal/smallest_size.hpp"
#include "twister/base/status.hpp"

namespace twister {

template <typename T, std::size_t N>
class InlineVector {
  static_assert(N > 0, "an InlineVector holds at least one element");

 public:
  using value_type = T;
  using size_type = std::size_t;
  using difference_type = std::ptrdiff_t;
  using reference = T&;
  using const_reference = const T&;
  using pointer = T*;
  using const_pointer = const T*;
  using iterator = T*;
  using const_iterator = const T*;

  constexpr InlineVector() = default;
  // The first N values (asserted: all of them fit).
  constexpr InlineVector(std::initializer_list<T> values) {
    TWISTER_ASSERT(values.size() <= N);
    for (const T& v : values) items_[size_++] = v;
  }

  static constexpr std::size_t capacity() { return N; }
  static constexpr std::size_t max_size() { return N; }
  constexpr std::size_t size() const { return std::size_t{size_}; }
  constexpr bool empty() const { return size_ == 0; }
  constexpr bool full() const { return size_ == N; }

  // resource_exhausted (nothing added) when full.
  constexpr Status push_back(const T& value) {
    if (full()) return StatusCode::resource_exhausted;
    items_[size_++] = value;
    return ok_status();
  }
  constexpr Status push_back(T&& value) {
    if (full()) return StatusCode::resource_exhausted;
    items_[size_++] = std::move(value);
    return ok_status();
  }
  // T{args...} at the end; resource_exhausted (nothing added) when full.
  template <typename... Args>
  constexpr Status emplace_back(Args&&... args) {
    if (full()) return StatusCode::resource_exhausted;
    items_[size_++] = T{std::forward<Args>(args)...};
    return ok_status();
  }
  // Appends as many of `values` as fit; resource_exhausted when not all did.
  constexpr Status append(std::span<const T> values) {
    const std::size_t n = std::min(values.size(), N - size());
    for (std::size_t i = 0; i < n; ++i) items_[size_++] = values[i];
    return n == values.size() ? ok_status() : Status(StatusCode::resource_exhausted);
  }
  // Replaces the contents by `values`; resource_exhausted (the vector then holds the
  // first N) when they do not fit.
  constexpr Status assign(std::span<const T> values) {
    clear();
    return append(values);
  }

  constexpr void pop_back() {
    TWISTER_DEBUG_ASSERT(size_ > 0);
    --size_;
  }
  constexpr void clear() { size_ = 0; }
  // Grows with value-initialised elements or shrinks to n (asserted: n <= N).
  constexpr void resize(std::size_t n) {
    TWISTER_ASSERT(n <= N);
    for (std::size_t i = size(); i < n; ++i) items_[i] = T{};
    size_ = static_cast<Size>(n);
  }

  // Removes the element at `pos`, keeping the order of the others; returns the
  // iterator to the element after it.
  constexpr iterator erase(const_iterator pos) { return erase(pos, pos + 1); }
  constexpr iterator erase(const_iterator first, const_iterator last) {
    TWISTER_DEBUG_ASSERT(begin() <= first && first <= last && last <= end());
    iterator f = begin() + (first - begin());
    iterator l = begin() + (last - begin());
    std::move(l, end(), f);
    size_ = static_cast<Size>(size_ - static_cast<std::size_t>(l - f));
    return f;
  }

  constexpr T& operator[](std::size_t i) {
    TWISTER_DEBUG_ASSERT(i < size_);
    return items_[i];
  }
  constexpr const T& operator[](std::size_t i) const {
    TWISTER_DEBUG_ASSERT(i < size_);
    return items_[i];
  }
  constexpr T& front() { return (*this)[0]; }
  constexpr const T& front() const { return (*this)[0]; }
  constexpr T& back() {
    TWISTER_DEBUG_ASSERT(size_ > 0);
    return items_[size() - 1];
  }
  constexpr const T& back() const {
    TWISTER_DEBUG_ASSERT(size_ > 0);
    return items_[size() - 1];
  }

  constexpr T* data() { return items_.data(); }
  constexpr const T* data() const { return items_.data(); }
  constexpr iterator begin() { return items_.data(); }
  constexpr iterator end() { return items_.data() + size(); }
  constexpr const_iterator begin() const { return items_.data(); }
  constexpr const_iterator end() const { return items_.data() + size(); }

  // The elements as a span. Where a span is expected, the vector itself converts
  // (it is a contiguous range: std::span's range constructor takes it).
  constexpr std::span<T> span() { return {items_.data(), size()}; }
  constexpr std::span<const T> span() const { return {items_.data(), size()}; }

  friend constexpr bool operator==(const InlineVector& a, const InlineVector& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end());
  }

 private:
  using Size = internal::SmallestSize<N>;

  std::array<T, N> items_{};
  Size size_ = 0;
};

// Removes every element for which pred(element) is true (order of the rest kept);
// returns how many were removed. Found by argument-dependent lookup, as std::erase_if.
template <typename T, std::size_t N, typename Pred>
constexpr std::size_t erase_if(InlineVector<T, N>& v, Pred pred) {
  auto* kept_end = std::remove_if(v.begin(), v.end(), pred);
  const auto removed = static_cast<std::size_t>(v.end() - kept_end);
  v.erase(kept_end, v.end());
  return removed;
}

}  // namespace twister
