#include "station_checks.hpp"

#include <sys/stat.h>
#include <sys/un.h>

#include <charconv>

namespace twister::station_app {
namespace {

// "" when `path` is a regular file, else why not.
std::string regular_file_problem(const std::filesystem::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return "does not exist or cannot be reached";
  if (!S_ISREG(st.st_mode)) return "is not a regular file";
  return "";
}

}  // namespace

std::vector<std::string> referenced_file_problems(const StationConfig& config,
                                                  const std::filesystem::path& config_dir) {
  std::vector<std::string> out;
  std::filesystem::path mesh = config.station.mesh;
  if (mesh.is_relative()) mesh = config_dir / mesh;
  if (const std::string why = regular_file_problem(mesh); !why.empty()) {
    out.push_back("station.mesh: " + mesh.string() + ": " + why);
  }
  const std::string& scenario = config.tracker.sim.scenario_file;
  if (config.tracker.backend == TrackerBackend::sim && !scenario.empty()) {
    if (const std::string why = regular_file_problem(scenario); !why.empty()) {
      out.push_back("tracker.sim.scenario_file: " + scenario + ": " + why);
    }
  }
  const std::filesystem::path journal = config.station.journal;
  struct stat st {};
  if (::stat(journal.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode))
      out.push_back("station.journal: " + journal.string() + ": is not a regular file");
  } else {
    const std::filesystem::path dir = journal.has_parent_path() ? journal.parent_path() : ".";
    if (::stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
      out.push_back("station.journal: " + journal.string() + ": its folder " + dir.string() +
                    " does not exist");
    }
  }
  return out;
}

std::string link_address_problem(const std::string& address) {
  if (address.rfind("unix:", 0) == 0) {
    const std::string path = address.substr(5);
    if (path.empty()) return "unix: needs a path (unix:/run/twister/link.sock)";
    if (path.size() >= sizeof(sockaddr_un::sun_path)) return "the socket path is too long";
    return "";
  }
  if (address.rfind("tcp:", 0) == 0) {
    const std::string rest = address.substr(4);
    const auto colon = rest.rfind(':');
    if (colon == std::string::npos || colon == 0)
      return "tcp: needs HOST:PORT (tcp:127.0.0.1:7070)";
    unsigned port = 0;
    const char* first = rest.data() + colon + 1;
    const char* last = rest.data() + rest.size();
    const auto [end, ec] = std::from_chars(first, last, port);
    if (first == last || ec != std::errc() || end != last || port == 0 || port > 65535) {
      return "the port must be a number from 1 to 65535";
    }
    return "";
  }
  return "expected unix:PATH or tcp:HOST:PORT";
}

}  // namespace twister::station_app
