// Stop signals during a program's start-up. Start-up (opening files, replaying the
// journal, setting up the link) must always be stoppable, also while it holds the
// journal's lock, and must never sit on a stop signal.
//
// StartupSignals (one, in main, before anything else): SIGINT, SIGTERM and SIGHUP are
// blocked in the calling thread (so every thread it starts inherits the block, as
// the loop's signalfd needs) and a watcher thread takes them with sigtimedwait(2):
// the first one is recorded and arms a one-second alarm. Start-up checks
// startup_stop_signal() between its steps and gives up cleanly (closing the journal
// releases its lock); if it is stuck for a second anyway, SIGALRM ends the process,
// which is no worse than a SIGKILL (the journal is made to survive one) and the
// kernel drops the lock.
// end(): stops the watcher, cancels the alarm, and re-raises a signal that came
// during start-up in the calling thread, where it stays pending (blocked) for the
// loop's signalfd: its first pass then stops as on any stop signal. The destructor
// ends it too (an early return from main).
#pragma once

namespace twister::hal {

class StartupSignals {
 public:
  StartupSignals();
  ~StartupSignals();
  StartupSignals(const StartupSignals&) = delete;
  StartupSignals& operator=(const StartupSignals&) = delete;
  void end();
};

// The stop signal received during start-up (0: none).
int startup_stop_signal();

}  // namespace twister::hal
