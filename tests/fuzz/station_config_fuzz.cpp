// Fuzz target: the station config parser's wrapper (toml++ + schema validation).
// Property: any input gives either a config or errors, never a crash; every error
// carries a line >= 1 and a message, and a valid config names a journal.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "config/station_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto result = twister::station_app::parse_station_config(text, "fuzz.toml");
  for (const auto& e : result.errors) {
    if (e.line == 0 || e.message.empty()) __builtin_trap();
    if (e.to_string().empty()) __builtin_trap();
  }
  if (result.ok() && result.config.station.journal.empty()) __builtin_trap();
  return 0;
}
