// TWISTER_ASSERT: programmer errors and broken invariants only. Field conditions
// (noise, unplugged receivers, full queues) are a Status, never an assert.
#pragma once

namespace twister::internal {
// Defined in core/src/base/assert.cpp: stops the program (no I/O in core).
[[noreturn]] void assert_failed(const char* expr, const char* file, int line);
}  // namespace twister::internal

#define TWISTER_ASSERT(cond)                                                    \
  do {                                                                          \
    if (!(cond)) ::twister::internal::assert_failed(#cond, __FILE__, __LINE__); \
  } while (0)
