// Stop signals during start-up (see the header): a watcher thread waits for them
// with sigtimedwait while every other thread keeps them blocked.
#include "twister/hal/startup_signals.hpp"

#include <pthread.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <ctime>
#include <thread>

namespace twister::hal {
namespace {

std::atomic<int> g_stop_signal{0};
std::atomic<bool> g_watching{false};
std::thread g_watcher;

sigset_t stop_set() {
  sigset_t set;
  sigemptyset(&set);
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&set, sig);
  return set;
}

void watch(sigset_t set) {
  const timespec tick{0, 20'000'000};  // how soon end() is noticed
  while (g_watching.load()) {
    const int sig = ::sigtimedwait(&set, nullptr, &tick);
    int none = 0;
    if (sig > 0 && g_stop_signal.compare_exchange_strong(none, sig)) {
      ::alarm(1);  // the limit for start-up to give up by itself
    }
  }
}

}  // namespace

StartupSignals::StartupSignals() {
  const sigset_t set = stop_set();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  std::signal(SIGALRM, SIG_DFL);
  g_stop_signal = 0;
  g_watching = true;
  g_watcher = std::thread(watch, set);
}

StartupSignals::~StartupSignals() { end(); }

void StartupSignals::end() {
  if (!g_watcher.joinable()) return;
  g_watching = false;
  g_watcher.join();
  ::alarm(0);
  // Blocked here: the signal stays pending until the loop's signalfd reads it.
  if (const int sig = g_stop_signal.load(); sig != 0) ::raise(sig);
}

int startup_stop_signal() { return g_stop_signal.load(); }

}  // namespace twister::hal
