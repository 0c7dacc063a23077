// Expected<T>: the one error channel of start-up code in the programs and their
// platform helpers (config, backends, files, link endpoints): a value, or an Error
// with a status code and a message for people. Shaped like C++23
// std::expected<T, Error> (has_value, value, error, *, ->) so it can be swapped.
// Start-up code only: it allocates (the message). Core uses Status / Result<T>.
#pragma once

#include <string>
#include <utility>
#include <variant>

#include "twister/base/status.hpp"

namespace twister::hal {

struct Error {
  Status status = StatusCode::io_error;  // what kind of failure (never ok)
  std::string message;                   // what failed and why, for the log
};

template <typename T>
class [[nodiscard]] Expected {
 public:
  Expected(T value) : state_(std::move(value)) {}      // NOLINT: implicit by design
  Expected(Error error) : state_(std::move(error)) {}  // NOLINT

  bool has_value() const { return state_.index() == 0; }
  explicit operator bool() const { return has_value(); }
  T& value() { return std::get<0>(state_); }
  const T& value() const { return std::get<0>(state_); }
  const Error& error() const { return std::get<1>(state_); }
  T& operator*() { return value(); }
  const T& operator*() const { return value(); }
  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }

 private:
  std::variant<T, Error> state_;
};

// Success without a value, or an Error.
template <>
class [[nodiscard]] Expected<void> {
 public:
  Expected() = default;
  Expected(Error error) : error_(std::move(error)), failed_(true) {}  // NOLINT

  bool has_value() const { return !failed_; }
  explicit operator bool() const { return has_value(); }
  const Error& error() const { return error_; }

 private:
  Error error_{};
  bool failed_ = false;
};

inline Error make_error(StatusCode code, std::string message) {
  return Error{Status(code), std::move(message)};
}

}  // namespace twister::hal
