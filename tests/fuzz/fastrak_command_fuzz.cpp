// libFuzzer harness for the Fastrak command decoder (fastrak_command.hpp). The input is
// one candidate command. Properties: no crash or out-of-bounds access; a decoded
// command encodes back to exactly the input bytes; its letter is the first byte; its
// fields, joined with commas, are its text; a refused input is not one whole command
// (empty, unknown first byte, bytes after a mode byte or after the CR, no CR, an LF, or
// too long).
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>
#include <string_view>

#include "twister/tracker/fastrak_command.hpp"

namespace {

using namespace twister::tracker;

void check(bool ok) {
  if (!ok) std::abort();
}

bool one_command(std::string_view in) {
  if (in.empty()) return false;
  if (mode_command(in[0])) return in.size() == 1;
  if (!parameter_command(in[0]) || in.back() != kCr) return false;
  const std::string_view text = in.substr(1, in.size() - 2);
  return text.size() <= kMaxCommandText && text.find(kCr) == std::string_view::npos &&
         text.find(kLf) == std::string_view::npos;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view in(reinterpret_cast<const char*>(data), size);
  const auto command = decode(std::span<const char>(in.data(), in.size()));
  check(command.ok() == one_command(in));
  if (!command.ok()) return 0;
  std::array<char, kMaxCommandBytes> out{};
  const auto n = encode(*command, out);
  check(n.ok() && std::string_view(out.data(), *n) == in);
  check(letter(*command) == in[0]);
  if (const auto* p = std::get_if<Parameters>(&*command)) {
    std::string joined;
    for (std::size_t i = 0; i < p->field_count(); ++i) {
      if (i > 0) joined += ',';
      joined += p->field(i);
    }
    check(joined == p->fields());
  }
  return 0;
}
