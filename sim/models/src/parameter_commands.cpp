// The simulated unit's parameter commands (docs/fastrak.md): output lists, station
// states, hemispheres, stylus mode and envelopes per station; the adaptive filters
// `x` / `v` (parameters, macros, read-back record) and the serial port `o`.
#include "twister/sim/parameter_commands.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "twister/tracker/liberty_wire.hpp"

// GCC 12 reports a false -Wrestrict inside std::string concatenation at -O3
// (GCC bug 105329); nothing here overlaps.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace twister::sim {
namespace {

using tracker::Item;
using tracker::OutputList;
using tracker::ParameterCommand;

// The command's fields ("1,2,,3": "1", "2", "", "3"; none: one empty field).
std::vector<std::string> split(const tracker::Parameters& p) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < p.field_count(); ++i) out.emplace_back(p.field(i));
  return out;
}

// -1 missing, -2 non-numeric, else 0 and the value.
int to_int(const std::string& s, int& v) {
  if (s.empty()) return -1;
  char* end = nullptr;
  const long x = std::strtol(s.c_str(), &end, 10);
  if (end == s.c_str() || *end != '\0') return -2;
  v = static_cast<int>(x);
  return 0;
}

// -1 missing, -2 non-numeric, else 0 and the value ("3", "3.", ".2", "3.0E+00").
int to_double(const std::string& s, double& v) {
  if (s.empty()) return -1;
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0' || !std::isfinite(x)) return -2;
  v = x;
  return 0;
}

bool valid(const FilterParams& p) {
  const bool open = 0.0 < p.f && p.f < 1.0 && 0.0 < p.factor && p.factor < 1.0;
  if (p.flow == 1.0) return open;  // FLOW = 1 disables the filter
  return open && 0.0 < p.flow && p.flow < p.fhigh && p.fhigh < 1.0;
}

// The read-back record: '2', blank, 'x' or 'v', four `bSx.xxx` fields, CR LF (33 bytes).
std::string filter_record(char command, const FilterParams& p) {
  std::string r = std::string("2 ") + command;
  char field[16];
  for (const double v : {p.f, p.flow, p.fhigh, p.factor}) {
    std::snprintf(field, sizeof field, " %6.3f", v);
    r += field;
  }
  return r + "\r\n";
}

bool per_station(ParameterCommand c) {
  switch (c) {
    case ParameterCommand::output_list:
    case ParameterCommand::station_state:
    case ParameterCommand::hemisphere:
    case ParameterCommand::stylus_mode:
    case ParameterCommand::envelope:
    case ParameterCommand::tip_offset:
    case ParameterCommand::boresight:
    case ParameterCommand::unboresight:
    case ParameterCommand::boresight_reference:
      return true;
    default:
      return false;
  }
}

}  // namespace

void ParameterCommands::execute(const tracker::Parameters& command, std::string_view echo,
                                ports::TimestampUs at) {
  const Fields f = split(command);
  const ParameterCommand c = command.command;
  if (c == ParameterCommand::position_filter || c == ParameterCommand::attitude_filter) {
    filter(c, f, echo, at);
    return;
  }
  if (c == ParameterCommand::serial_port) {
    serial_port(f, echo, at);
    return;
  }
  if (!per_station(c)) return;  // accepted, no effect on the model (A, R, I, X)
  int station = 0;
  if (const int rc = to_int(f[0], station); rc != 0) {
    replies_.error(echo, rc, at);
    return;
  }
  if (station < 1 || station > 4) {
    replies_.error(echo, -3, at);
    return;
  }
  switch (c) {
    case ParameterCommand::output_list:
      output_list(station, f, echo, at);
      return;
    case ParameterCommand::station_state:
      station_state(station, f, echo, at);
      return;
    case ParameterCommand::hemisphere:
      hemisphere(station, f, echo, at);
      return;
    case ParameterCommand::envelope:
      envelope(station, f, echo, at);
      return;
    case ParameterCommand::tip_offset:
    case ParameterCommand::boresight_reference:
      station_vector(c, station, f, echo, at);
      return;
    case ParameterCommand::boresight:
      ++settings_.boresight_requests[static_cast<std::size_t>(station - 1)];
      settings_.boresight_on[static_cast<std::size_t>(station - 1)] = true;
      return;
    case ParameterCommand::unboresight:
      settings_.boresight_on[static_cast<std::size_t>(station - 1)] = false;
      return;
    default:
      stylus_mode(f, echo, at);
      return;
  }
}

