#!/usr/bin/env python3
"""twister-sim's boot time and scenario clock on a PTY (issue 22).

1. By default the unit boots as a real Fastrak does (10 s: deaf and mute meanwhile):
   a status request (`S`) sent every 0.25 s for 3 s gets no answer.
2. With `--reset-time 0.5` (what tests and scripts pass) it answers within 2 s.
3. With `--scenario-clock stream` the scenario's `duration` counts from the host's first
   `C`: the program is still serving 2.5 s after start-up (the scenario lasts 1 s) and
   ends about 1 s after the `C`.
4. A hang-up (`--port usb`: the link and the PTY vanish, then come back) leaves the unit
   streaming in its configuration: a client that configured binary continuous output
   before the hang-up reads binary records from the new PTY without sending anything.

    sim_boot_and_clock_test.py TWISTER_SIM WORK_DIR
"""
import os
import shutil
import subprocess
import sys
import termios
import time
import tty


def open_raw(link):
    fd = os.open(link, os.O_RDWR | os.O_NOCTTY | os.O_NONBLOCK)
    tty.setraw(fd)
    attrs = termios.tcgetattr(fd)  # the unit's rate: twister-sim garbles a mismatch
    attrs[4] = attrs[5] = termios.B115200
    termios.tcsetattr(fd, termios.TCSANOW, attrs)
    return fd


def read_for(fd, seconds):
    got = b""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        time.sleep(0.02)
        try:
            got += os.read(fd, 65536)
        except (BlockingIOError, OSError):
            pass
    return got


def start(sim, work, name, extra, scenario=None, port="fixed"):
    link = os.path.join(work, name)
    args = [sim, "--link", link, "--port", port] + extra
    if scenario:
        path = os.path.join(work, name + ".scn")
        open(path, "w").write(scenario)
        args += ["--scenario", path]
    p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    if not p.stdout.readline():
        sys.exit("boot test: twister-sim printed no link path")
    return p, open_raw(link)


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

    p, fd = start(sim, work, "hangup", ["--reset-time", "0.2"],
                  "receivers 1\nfault 1.5 hangup 1\n", port="usb")
    time.sleep(0.3)
    os.write(fd, b"O1,2,11,1\rfC")  # back to back: the unit buffers while O runs
    before = read_for(fd, 0.8)
    time.sleep(1.0)  # the line is down from 1.5 s to 2.5 s
    link = os.path.join(work, "hangup")
    deadline = time.monotonic() + 3.0
    while not os.path.exists(link) and time.monotonic() < deadline:
        time.sleep(0.05)
    os.close(fd)
    fd = open_raw(link)
    after = read_for(fd, 0.5)  # nothing sent on the new PTY
    p.terminate()
    p.wait(10)
    os.close(fd)
    records = after.count(b"01 ")
    print("hang-up: %d bytes before, %d bytes (%d record headers) after, no command sent"
          % (len(before), len(after), records))
    if before.count(b"01 ") < 50:
        problems.append("hang-up: only %d bytes streamed before the hang-up" % len(before))
    if records < 40 or b"21S" in after:
        problems.append("hang-up: %d records after the line came back (still streaming "
                        "binary expected)" % records)

    for problem in problems:
        print("PROBLEM: " + problem)
    print("twister-sim boot and clock: %s" % ("ok" if not problems else "FAILED"))
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
