// The device model's command interpreter (docs/fastrak-protocol.md §2): mode letters, parameter
// commands with their read-backs, and the command-error record for bad input.
#include <cstdio>
#include <cstdlib>

#include "twister/sim/fastrak_device.hpp"
#include "twister/tracker/fastrak_encoder.hpp"

// GCC 12 reports a false -Wrestrict inside std::string concatenation at -O3
// (GCC bug 105329); nothing here overlaps.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wrestrict"
#endif

namespace twister::sim {
namespace {

using tracker::Format;
using tracker::Item;
using tracker::kCtrlY;
using tracker::OutputList;
using tracker::Units;

// Splits "1,2,,3" into fields; empty fields are kept as "".
std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out(1);
  for (char c : s) {
    if (c == ',')
      out.emplace_back();
    else
      out.back() += c;
  }
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

}  // namespace

void FastrakDevice::execute(char command, const std::string& args, ports::TimestampUs now) {
  ++counters_.commands;
  if (execute_mode(command, now)) return;
  const std::string echo = std::string(1, command) + args;
  const auto f = split(args);
  if (command == 'x' || command == 'v') {
    execute_filter(command, f, echo, now);
    return;
  }
  if (command == 'o') {
    execute_serial_port(f, echo, now);
    return;
  }
  if (std::string("OlHeQ").find(command) == std::string::npos) {
    return;  // accepted, no effect on the model (A, R, B, b, G, N, I, X)
  }
  int station = 0;
  if (const int rc = to_int(f[0], station); rc != 0) {
    send_error(echo, rc, now);
    return;
  }
  if (station < 1 || station > 4) {
    send_error(echo, -3, now);
    return;
  }
  switch (command) {
    case 'O':
      execute_output_list(station, f, echo, now);
      return;
    case 'l':
      execute_station_state(station, f, echo, now);
      return;
    case 'H':
      execute_hemisphere(station, f, echo, now);
      return;
    case 'Q':
      execute_envelope(station, f, echo, now);
      return;
    default: {  // 'e': stylus mode 0 or 1
      int mode = 0;
      if (f.size() < 2 || to_int(f[1], mode) != 0 || (mode != 0 && mode != 1)) {
        send_error(echo, -3, now);
        return;
      }
      e_mode_ = mode;
      return;
    }
  }
}

bool FastrakDevice::execute_mode(char command, ports::TimestampUs now) {
  switch (command) {
    case 'P':
      for (const int station : active_stations()) queue_record(station, now);
      return true;
    case 'C':
      continuous_ = true;
      output_on_ = true;
      return true;
    case 'c':
      continuous_ = false;
      // The stream stopped: what was left of a line hit's budget has nothing to eat.
      counters_.drop_expired += drop_left_;
      drop_left_ = 0;
      return true;
    case 'F':
      proto_.format = Format::ascii;
      return true;
    case 'f':
      proto_.format = config_.packed16 ? Format::binary16 : Format::binary;
      return true;
    case 'U':
      proto_.units = Units::inches;
      return true;
    case 'u':
      proto_.units = Units::centimetres;
      return true;
    case 'S':
      send_status(now);
      return true;
    case 'W': {
      const bool cont = continuous_;
      const ports::TimestampUs busy = busy_until_;
      power_up(now);
      --counters_.resets;
      continuous_ = cont;
      busy_until_ = busy;
      return true;
    }
    case kCtrlY:
      power_up(now);
      return true;
    default:
      return false;
  }
}

void FastrakDevice::send_status(ports::TimestampUs now) {
  tracker::FastrakStatus st;
  const ActiveStations act = active_stations();
  st.station = static_cast<std::uint8_t>(act.empty() ? 1 : act[next_station_ % act.size()]);
  st.flags = 0x3F0;
  st.binary = proto_.format != Format::ascii;
  st.centimetres = proto_.units == Units::centimetres;
  st.continuous = continuous_;
  std::array<std::byte, 64> buf{};
  auto n = tracker::encode_status(st, buf);
  if (n.ok()) queue(std::string(reinterpret_cast<const char*>(buf.data()), *n), now);
}

void FastrakDevice::execute_output_list(int station, const std::vector<std::string>& f,
                                        const std::string& echo, ports::TimestampUs now) {
  auto& st = proto_.stations[static_cast<std::size_t>(station - 1)];
  if (f.size() == 1) {
    std::string r = "2" + std::to_string(station) + "O";
    char item[8];
    for (std::size_t i = 0; i < st.list.count; ++i) {
      std::snprintf(item, sizeof item, "%2d", static_cast<int>(st.list.items[i]));
      r += item;
    }
    queue(r + "\r\n", now);
    return;
  }
  OutputList list;
  for (std::size_t i = 1; i < f.size(); ++i) {
    int code = 0;
    if (const int rc = to_int(f[i], code); rc != 0) {
      send_error(echo, rc, now);
      return;
    }
    if (code < 0 || code > 255 || !tracker::is_supported_item(static_cast<std::uint8_t>(code)) ||
        list.count >= tracker::kMaxItems) {
      send_error(echo, -3, now);
      return;
    }
    list.items[list.count++] = static_cast<Item>(code);
  }
  if (tracker::record_length(list, proto_.format) > tracker::kMaxRecordBytes) {
    send_error(echo, -5, now);
    return;
  }
  st.list = list;
}

void FastrakDevice::execute_station_state(int station, const std::vector<std::string>& f,
                                          const std::string& echo, ports::TimestampUs now) {
  if (f.size() == 1) {
    std::string r = "2" + std::to_string(station) + "l";
    for (const auto& s : proto_.stations) r += s.enabled ? '1' : '0';
    queue(r + "\r\n", now);
    return;
  }
  int state = 0;
  if (const int rc = to_int(f[1], state); rc != 0) {
    send_error(echo, rc, now);
    return;
  }
  proto_.stations[static_cast<std::size_t>(station - 1)].enabled = state != 0;
}

void FastrakDevice::execute_hemisphere(int station, const std::vector<std::string>& f,
                                       const std::string& echo, ports::TimestampUs now) {
  if (f.size() < 4) {
    send_error(echo, -1, now);
    return;
  }
  auto& h = hemisphere_[static_cast<std::size_t>(station - 1)];
  for (std::size_t i = 0; i < 3; ++i) {
    int v = 0;
    if (const int rc = to_int(f[i + 1], v); rc != 0) {
      send_error(echo, rc, now);
      return;
    }
    h[i] = v;
  }
}

}  // namespace twister::sim
