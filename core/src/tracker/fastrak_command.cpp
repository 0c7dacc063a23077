// Fastrak command encoder/decoder and the builders of what the session sends.
#include "twister/tracker/fastrak_command.hpp"

#include <cmath>
#include <cstring>

namespace twister::tracker {
namespace {

constexpr ModeCommand kModes[] = {
    ModeCommand::poll,
    ModeCommand::continuous,
    ModeCommand::polled,
    ModeCommand::ascii,
    ModeCommand::binary,
    ModeCommand::inches,
    ModeCommand::centimetres,
    ModeCommand::status,
    ModeCommand::factory_defaults,
    ModeCommand::built_in_test,
    ModeCommand::metal_compensation_on,
    ModeCommand::metal_compensation_off,
    ModeCommand::reinitialise,
    ModeCommand::save,
    ModeCommand::suspend,
    ModeCommand::resume,
};

constexpr ParameterCommand kParameters[] = {
    ParameterCommand::output_list,     ParameterCommand::station_state,
    ParameterCommand::hemisphere,      ParameterCommand::alignment,
    ParameterCommand::reset_alignment, ParameterCommand::boresight,
    ParameterCommand::unboresight,     ParameterCommand::boresight_reference,
    ParameterCommand::tip_offset,      ParameterCommand::stylus_mode,
    ParameterCommand::increment,       ParameterCommand::position_filter,
    ParameterCommand::attitude_filter, ParameterCommand::envelope,
    ParameterCommand::user_id,         ParameterCommand::serial_port,
};

// A value 0..1 with three decimals ("0.200", "1.000").
bool append_unit3(Parameters& p, float v) {
  const float c = v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v);
  const auto m = static_cast<unsigned>(std::lround(static_cast<double>(c) * 1000.0));
  const char digits[5] = {static_cast<char>('0' + m / 1000), '.',
                          static_cast<char>('0' + (m / 100) % 10),
                          static_cast<char>('0' + (m / 10) % 10), static_cast<char>('0' + m % 10)};
  return p.append(std::string_view(digits, sizeof digits));
}

Parameters with_station(ParameterCommand command, int station) {
  Parameters p;
  p.command = command;
  const bool ok = p.append_int(station);
  TWISTER_ASSERT(ok);
  return p;
}

}  // namespace

std::size_t Parameters::field_count() const {
  std::size_t n = 1;
  for (const char c : fields()) n += c == ',' ? 1 : 0;
  return n;
}

std::string_view Parameters::field(std::size_t i) const {
  std::string_view rest = fields();
  for (; i > 0; --i) {
    const std::size_t comma = rest.find(',');
    if (comma == std::string_view::npos) return {};
    rest.remove_prefix(comma + 1);
  }
  return rest.substr(0, rest.find(','));
}

bool Parameters::append(std::string_view more) {
  if (more.size() > text.size() - length) return false;
  for (const char c : more) {
    if (c == kCr || c == kLf) return false;
    text[length++] = c;
  }
  return true;
}

bool Parameters::append_int(int value) {
  char tmp[12];
  std::size_t n = 0;
  const bool neg = value < 0;
  unsigned u = neg ? 0u - static_cast<unsigned>(value) : static_cast<unsigned>(value);
  do {
    tmp[n++] = static_cast<char>('0' + u % 10);
    u /= 10;
  } while (u != 0);
  if (neg) tmp[n++] = '-';
  char out[12];
  for (std::size_t i = 0; i < n; ++i) out[i] = tmp[n - 1 - i];
  return append(std::string_view(out, n));
}

std::optional<ModeCommand> mode_command(char byte) {
  for (const ModeCommand m : kModes) {
    if (static_cast<char>(m) == byte) return m;
  }
  return std::nullopt;
}

std::optional<ParameterCommand> parameter_command(char byte) {
  for (const ParameterCommand p : kParameters) {
    if (static_cast<char>(p) == byte) return p;
  }
  return std::nullopt;
}

