#include "station_checks.hpp"

#include <sys/stat.h>

#include "config/link_config.hpp"

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

std::vector<std::string> referenced_file_problems(const StationFileConfig& config,
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
  bool loopback = true;
  const std::string form = internal::check_link_address(address, loopback);
  return form.empty() ? "" : "expected " + form;
}

}  // namespace twister::station_app
