#!/usr/bin/env python3
"""twister-sim's boot time and scenario clock on a PTY (issue 22).

1. By default the unit boots as a real Fastrak does (10 s: deaf and mute meanwhile):
   a status request (`S`) sent every 0.25 s for 3 s gets no answer.
2. With `--reset-time 0.5` (what tests and scripts pass) it answers within 2 s.
3. With `--scenario-clock stream` the scenario's `duration` counts from the host's first
   `C`: the program is still serving 2.5 s after start-up (the scenario lasts 1 s) and
   ends about 1 s after the `C`.

    sim_boot_and_clock_test.py TWISTER_SIM WORK_DIR
"""
import os
import shutil
import subprocess
import sys
import termios
import time
import tty


def start(sim, work, name, extra, scenario=None):
    link = os.path.join(work, name)
    args = [sim, "--link", link, "--port", "fixed"] + extra
    if scenario:
        path = os.path.join(work, name + ".scn")
        open(path, "w").write(scenario)
        args += ["--scenario", path]
    p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    if not p.stdout.readline():
        sys.exit("boot test: twister-sim printed no link path")
    fd = os.open(link, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
    tty.setraw(fd)
    attrs = termios.tcgetattr(fd)  # the unit's rate: twister-sim garbles a mismatch
    attrs[4] = attrs[5] = termios.B115200
    termios.tcsetattr(fd, termios.TCSANOW, attrs)
    return p, fd


def ask_status(fd, seconds):
    """Sends S every 0.25 s for up to `seconds`; the seconds until a status came, or None."""
    t0 = time.monotonic()
    got = b""
    while time.monotonic() - t0 < seconds:
        os.write(fd, b"S")
        time.sleep(0.25)
        try:
            got += os.read(fd, 4096)
        except BlockingIOError:
            pass
        if b"2" in got and b"S" in got:
            return time.monotonic() - t0
    return None


def main():
    sim, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    problems = []

    p, fd = start(sim, work, "default", [])
    waited = ask_status(fd, 3.0)
    p.terminate()
    p.wait(10)
    os.close(fd)
    print("default boot: status after %s s of 3" % waited)
    if waited is not None:
        problems.append("a status came %.2f s after start-up; a real unit boots 10 s" % waited)

    p, fd = start(sim, work, "quick", ["--reset-time", "0.5"])
    waited = ask_status(fd, 2.0)
    p.terminate()
    p.wait(10)
    os.close(fd)
    print("--reset-time 0.5: status after %s s" % waited)
    if waited is None or waited < 0.4:
        problems.append("--reset-time 0.5: status after %s s (expected 0.5-2 s)" % waited)

    p, fd = start(sim, work, "stream", ["--reset-time", "0.2", "--scenario-clock", "stream"],
                  "receivers 1\nduration 1\n")
    time.sleep(2.5)
    if p.poll() is not None:
        problems.append("--scenario-clock stream: ended before any C")
    os.write(fd, b"C")
    t0 = time.monotonic()
    try:
        p.wait(5)
    except subprocess.TimeoutExpired:
        p.kill()
        problems.append("--scenario-clock stream: still running 5 s after C")
    ran = time.monotonic() - t0
    os.close(fd)
    print("--scenario-clock stream: ended %.2f s after C (scenario duration 1 s)" % ran)
    if ran < 0.8:
        problems.append("--scenario-clock stream: ended %.2f s after C" % ran)

    for problem in problems:
        print("PROBLEM: " + problem)
    print("twister-sim boot and clock: %s" % ("ok" if not problems else "FAILED"))
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