char letter(const FastrakCommand& command) {
  if (const Mode* m = std::get_if<Mode>(&command)) return static_cast<char>(m->command);
  return static_cast<char>(std::get<Parameters>(command).command);
}

Parameters station_state_command(int station, bool enabled) {
  Parameters p = with_station(ParameterCommand::station_state, station);
  const bool ok = p.append(enabled ? ",1" : ",0");
  TWISTER_ASSERT(ok);
  return p;
}

Parameters output_list_command(int station, const OutputList& list) {
  Parameters p = with_station(ParameterCommand::output_list, station);
  bool ok = true;
  for (std::size_t i = 0; i < list.count && i < kMaxItems; ++i) {
    ok = ok && p.append(",") && p.append_int(static_cast<int>(list.items[i]));
  }
  TWISTER_ASSERT(ok);  // 32 items of at most 2 digits fit
  return p;
}

Parameters hemisphere_command(int station, const std::array<int, 3>& toward) {
  Parameters p = with_station(ParameterCommand::hemisphere, station);
  bool ok = true;
  for (const int c : toward) ok = ok && p.append(",") && p.append_int(c);
  TWISTER_ASSERT(ok);
  return p;
}

Parameters stylus_mode_command(int station, int function) {
  Parameters p = with_station(ParameterCommand::stylus_mode, station);
  const bool ok = p.append(",") && p.append_int(function);
  TWISTER_ASSERT(ok);
  return p;
}

std::optional<Parameters> filter_command(ParameterCommand which, const FilterSetting& setting) {
  if (setting.mode == FilterSetting::Mode::leave) return std::nullopt;
  Parameters p;
  p.command = which;
  if (setting.mode == FilterSetting::Mode::off) {
    const bool ok = p.append(",1");  // FLOW = 1.0 disables the filter
    TWISTER_ASSERT(ok);
    return p;
  }
  const bool ok = append_unit3(p, setting.f) && p.append(",") && append_unit3(p, setting.flow) &&
                  p.append(",") && append_unit3(p, setting.fhigh) && p.append(",") &&
                  append_unit3(p, setting.factor);
  TWISTER_ASSERT(ok);
  return p;
}

Result<std::size_t> encode(const FastrakCommand& command, std::span<char> out) {
  if (const Mode* m = std::get_if<Mode>(&command)) {
    if (out.empty()) return StatusCode::resource_exhausted;
    out[0] = static_cast<char>(m->command);
    return std::size_t{1};
  }
  const Parameters& p = std::get<Parameters>(command);
  const std::size_t n = std::size_t{2} + p.length;
  if (out.size() < n) return StatusCode::resource_exhausted;
  out[0] = static_cast<char>(p.command);
  if (p.length > 0) std::memcpy(out.data() + 1, p.text.data(), p.length);
  out[n - 1] = kCr;
  return n;
}

Result<FastrakCommand> decode(std::span<const char> bytes) {
  if (bytes.empty()) return StatusCode::invalid_argument;
  if (const auto m = mode_command(bytes[0])) {
    if (bytes.size() != 1) return StatusCode::invalid_argument;
    return FastrakCommand{Mode{*m}};
  }
  const auto which = parameter_command(bytes[0]);
  if (!which || bytes.back() != kCr) return StatusCode::invalid_argument;
  const std::string_view fields(bytes.data() + 1, bytes.size() - 2);
  if (fields.find(kCr) != std::string_view::npos || fields.find(kLf) != std::string_view::npos) {
    return StatusCode::invalid_argument;
  }
  if (fields.size() > kMaxCommandText) return StatusCode::resource_exhausted;
  Parameters p;
  p.command = *which;
  const bool ok = p.append(fields);
  TWISTER_ASSERT(ok);
  return FastrakCommand{p};
}

}  // namespace twister::tracker
