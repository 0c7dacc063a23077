// Helpers for the tests that run twister-station as a process: shell commands with
// their output, scratch files, journals read back, and simulator scenarios with
// freeze chains (hand 1 = receiver 2 grabs with button line 3 and freezes with line
// 5 while twisting) on the deploy sphere.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "twister/hal/posix_file_storage.hpp"
#include "twister/journal/journal_reader.hpp"
#include "twister/journal/journal_scanner.hpp"

namespace twister::station_test {

struct RunResult {
  int exit_code = -1;  // -1: could not start or did not exit normally
  std::string output;  // stdout + stderr
};

inline RunResult run_command(const std::string& cmd) {
  RunResult r;
  FILE* p = ::popen((cmd + " 2>&1").c_str(), "r");
  if (p == nullptr) return r;
  std::array<char, 512> buf{};
  while (std::fgets(buf.data(), buf.size(), p) != nullptr) r.output += buf.data();
  const int status = ::pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_file(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Every good record of a journal (and the reader's verdict on what follows them).
struct Journal {
  std::vector<journal::JournalRecord> records;
  journal::TailProblem problem = journal::TailProblem::none;
  bool opened = false;
};

inline Journal read_journal(const std::string& path) {
  Journal j;
  hal::PosixFileStorage storage;
  if (!storage.open({.path = path, .create_if_missing = false, .read_only = true}).ok()) return j;
  journal::JournalReader reader(storage);
  if (!reader.open().ok()) return j;
  j.opened = true;
  for (auto r = reader.next(); r.ok(); r = reader.next()) j.records.push_back(*r);
  j.problem = reader.problem();
  return j;
}

// The sequences of "committed as journal record N" lines in a station's log.
inline std::set<std::uint32_t> committed_sequences(const std::string& log) {
  std::set<std::uint32_t> out;
  const std::string key = "committed as journal record ";
  for (std::size_t at = log.find(key); at != std::string::npos; at = log.find(key, at + 1)) {
    std::size_t end = at + key.size();
    std::uint32_t n = 0;
    bool digits = false;
    while (end < log.size() && log[end] >= '0' && log[end] <= '9') {
      n = n * 10 + static_cast<std::uint32_t>(log[end++] - '0');
      digits = true;
    }
    if (digits) out.insert(n);
  }
  return out;
}

inline std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// `strokes` strokes of hand 1, each a chain of `freezes` freeze steps (twist 40 degrees
// per step), one every 3 s from 3 s; hand 0 holds still, away from the model.
inline std::string chain_scenario(int strokes, int freezes) {
  std::ostringstream s;
  const double end = 3.0 + 3.0 * strokes + 1.0;
  s << "seed 7\nreceivers 2\nduration " << end << "\n";
  s << "key 0 1 11.81 -14.00 1.97 0 0 0\nkey " << end << " 1 11.81 -14.00 1.97 0 0 0\n";
  s << "key 0 2 11.81 -3.15 1.97 0 0 0\n";
  for (int k = 0; k < strokes; ++k) {
    const double t0 = 3.0 + 3.0 * k;
    s << "key " << t0 << " 2 11.81 -3.15 1.97 0 0 0\n";
    s << "button " << t0 + 0.05 << " 3 1\n";
    const double step = 2.0 / (freezes + 1);
    for (int f = 1; f <= freezes + 1; ++f) {
      s << "key " << t0 + step * f << " 2 11.81 " << -3.15 + 0.2 * f << " 1.97 0 0 " << 40 * f
        << "\n";
      if (f <= freezes) {
        s << "button " << t0 + step * f + 0.05 << " 5 1\n";
        s << "button " << t0 + step * f + 0.15 << " 5 0\n";
      }
    }
    s << "button " << t0 + 2.2 << " 3 0\n";
    s << "key " << t0 + 2.9 << " 2 11.81 -3.15 1.97 0 0 0\n";
  }
  s << "key " << end << " 2 11.81 -3.15 1.97 0 0 0\n";
  return s.str();
}

// A station.toml on the deploy sphere with the simulator playing `scenario_path`
// (virtual time) and its buttons.
inline std::string sim_config(const std::string& journal, const std::string& scenario_path,
                              const char* time = "virtual") {
  return std::string("[station]\njournal = \"") + journal +
         "\"\nmesh = \"" TWISTER_DEPLOY_DIR
         "/sim_sphere.obj\"\n[tracker]\nbackend = \"sim\"\n[tracker.sim]\nscenario_file = \"" +
         scenario_path + "\"\ntime = \"" + time +
         "\"\n[buttons]\nbackend = \"sim\"\n[systemd]\nnotify = false\nwatchdog = false\n";
}

}  // namespace twister::station_test
