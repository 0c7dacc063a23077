// A twister-station (or any program) running in the background for a test: its
// stderr in a file, waits with deadlines that fail the test instead of hanging it
// (a process that outlives its deadline is SIGKILLed).
#pragma once

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "station_test_support.hpp"

namespace twister::station_test {

class BackgroundProcess {
 public:
  BackgroundProcess(const std::vector<std::string>& argv, std::string log_path)
      : log_(std::move(log_path)) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_ = ::fork();
    if (pid_ == 0) {
      FILE* err = std::freopen(log_.c_str(), "w", stderr);
      FILE* out = std::freopen("/dev/null", "w", stdout);
      (void)err;
      (void)out;
      ::execv(args[0], args.data());
      ::_exit(127);
    }
  }
  ~BackgroundProcess() {
    if (pid_ > 0 && !exited_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  BackgroundProcess(const BackgroundProcess&) = delete;
  BackgroundProcess& operator=(const BackgroundProcess&) = delete;

  pid_t pid() const { return pid_; }
  std::string log() const { return read_file(log_); }

  // Waits until `ready` holds (true) or the process ends or `seconds` pass (false).
  bool wait_until(const std::function<bool()>& ready, double seconds) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < until) {
      if (ready()) return true;
      if (poll_exit()) return ready();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }
  bool wait_for_log(const std::string& text, double seconds) {
    return wait_until([this, &text] { return log().find(text) != std::string::npos; }, seconds);
  }
  // Its exit code within `seconds` (-1: killed by a signal); -2 when it was still
  // running then (it is SIGKILLed).
  int exit_within(double seconds) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (!poll_exit() && std::chrono::steady_clock::now() < until) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (!exited_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
      exited_ = true;
      return -2;
    }
    return WIFEXITED(status_) ? WEXITSTATUS(status_) : -1;
  }
  bool exited() { return poll_exit(); }

 private:
  bool poll_exit() {
    if (exited_) return true;
    if (::waitpid(pid_, &status_, WNOHANG) == pid_) exited_ = true;
    return exited_;
  }

  std::string log_;
  pid_t pid_ = -1;
  int status_ = 0;
  bool exited_ = false;
};

// Can the journal be locked now (no station holds it)?
inline bool journal_lock_is_free(const std::string& journal) {
  hal::PosixFileStorage storage;
  return storage.open({.path = journal, .create_if_missing = false, .lock = true}).ok();
}

// A station.toml on `mesh` with the simulator playing `scenario_path`.
inline std::string station_config(const std::string& journal, const std::string& mesh,
                                  const std::string& scenario_path, const char* time) {
  return "[station]\njournal = \"" + journal + "\"\nmesh = \"" + mesh +
         "\"\n[tracker]\nbackend = \"sim\"\n[tracker.sim]\nscenario_file = \"" + scenario_path +
         "\"\ntime = \"" + time +
         "\"\n[buttons]\nbackend = \"sim\"\n[systemd]\nnotify = false\nwatchdog = false\n";
}

// Both hands resting away from the model for `seconds`: no stroke, nothing written.
inline std::string still_scenario(double seconds) {
  return "seed 7\nreceivers 2\nduration " + std::to_string(seconds) +
         "\nkey 0 1 11.81 -14.00 1.97 0 0 0\nkey 0 2 11.81 -3.15 1.97 0 0 0\n";
}

}  // namespace twister::station_test
