// Status: the error channel of core/ (no exceptions). One short list of codes;
// every public function documents which of them it returns and what they mean.
#pragma once

#include <cstdint>

namespace twister {

enum class StatusCode : std::uint8_t {
  ok = 0,
  unavailable,          // no data yet / device not present; try again later
  invalid_argument,     // the caller passed something malformed
  out_of_range,         // a value outside its documented range
  resource_exhausted,   // a fixed capacity is full (the operation did nothing)
  data_loss,            // bytes or records were corrupt and were dropped
  failed_precondition,  // the object is not in a state that allows the call
  io_error,             // the underlying device or file failed or was disconnected
  timeout,              // a deadline passed without the expected answer
  not_supported,        // the backend or build cannot do this
};

// Name of a code, for logs and messages ("ok", "data_loss", ...).
constexpr const char* status_code_name(StatusCode code) {
  switch (code) {
    case StatusCode::ok:
      return "ok";
    case StatusCode::unavailable:
      return "unavailable";
    case StatusCode::invalid_argument:
      return "invalid_argument";
    case StatusCode::out_of_range:
      return "out_of_range";
    case StatusCode::resource_exhausted:
      return "resource_exhausted";
    case StatusCode::data_loss:
      return "data_loss";
    case StatusCode::failed_precondition:
      return "failed_precondition";
    case StatusCode::io_error:
      return "io_error";
    case StatusCode::timeout:
      return "timeout";
    case StatusCode::not_supported:
      return "not_supported";
  }
  return "unknown";
}

class [[nodiscard]] Status {
 public:
  constexpr Status() = default;
  constexpr Status(StatusCode code) : code_(code) {}  // NOLINT: implicit by design

  constexpr bool ok() const { return code_ == StatusCode::ok; }
  constexpr StatusCode code() const { return code_; }
  constexpr const char* name() const { return status_code_name(code_); }

  // Explicitly drops a status the caller has decided not to act on.
  constexpr void ignore() const {}

  friend constexpr bool operator==(Status a, Status b) { return a.code_ == b.code_; }

 private:
  StatusCode code_ = StatusCode::ok;
};

constexpr Status ok_status() { return Status(); }

}  // namespace twister

// Early return of a non-ok Status (or the status of a non-ok Result).
#define TWISTER_TRY(expr)                                                \
  do {                                                                   \
    if (auto twister_try_status_ = ::twister::internal::to_status(expr); \
        !twister_try_status_.ok()) {                                     \
      return twister_try_status_;                                        \
    }                                                                    \
  } while (0)

namespace twister::internal {
constexpr Status to_status(Status s) { return s; }
}  // namespace twister::internal
