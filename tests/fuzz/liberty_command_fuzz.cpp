// libFuzzer harness for twister-sim's Liberty / Patriot command lines (issue 22): the
// host's bytes through sim::CommandInput in the Liberty dialect (lines up to CR but `P`,
// docs/liberty-protocol.md §9) and through the whole device model playing a Liberty or
// Patriot (FastrakDevice: the commands executed, replies and records on its line).
// Input: byte 0 chooses the unit (bit 0: Patriot, else Liberty; bit 1: no input buffer;
// bit 2: the default command times, else every command at once); the rest is what the
// host sends, one byte per millisecond of virtual time, then 0.6 s of output (a filter
// command takes 0.5 s).
// Properties: no crash, leak or undefined behaviour; the input buffer never holds more
// than its limit; an error is -5 (a line over 80 bytes) or -99 (not a command) and
// echoes at most 81 bytes; a command heard is one the shared codec encodes (a mode
// letter, or a parameter command whose text fits); the device executes at most one
// command or error per byte it was sent; the dialect takes either case: the same bytes
// with their letters in upper case are heard alike.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "twister/sim/command_input.hpp"
#include "twister/sim/fastrak_device.hpp"
#include "twister/tracker/fastrak_command.hpp"

namespace {

using namespace twister;

void check(bool ok) {
  if (!ok) std::abort();
}

constexpr std::int64_t kByteUs = 1'000;     // one host byte per millisecond
constexpr std::int64_t kDrainUs = 600'000;  // then the unit's output for 0.6 s

// One heard result of CommandInput, checked.
void check_heard(const sim::CommandInput& input, sim::CommandInput::Heard heard,
                 std::size_t limit) {
  check(input.buffered() <= limit);
  switch (heard) {
    case sim::CommandInput::Heard::error:
      check(input.error_code() == -5 || input.error_code() == -99);
      check(input.echo().size() <= 81);
      break;
    case sim::CommandInput::Heard::command: {
      std::array<char, tracker::kMaxCommandBytes> out{};
      check(tracker::encode(input.command(), out).ok());
      break;
    }
    case sim::CommandInput::Heard::nothing:
    case sim::CommandInput::Heard::lost:
    case sim::CommandInput::Heard::who_am_i:
      break;
  }
}

// What CommandInput heard, in order: each result, and a command's bytes as the shared
// codec encodes it.
std::string heard_text(sim::CommandInput::Heard heard, const sim::CommandInput& input) {
  std::string out(1, static_cast<char>('0' + static_cast<int>(heard)));
  if (heard == sim::CommandInput::Heard::command) {
    std::array<char, tracker::kMaxCommandBytes> bytes{};
    const auto n = tracker::encode(input.command(), bytes);
    if (n.ok()) out.append(bytes.data(), *n);
  }
  return out;
}

std::string fuzz_input(std::span<const char> host, std::size_t buffer,
                       const sim::CommandTimes& times) {
  sim::CommandInput input(times, buffer, true);
  const std::size_t limit = buffer < sim::kInputBufferBytes ? buffer : sim::kInputBufferBytes;
  std::string heard;
  auto take = [&](sim::CommandInput::Heard h) {
    check_heard(input, h, limit);
    heard += heard_text(h, input);
  };
  std::int64_t now = 0;
  for (const char byte : host) {
    while (input.buffered_ready(now)) take(input.take_buffered());
    take(input.take(byte, now));
    now += kByteUs;
  }
  for (int i = 0; i < 1000 && input.buffered() > 0; ++i) {
    now = input.ready_at();
    while (input.buffered_ready(now)) take(input.take_buffered());
  }
  return heard;
}

void fuzz_device(std::span<const char> host, sim::DeviceModel model, std::size_t buffer,
                 const sim::CommandTimes& times) {
  sim::FastrakDeviceConfig config;
  config.model = model;
  config.reset_time_us = 1'000;  // listening almost at once (a ^Y in the input: again)
  config.input_buffer_bytes = buffer;
  config.command_time_us = times;
  sim::Scenario scenario;
  scenario.duration_s = 0.0;
  sim::FastrakDevice device(config, scenario, 0);
  std::vector<std::byte> out;
  std::int64_t now = 2'000;
  for (const char byte : host) {
    const std::byte b{static_cast<unsigned char>(byte)};
    device.receive(&b, 1, now);
    device.advance(now, out);
    now += kByteUs;
  }
  for (const std::int64_t end = now + kDrainUs; now < end; now += 50'000) device.advance(now, out);
  const auto& c = device.counters();
  check(c.commands + c.command_errors <= host.size());
  check(c.output.bytes_out >= out.size());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::uint8_t flags = data[0];
  const std::span<const char> host(reinterpret_cast<const char*>(data) + 1, size - 1);
  const sim::DeviceModel model =
      (flags & 1U) != 0 ? sim::DeviceModel::patriot : sim::DeviceModel::liberty;
  const std::size_t buffer = (flags & 2U) != 0 ? 0 : sim::kInputBufferBytes;
  static const sim::CommandTimes kDefault = sim::default_command_times();
  static const sim::CommandTimes kInstant = sim::instant_commands();
  const sim::CommandTimes& times = (flags & 4U) != 0 ? kDefault : kInstant;
  // The dialect takes either case (docs/liberty-protocol.md §9: polhemus_ros_driver sends
  // `f1`, `c`, `h*`, `p`): the same bytes with their letters in upper case are heard alike.
  std::string upper(host.begin(), host.end());
  for (char& c : upper) c = (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c;
  check(fuzz_input(host, buffer, times) ==
        fuzz_input(std::span<const char>(upper.data(), upper.size()), buffer, times));
  fuzz_device(host, model, buffer, times);
  return 0;
}