void ParameterCommands::stylus_mode(const Fields& f, std::string_view echo, ports::TimestampUs at) {
  int mode = 0;  // 0 or 1
  if (f.size() < 2 || to_int(f[1], mode) != 0 || (mode != 0 && mode != 1)) {
    replies_.error(echo, -3, at);
    return;
  }
  settings_.stylus_mode = mode;
}

void ParameterCommands::output_list(int station, const Fields& f, std::string_view echo,
                                    ports::TimestampUs at) {
  auto& st = settings_.protocol.stations[static_cast<std::size_t>(station - 1)];
  if (f.size() == 1) {
    std::string r = "2" + std::to_string(station) + "O";
    char item[8];
    tracker::LibertyOutputList codes;
    if (liberty_codes_ && !tracker::to_liberty_list(st.list, codes).ok()) codes = {};
    const std::size_t n = liberty_codes_ ? codes.count : st.list.count;
    for (std::size_t i = 0; i < n; ++i) {
      const int code =
          liberty_codes_ ? static_cast<int>(codes.items[i]) : static_cast<int>(st.list.items[i]);
      std::snprintf(item, sizeof item, "%2d", code);
      r += item;
    }
    replies_.reply(r + "\r\n", at);
    return;
  }
  OutputList list;
  if (!read_list(f, echo, at, list)) return;
  if (tracker::record_length(list, settings_.protocol.format) > tracker::kMaxRecordBytes) {
    replies_.error(echo, -5, at);
    return;
  }
  st.list = list;
}

bool ParameterCommands::read_list(const Fields& f, std::string_view echo, ports::TimestampUs at,
                                  OutputList& list) {
  tracker::LibertyOutputList codes;
  for (std::size_t i = 1; i < f.size(); ++i) {
    int code = 0;
    if (const int rc = to_int(f[i], code); rc != 0) {
      replies_.error(echo, rc, at);
      return false;
    }
    const bool known =
        code >= 0 && code <= 255 &&
        (liberty_codes_ ? tracker::is_supported_liberty_item(static_cast<std::uint8_t>(code))
                        : tracker::is_supported_item(static_cast<std::uint8_t>(code)));
    const std::size_t count = liberty_codes_ ? codes.count : list.count;
    if (!known || count >= tracker::kMaxItems) {
      replies_.error(echo, -3, at);
      return false;
    }
    if (liberty_codes_) {
      codes.items[codes.count++] = static_cast<tracker::LibertyItem>(code);
    } else {
      list.items[list.count++] = static_cast<Item>(code);
    }
  }
  // A Liberty item the model cannot send (timestamp, frame count, distortion): refused.
  if (liberty_codes_ && !tracker::to_fastrak_list(codes, list).ok()) {
    replies_.error(echo, -3, at);
    return false;
  }
  return true;
}

void ParameterCommands::station_state(int station, const Fields& f, std::string_view echo,
                                      ports::TimestampUs at) {
  if (f.size() == 1) {
    std::string r = "2" + std::to_string(station) + "l";
    for (const auto& s : settings_.protocol.stations) r += s.enabled ? '1' : '0';
    replies_.reply(r + "\r\n", at);
    return;
  }
  int state = 0;
  if (const int rc = to_int(f[1], state); rc != 0) {
    replies_.error(echo, rc, at);
    return;
  }
  settings_.protocol.stations[static_cast<std::size_t>(station - 1)].enabled = state != 0;
}

void ParameterCommands::hemisphere(int station, const Fields& f, std::string_view echo,
                                   ports::TimestampUs at) {
  if (f.size() < 4) {
    replies_.error(echo, -1, at);
    return;
  }
  auto& h = settings_.hemisphere[static_cast<std::size_t>(station - 1)];
  for (std::size_t i = 0; i < 3; ++i) {
    int v = 0;
    if (const int rc = to_int(f[i + 1], v); rc != 0) {
      replies_.error(echo, rc, at);
      return;
    }
    h[i] = v;
  }
}

