// Result<T>: a value or a non-ok Status. Shaped like C++23 std::expected<T, Status>
// so it can be swapped later; allocation-free and usable without exceptions.
#pragma once

#include <memory>
#include <new>
#include <type_traits>
#include <utility>

#include "twister/base/assert.hpp"
#include "twister/base/status.hpp"

namespace twister {

template <typename T>
class [[nodiscard]] Result {
 public:
  Result(const T& value) : has_value_(true) { ::new (&value_) T(value); }        // NOLINT
  Result(T&& value) : has_value_(true) { ::new (&value_) T(std::move(value)); }  // NOLINT
  Result(Status status) : status_(status) {                                      // NOLINT
    TWISTER_ASSERT(!status.ok());
  }
  Result(StatusCode code) : Result(Status(code)) {}  // NOLINT

  Result(const Result& other) : status_(other.status_), has_value_(other.has_value_) {
    if (has_value_) ::new (&value_) T(other.value_);
  }
  Result(Result&& other) noexcept : status_(other.status_), has_value_(other.has_value_) {
    if (has_value_) ::new (&value_) T(std::move(other.value_));
  }
  Result& operator=(const Result& other) {
    if (this != &other) {
      destroy();
      status_ = other.status_;
      has_value_ = other.has_value_;
      if (has_value_) ::new (&value_) T(other.value_);
    }
    return *this;
  }
  Result& operator=(Result&& other) noexcept {
    if (this != &other) {
      destroy();
      status_ = other.status_;
      has_value_ = other.has_value_;
      if (has_value_) ::new (&value_) T(std::move(other.value_));
    }
    return *this;
  }
  ~Result() { destroy(); }

  bool ok() const { return has_value_; }
  explicit operator bool() const { return has_value_; }
  Status status() const { return status_; }

  T& value() & {
    TWISTER_ASSERT(has_value_);
    return value_;
  }
  const T& value() const& {
    TWISTER_ASSERT(has_value_);
    return value_;
  }
  T&& value() && {
    TWISTER_ASSERT(has_value_);
    return std::move(value_);
  }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

  T value_or(T fallback) const { return has_value_ ? value_ : fallback; }

 private:
  void destroy() {
    if (has_value_) {
      value_.~T();
      has_value_ = false;
    }
  }

  Status status_;  // ok iff has_value_
  bool has_value_ = false;
  union {
    T value_;
  };
};

namespace internal {
template <typename T>
Status to_status(const Result<T>& r) {
  return r.status();
}
}  // namespace internal

}  // namespace twister

#define TWISTER_CONCAT_INNER_(a, b) a##b
#define TWISTER_CONCAT_(a, b) TWISTER_CONCAT_INNER_(a, b)

// TWISTER_TRY_ASSIGN(lhs, expr): evaluates a Result; on error returns its Status,
// otherwise assigns the value to lhs (which may be a declaration: `auto x`, so it
// cannot be parenthesised).
// NOLINTBEGIN(bugprone-macro-parentheses)
#define TWISTER_TRY_ASSIGN(lhs, expr) \
  TWISTER_TRY_ASSIGN_IMPL_(TWISTER_CONCAT_(twister_result_, __LINE__), lhs, expr)
#define TWISTER_TRY_ASSIGN_IMPL_(tmp, lhs, expr) \
  auto tmp = (expr);                             \
  if (!tmp.ok()) return tmp.status();            \
  lhs = std::move(tmp).value()
// NOLINTEND(bugprone-macro-parentheses)
