// Stop signals during a program's start-up. Start-up (opening files, replaying the
// journal, setting up the link) must always be stoppable, also while it holds the
// journal's lock, and must never sit on a stop signal.
//
// begin_startup_signals(): SIGINT, SIGTERM and SIGHUP get a handler installed without
// SA_RESTART (a blocking call returns EINTR) that records the signal and arms a
// one-second alarm. Start-up checks startup_stop_signal() between its steps and gives
// up cleanly (closing the journal releases its lock); if it is stuck for a second
// anyway, SIGALRM ends the process, which is no worse than a SIGKILL (the journal is
// made to survive one) and the kernel drops the lock.
// end_startup_signals(): blocks the three signals (the loop's signalfd takes them),
// cancels the alarm, and re-raises a signal that came during start-up, so it is
// pending for the loop: its first pass then stops as on any stop signal.
#pragma once

namespace twister::hal {

void begin_startup_signals();
// The stop signal received since begin_startup_signals() (0: none).
int startup_stop_signal();
void end_startup_signals();

}  // namespace twister::hal
