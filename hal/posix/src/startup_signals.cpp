// Stop signals during start-up (see the header). The handler only does
// async-signal-safe things: store to a sig_atomic_t, alarm(2).
#include "twister/hal/startup_signals.hpp"

#include <pthread.h>
#include <unistd.h>

#include <csignal>

namespace twister::hal {
namespace {

volatile std::sig_atomic_t g_stop_signal = 0;
constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};

void on_stop_signal(int sig) {
  if (g_stop_signal == 0) {
    g_stop_signal = sig;
    ::alarm(1);  // the limit for start-up to give up by itself
  }
}

sigset_t stop_set() {
  sigset_t set;
  sigemptyset(&set);
  for (const int sig : kStopSignals) sigaddset(&set, sig);
  return set;
}

}  // namespace

void begin_startup_signals() {
  g_stop_signal = 0;
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: a blocking call returns EINTR
  for (const int sig : kStopSignals) ::sigaction(sig, &action, nullptr);
  std::signal(SIGALRM, SIG_DFL);
  const sigset_t set = stop_set();
  pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
}

int startup_stop_signal() { return g_stop_signal; }

void end_startup_signals() {
  const sigset_t set = stop_set();
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  ::alarm(0);
  struct sigaction action {};
  action.sa_handler = SIG_DFL;
  sigemptyset(&action.sa_mask);
  for (const int sig : kStopSignals) ::sigaction(sig, &action, nullptr);
  // Blocked now: the signal stays pending until the loop's signalfd reads it.
  if (const int sig = g_stop_signal; sig != 0) ::raise(sig);
}

}  // namespace twister::hal
