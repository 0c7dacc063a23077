// [link]: address, socket_mode, socket_group, listen, psk_file,
// allow_unauthenticated_tcp, baud, max_spectators, spectator_stall_seconds.
#include "link_config.hpp"

#include <algorithm>
#include <cstdio>

namespace twister::station_app::internal {
namespace {

constexpr std::int64_t kLinkBauds[] = {9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600};

bool parse_ipv4(const std::string& host, bool& loopback) {
  unsigned a = 0, b = 0, c = 0, d = 0;
  char tail = 0;
  if (std::sscanf(host.c_str(), "%u.%u.%u.%u%c", &a, &b, &c, &d, &tail) != 4) return false;
  if (a > 255 || b > 255 || c > 255 || d > 255) return false;
  loopback = a == 127;
  return true;
}

}  // namespace

std::string check_link_address(const std::string& address, bool& loopback) {
  loopback = true;
  const auto rest_of = [&](const char* prefix) {
    return address.substr(std::string(prefix).size());
  };
  if (address.rfind("unix:", 0) == 0) {
    const std::string path = rest_of("unix:");
    if (path.empty() || path.size() > 107) return "a socket path of 1 to 107 characters";
    return "";
  }
  if (address.rfind("serial:", 0) == 0) {
    return rest_of("serial:").empty() ? "a device path after serial:" : "";
  }
  if (address.rfind("tcp:", 0) == 0) {
    const std::string rest = rest_of("tcp:");
    const auto colon = rest.rfind(':');
    if (colon == std::string::npos) return "tcp:A.B.C.D:PORT";
    const std::string port = rest.substr(colon + 1);
    const bool digits =
        !port.empty() && port.size() <= 5 &&
        std::all_of(port.begin(), port.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
    if (!parse_ipv4(rest.substr(0, colon), loopback) || !digits || std::stoi(port) < 1 ||
        std::stoi(port) > 65535) {
      return "tcp:A.B.C.D:PORT (IPv4 address, port 1..65535)";
    }
    return "";
  }
  return "unix:PATH, tcp:A.B.C.D:PORT or serial:DEVICE";
}

std::string unauthenticated_tcp_problem(const LinkSection& link) {
  if (link.address.rfind("tcp:", 0) != 0 || !link.psk_file.empty() ||
      link.allow_unauthenticated_tcp) {
    return "";
  }
  return "expected psk_file with a tcp: address (without a key any local user can take the "
         "display; use unix:PATH with socket_group, or set allow_unauthenticated_tcp = true), "
         "got \"" +
         link.address + "\"";
}

void read_link(ConfigReader& root, StationFileConfig& cfg) {
  ConfigReader l = root.table("link", false);
  LinkSection& lc = cfg.link;
  bool loopback = true;
  if (l.string("address", false, lc.address)) {
    const std::string bad = check_link_address(lc.address, loopback);
    if (!bad.empty()) {
      l.error(l.node("address"), "address", "expected " + bad + ", got \"" + lc.address + "\"");
    }
  }
  std::int64_t mode = 0;
  if (l.integer("socket_mode", false, 0, 0777, mode)) {
    if ((mode & 0600) != 0600) {
      char text[32];
      std::snprintf(text, sizeof text, "0o%03llo", static_cast<unsigned long long>(mode));
      l.error(l.node("socket_mode"), "socket_mode",
              std::string("expected a mode the station can use (owner read and write: 0o600 to "
                          "0o777), got ") +
                  text);
    } else {
      lc.socket_mode = static_cast<std::uint32_t>(mode);
    }
  }
  l.string("socket_group", false, lc.socket_group);
  std::string listen;
  if (l.string("listen", false, listen, {"loopback", "network"})) {
    lc.listen = listen == "network" ? LinkListen::network : LinkListen::loopback;
  }
  l.string("psk_file", false, lc.psk_file);
  l.boolean("allow_unauthenticated_tcp", lc.allow_unauthenticated_tcp);
  std::int64_t baud = 0;
  if (l.integer("baud", false, 1, 4'000'000, baud)) {
    if (std::find(std::begin(kLinkBauds), std::end(kLinkBauds), baud) == std::end(kLinkBauds)) {
      l.error(l.node("baud"), "baud",
              "expected one of 9600 19200 38400 57600 115200 230400 460800 921600, got " +
                  std::to_string(baud));
    } else {
      lc.baud = static_cast<std::uint32_t>(baud);
    }
  }
  std::int64_t spectators = 0;
  if (l.integer("max_spectators", false, 0, 8, spectators)) {
    lc.max_spectators = static_cast<std::uint32_t>(spectators);
  }
  l.real("spectator_stall_seconds", false, 0.1, 600.0, lc.spectator_stall_seconds);
  if (lc.listen == LinkListen::network && lc.psk_file.empty()) {
    l.error(l.node("listen"), "listen",
            "expected psk_file with listen = \"network\" (a link beyond loopback needs a key)");
  }
  if (const std::string why = unauthenticated_tcp_problem(lc); !why.empty()) {
    l.error(l.node("address"), "address", why);
  }
  if (!loopback && lc.listen != LinkListen::network) {
    l.error(l.node("address"), "address",
            "expected a loopback address (127.x.x.x) unless listen = \"network\", got \"" +
                lc.address + "\"");
  }
  l.finish();
}

}  // namespace twister::station_app::internal
