#!/usr/bin/env python3
"""End-to-end over a PTY (issue 16): twister-sim serves a stylus scenario on a
pseudo-terminal, twister-station reads it as a serial Fastrak (buttons: the stylus
item), serves a Unix-socket link, twister-bridge --offscreen renders and exports.

Checks: the station's final model = the display's = `twister replay` of the journal
= the station alone on the in-process simulator in virtual time (run_scenario.py);
the poses line reports no conversion error; every stroke of the scenario committed.
Only stylus scenarios can run here: the Fastrak line carries no other button.
`--model liberty|patriot` (issue 22): twister-sim plays that unit (`--model`) and the
station reads it as one (`tracker.model`); the reference stays the in-process Fastrak
run, so the checksum shows the frames carry the same poses.

    pty_chain_test.py --bin BUILD/bin --scenario S.scn --out DIR --commits N [--model M]
"""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "sim", "scenarios"))
sys.path.insert(0, os.path.join(HERE, "..", "soak"))
import run_scenario  # noqa: E402
from soak_support import Proc, wait_for_line  # noqa: E402


def reference(a):
    r = subprocess.run([sys.executable, run_scenario.__file__, a.scenario, "--bin", a.bin,
                        "--out", os.path.join(a.out, "reference")], capture_output=True,
                       text=True)
    m = re.search(r"^station ([0-9a-f]{16})$", r.stdout, re.M)
    if r.returncode != 0 or not m:
        sys.exit("pty e2e: the reference run failed:\n" + r.stdout + r.stderr)
    return m.group(1)


def chain(a, out):
    exe = lambda name: os.path.join(a.bin, name)  # noqa: E731
    h = run_scenario.header(a.scenario)
    subprocess.run([exe("twister"), "mesh"] + h["mesh"].split() +
                   ["--out", os.path.join(out, "start.obj")], check=True,
                   stdout=subprocess.DEVNULL)
    duration = float(re.search(r"^duration (\S+)", open(a.scenario).read(), re.M).group(1))
    link = os.path.join(out, "fastrak")
    # Commands take no time here: on a loaded machine a starved twister-sim would lose
    # a configuration command that arrived while it "processed" the one before (as a
    # real unit would), e.g. `e1,0`, and the stylus would then stop the stream. The
    # command-time model has its own tests (fastrak_fidelity_pty_test).
    sim = Proc([exe("twister-sim"), "--scenario", a.scenario, "--link", link,
                "--command-time", "all=0", "--model", a.model, "--reset-time", "0.5"],
               os.path.join(out, "sim.log"), stdout_pipe=True)
    if wait_for_line(sim.popen.stdout, 10.0) is None:
        sys.exit("pty e2e: twister-sim printed no link path")
    cfg = os.path.join(out, "station.toml")
    open(cfg, "w").write(
        '[station]\njournal = "%s/journal.twj"\nmesh = "%s/start.obj"\n'
        '[tracker]\nbackend = "serial"\nmodel = "%s"\nreconnect_interval_ms = 200\n'
        '[tracker.serial]\ndevice = "%s"\n[buttons]\nbackend = "stylus"\ndebounce_ms = 10\n'
        '[systemd]\nnotify = false\nwatchdog = false\n' % (out, out, a.model, link))
    sock = os.path.join(out, "link.sock")
    station = Proc([exe("twister-station"), "--config", cfg, "--log-level", "info",
                    "--link", "unix:" + sock, "--link-wait", "10",
                    "--duration", "%g" % (duration - 0.5)], os.path.join(out, "station.log"))
    env = dict(os.environ, EGL_PLATFORM="surfaceless")
    env.pop("DISPLAY", None)
    bridge = Proc([exe("twister-bridge"), "--connect", "unix:" + sock, "--offscreen",
                   "--size", "320x240", "--snapshots", os.path.join(out, "pictures"),
                   "--export", os.path.join(out, "final.obj"), "--exit-on-disconnect",
                   "--timeout", str(duration + 30)] + h["view"].split(),
                  os.path.join(out, "bridge.log"), env=env)
    rc = (station.popen.wait(duration + 40), bridge.popen.wait(60))
    sim.stop(signal.SIGTERM)
    return rc, station.text(), bridge.text()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--scenario", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--commits", type=int, required=True, help="strokes in the scenario")
    ap.add_argument("--model", default="fastrak", choices=["fastrak", "liberty", "patriot"])
    a = ap.parse_args()
    shutil.rmtree(a.out, ignore_errors=True)
    out = os.path.join(os.path.abspath(a.out), "chain")
    os.makedirs(os.path.join(out, "pictures"))
    ref = reference(a)
    rc, slog, blog = chain(a, out)
    problems = [] if rc == (0, 0) else ["exit codes (station, bridge) %s" % (rc,)]
    station = re.findall(r"^twister-station: mesh checksum ([0-9a-f]+)$", slog, re.M)
    display = re.findall(r"exported mesh version \d+ \(checksum ([0-9a-f]+)\)", blog)
    r = subprocess.run([os.path.join(a.bin, "twister"), "replay", out + "/journal.twj",
                        "--mesh", out + "/start.obj", "--out", out + "/replayed.obj"],
                       capture_output=True, text=True)
    replay = re.findall(r"checksum ([0-9a-f]{16})", r.stdout)
    print("model %s: reference %s, station %s, display %s, replay %s" %
          (a.model, ref, station, display, replay))
    for name, got in (("station", station), ("display", display), ("replay", replay)):
        if got[-1:] != [ref]:
            problems.append("%s checksum %s, reference %s" % (name, got, ref))
    m = re.search(r"poses: applied (\d+), conversion errors (\d+)", slog)
    if not m or int(m.group(2)) != 0:
        problems.append("poses line: %s" % (m.group(0) if m else "missing"))
    names = {"fastrak": "FASTRAK", "liberty": "Liberty", "patriot": "Patriot"}
    found = r"tracker: streaming \(start-up #1\): %s found on serial " % names[a.model]
    if not re.search(found, slog):
        problems.append("no line saying the %s was found" % names[a.model])
    commits = len(re.findall(r"committed as journal record", slog))
    if commits != a.commits:
        problems.append("%d commits, the scenario has %d strokes" % (commits, a.commits))
    for p in problems:
        print("PROBLEM: " + p)
    print("pty e2e: %s" % ("ok" if not problems else "FAILED\n" + slog))
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
