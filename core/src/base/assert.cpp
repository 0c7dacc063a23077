#include "twister/base/assert.hpp"

namespace twister::internal {

// Kept in a variable so a debugger or a core dump shows what failed.
volatile const char* g_last_assert_expr = nullptr;
volatile const char* g_last_assert_file = nullptr;
volatile int g_last_assert_line = 0;

void assert_failed(const char* expr, const char* file, int line) {
  g_last_assert_expr = expr;
  g_last_assert_file = file;
  g_last_assert_line = line;
  __builtin_trap();
}

}  // namespace twister::internal
