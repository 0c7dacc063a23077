// TWISTER_ASSERT: programmer errors and broken invariants only. Field conditions
// (noise, unplugged receivers, full queues) are a Status, never an assert.
// TWISTER_DEBUG_ASSERT: the same, checked in debug builds only (NDEBUG unset) and
// compiled to nothing in release: bounds checks on hot paths (InlineVector,
// InlineRing). The condition is not evaluated in release, so it must have no effect.
#pragma once

namespace twister::internal {
// Defined in core/src/base/assert.cpp: stops the program (no I/O in core).
[[noreturn]] void assert_failed(const char* expr, const char* file, int line);
}  // namespace twister::internal

#define TWISTER_ASSERT(cond)                                                    \
  do {                                                                          \
    if (!(cond)) ::twister::internal::assert_failed(#cond, __FILE__, __LINE__); \
  } while (0)

#ifdef NDEBUG
#define TWISTER_DEBUG_ASSERT(cond) \
  do {                             \
    (void)sizeof(cond);            \
  } while (0)
#else
#define TWISTER_DEBUG_ASSERT(cond) TWISTER_ASSERT(cond)
#endif

namespace twister::internal {
// True where TWISTER_DEBUG_ASSERT checks (tests ask which build they run in).
#ifdef NDEBUG
inline constexpr bool kDebugChecks = false;
#else
inline constexpr bool kDebugChecks = true;
#endif
}  // namespace twister::internal
