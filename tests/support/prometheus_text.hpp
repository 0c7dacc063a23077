// Reading a Prometheus text exposition in tests (the station's metrics file): the
// value of one sample line.
#pragma once

#include <cmath>
#include <cstdlib>
#include <string>

namespace twister::test {

// The value of the sample line "NAME VALUE" (NAME may carry labels) after the first
// line, or NaN when there is none (so an expected value never matches).
inline double prometheus_sample(const std::string& text, const std::string& name) {
  const std::string line = "\n" + name + " ";
  const std::size_t at = text.find(line);
  if (at == std::string::npos) return std::nan("");
  return std::strtod(text.c_str() + at + line.size(), nullptr);
}

}  // namespace twister::test