void ParameterCommands::filter(ParameterCommand which, const Fields& f, std::string_view echo,
                               ports::TimestampUs at) {
  FilterParams& target = settings_.filter[which == ParameterCommand::position_filter ? 0 : 1];
  if (f.size() == 1 && f[0].empty()) {  // `x<>`: the current values
    replies_.reply(filter_record(static_cast<char>(which), target), at);
    return;
  }
  if (f.size() == 1) {  // `x n<>`: a macro, 2..5; it sets position and attitude
    double n = 0.0;
    if (const int rc = to_double(f[0], n); rc != 0) {
      replies_.error(echo, rc, at);
      return;
    }
    static constexpr FilterParams kMacros[] = {kFilterOff, kFilterLow, kFilterMedium, kFilterHeavy};
    if (n != std::floor(n) || n < 2.0 || n > 5.0) {  // x1: neither a macro nor 0 < F < 1
      replies_.error(echo, -3, at);
      return;
    }
    settings_.filter[0] = settings_.filter[1] = kMacros[static_cast<int>(n) - 2];
    return;
  }
  FilterParams p = target;
  double* fields[] = {&p.f, &p.flow, &p.fhigh, &p.factor};
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (i >= 4) {
      replies_.error(echo, -3, at);
      return;
    }
    if (f[i].empty()) continue;  // an empty field keeps the current value
    if (const int rc = to_double(f[i], *fields[i]); rc != 0) {
      replies_.error(echo, rc, at);
      return;
    }
  }
  if (!valid(p)) {
    replies_.error(echo, -3, at);
    return;
  }
  target = p;
}

void ParameterCommands::envelope(int station, const Fields& f, std::string_view echo,
                                 ports::TimestampUs at) {
  auto e = settings_.envelope[static_cast<std::size_t>(station - 1)];
  for (std::size_t i = 1; i < f.size(); ++i) {
    if (i > 6) {
      replies_.error(echo, -3, at);
      return;
    }
    if (f[i].empty()) continue;
    if (const int rc = to_double(f[i], e[i - 1]); rc != 0) {
      replies_.error(echo, rc, at);
      return;
    }
  }
  settings_.envelope[static_cast<std::size_t>(station - 1)] = e;
}

void ParameterCommands::station_vector(ParameterCommand which, int station, const Fields& f,
                                       std::string_view echo, ports::TimestampUs at) {
  const auto i = static_cast<std::size_t>(station - 1);
  const bool tip = which == ParameterCommand::tip_offset;
  // N: the current units (stored in inches); G: az, el, roll degrees.
  std::array<double, 3> v = tip ? settings_.tip_offset_in[i] : settings_.boresight_reference_deg[i];
  if (tip && settings_.protocol.units == tracker::Units::centimetres) {
    for (double& x : v) x *= 2.54;
  }
  if (f.size() < 4) {
    replies_.error(echo, -1, at);
    return;
  }
  for (std::size_t k = 0; k < 3; ++k) {
    if (f[k + 1].empty()) continue;  // an empty field keeps the value
    if (const int rc = to_double(f[k + 1], v[k]); rc != 0) {
      replies_.error(echo, rc, at);
      return;
    }
  }
  if (tip) {
    if (settings_.protocol.units == tracker::Units::centimetres) {
      for (double& x : v) x /= 2.54;
    }
    settings_.tip_offset_in[i] = v;
  } else {
    if (std::fabs(v[1]) > 90.0 || std::fabs(v[0]) > 180.0 || std::fabs(v[2]) > 180.0) {
      replies_.error(echo, -3, at);
      return;
    }
    settings_.boresight_reference_deg[i] = v;
  }
}

void ParameterCommands::serial_port(const Fields& f, std::string_view echo, ports::TimestampUs at) {
  double rate = 0.0;
  if (const int rc = to_double(f[0], rate); rc != 0) {
    replies_.error(echo, rc, at);
    return;
  }
  static constexpr int kRates[] = {24, 48, 96, 192, 384, 576, 1152};
  for (const int r : kRates) {
    if (rate == r) {
      settings_.baud = r * 100;  // the host must follow at once (parity, bits, HHS: accepted)
      return;
    }
  }
  replies_.error(echo, -3, at);
}

}  // namespace twister::sim
