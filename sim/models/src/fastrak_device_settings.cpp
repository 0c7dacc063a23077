// The device model's setting commands beyond the output lists (docs/fastrak-protocol.md §2): the
// adaptive filters `x` / `v` (parameters, macros, read-back record), the angular
// envelope `Q` and the serial port `o`.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "twister/sim/fastrak_device.hpp"

namespace twister::sim {
namespace {

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

}  // namespace

void FastrakDevice::execute_filter(char command, const std::vector<std::string>& f,
                                   const std::string& echo, ports::TimestampUs now) {
  FilterParams& target = filter_params_[command == 'x' ? 0 : 1];
  if (f.size() == 1 && f[0].empty()) {  // `x<>`: the current values
    queue(filter_record(command, target), now);
    return;
  }
  if (f.size() == 1) {  // `x n<>`: a macro, 2..5; it sets position and attitude
    double n = 0.0;
    if (const int rc = to_double(f[0], n); rc != 0) {
      send_error(echo, rc, now);
      return;
    }
    static constexpr FilterParams kMacros[] = {kFilterOff, kFilterLow, kFilterMedium, kFilterHeavy};
    if (n != std::floor(n) || n < 2.0 || n > 5.0) {  // x1: neither a macro nor 0 < F < 1
      send_error(echo, -3, now);
      return;
    }
    filter_params_[0] = filter_params_[1] = kMacros[static_cast<int>(n) - 2];
    return;
  }
  FilterParams p = target;
  double* fields[] = {&p.f, &p.flow, &p.fhigh, &p.factor};
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (i >= 4) {
      send_error(echo, -3, now);
      return;
    }
    if (f[i].empty()) continue;  // an empty field keeps the current value
    if (const int rc = to_double(f[i], *fields[i]); rc != 0) {
      send_error(echo, rc, now);
      return;
    }
  }
  if (!valid(p)) {
    send_error(echo, -3, now);
    return;
  }
  target = p;
}

void FastrakDevice::execute_envelope(int station, const std::vector<std::string>& f,
                                     const std::string& echo, ports::TimestampUs now) {
  auto e = envelope_[static_cast<std::size_t>(station - 1)];
  for (std::size_t i = 1; i < f.size(); ++i) {
    if (i > 6) {
      send_error(echo, -3, now);
      return;
    }
    if (f[i].empty()) continue;
    if (const int rc = to_double(f[i], e[i - 1]); rc != 0) {
      send_error(echo, rc, now);
      return;
    }
  }
  envelope_[static_cast<std::size_t>(station - 1)] = e;
}

void FastrakDevice::execute_serial_port(const std::vector<std::string>& f, const std::string& echo,
                                        ports::TimestampUs now) {
  double rate = 0.0;
  if (const int rc = to_double(f[0], rate); rc != 0) {
    send_error(echo, rc, now);
    return;
  }
  static constexpr int kRates[] = {24, 48, 96, 192, 384, 576, 1152};
  for (const int r : kRates) {
    if (rate == r) {
      baud_ = r * 100;  // the host must follow at once (parity, bits, HHS: accepted)
      return;
    }
  }
  send_error(echo, -3, now);
}

}  // namespace twister::sim
