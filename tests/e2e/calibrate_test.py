#!/usr/bin/env python3
"""`twister calibrate` end to end (issue 23): touch three points, sculpt, export upright.

1. twister-sim serves a stylus (receiver 1, its tip 5 cm along its own x axis) that
   rests on three points of a table 0.30 m below the transmitter (+Z down): the
   origin, a point on the model's +X, a point in its +Y half-plane (not on the
   perpendicular: calibrate makes y perpendicular). `twister fastrak-dump` records the
   poses over the PTY, as on a rig.
2. `twister calibrate --file POSES --tip-offset 0.05,0,0 --rest-poses 30` prints the
   work frame; it must match the touched points (origin within 2 mm, axes within 0.01).
   Too-close or collinear points are refused (exit 2).
3. twister-station, in virtual time on its in-process simulator, with the snippet and
   the tip offset in [tracker.calibration]: a box standing on the model's origin
   (twister mesh box: half size 0.05 m, z from 0 to 0.10 m) is grabbed at its top by the stylus where it
   stands on the table, and pulled 5 cm physically up (the transmitter's -Z). The
   journal replayed by `twister replay` is the export: its bounding box must stand
   upright at the origin (bottom at z = 0, centred on x = y = 0, top raised by the
   pull, within 5 mm), where the transmitter frame would have it 0.5 m off, +Z down.

    calibrate_test.py --bin BUILD/bin --out DIR
"""
import argparse
import math
import os
import shutil
import signal
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "sim", "scenarios"))
sys.path.insert(0, os.path.join(HERE, "..", "soak"))
import run_scenario  # noqa: E402
from soak_support import Proc, wait_for_line  # noqa: E402

INCH = 0.0254
TIP = 0.05  # metres along the stylus's x axis
# The stylus's attitude: az 0, el -60 (its x axis points forward and down, +Z).
AZ, EL = 0.0, -60.0
STYLUS_X = (math.cos(math.radians(EL)), 0.0, -math.sin(math.radians(EL)))
ORIGIN = (0.50, 0.00, 0.30)
X_DIR = (0.6, 0.8, 0.0)
UP = (0.0, 0.0, -1.0)
Y_DIR = (0.8, -0.6, 0.0)  # UP x X_DIR: X x Y = UP
add = lambda a, b: tuple(x + y for x, y in zip(a, b))  # noqa: E731
mul = lambda s, a: tuple(s * x for x in a)  # noqa: E731
X_POINT = add(ORIGIN, mul(0.20, X_DIR))
Y_POINT = add(add(ORIGIN, mul(0.15, Y_DIR)), mul(0.05, X_DIR))


def key(t, station, tip, az=AZ, el=EL):
    """A scenario key frame putting the stylus tip at `tip` (metres)."""
    receiver = add(tip, mul(-TIP, STYLUS_X))
    return "key %g %d %.4f %.4f %.4f %g %g 0\n" % ((t, station) + mul(1 / INCH, receiver) +
                                                   (az, el))


def record_touches(exe, out):
    scn = os.path.join(out, "touches.scn")
    open(scn, "w").write(
        "# The stylus rests on the origin, the +X point and the +Y point in turn.\n"
        "receivers 1\nduration 30\n" +
        key(0, 1, ORIGIN) + key(4, 1, ORIGIN) + key(4.5, 1, X_POINT) + key(6.5, 1, X_POINT) +
        key(7, 1, Y_POINT))
    link = os.path.join(out, "fastrak")
    sim = Proc([exe("twister-sim"), "--scenario", scn, "--link", link, "--command-time", "all=0",
                "--reset-time", "0.5"],
               os.path.join(out, "sim.log"), stdout_pipe=True)
    if wait_for_line(sim.popen.stdout, 10.0) is None:
        sys.exit("calibrate e2e: twister-sim printed no link path")
    poses = os.path.join(out, "poses.txt")
    with open(poses, "w") as f:
        r = subprocess.run([exe("twister"), "fastrak-dump", link, "-O", "1,2,11,1", "-f",
                            "--quick", "--seconds", "9"], stdout=f, stderr=subprocess.PIPE,
                           text=True, timeout=60)
    sim.stop(signal.SIGTERM)
    if r.returncode != 0:
        sys.exit("calibrate e2e: fastrak-dump failed (%d):\n%s" % (r.returncode, r.stderr))
    return poses


def calibrate(exe, poses):
    r = subprocess.run([exe("twister"), "calibrate", "--file", poses, "--tip-offset",
                        "%g,0,0" % TIP, "--rest-poses", "30"], capture_output=True, text=True)
    print(r.stdout + r.stderr, end="")
    if r.returncode != 0:
        sys.exit("calibrate e2e: twister calibrate failed (%d)" % r.returncode)
    values = {}
    for line in r.stdout.splitlines():
        if "=" in line and not line.startswith("#"):
            k, v = line.split("=")
            values[k.strip()] = tuple(float(x) for x in v.strip(" []").split(","))
    problems = []
    for name, got, want, tol in (("origin", values["origin"], ORIGIN, 0.002),
                                 ("x_axis", values["x_axis"], X_DIR, 0.01),
                                 ("y_axis", values["y_axis"], Y_DIR, 0.01)):
        miss = math.dist(got, want)
        print("check %s: %.4f from the touched frame (tolerance %g) %s"
              % (name, miss, tol, "ok" if miss <= tol else "FAILED"))
        if miss > tol:
            problems.append(name)
    return r.stdout, problems


def sculpt(exe, out, snippet):
    """The stroke on the calibrated station; the replayed mesh's vertices."""
    top = add(ORIGIN, mul(0.10, UP))  # the box's top centre where it stands
    pulled = add(top, mul(0.05, UP))
    away = (0.45, 0.30, 0.20)  # receiver 2, idle
    scn = os.path.join(out, "pull.scn")
    open(scn, "w").write(
        "receivers 2\nduration 9\n" + key(0, 1, top) + key(5, 1, top) + key(6.5, 1, pulled) +
        key(9, 1, pulled) + key(0, 2, away, 0, 0) + "button 4 0 1\nbutton 8 0 0\n")
    subprocess.run([exe("twister"), "mesh", "box", "-n", "6", "--size", "0.05", "--center", "0",
                    "0", "0.05", "--out", os.path.join(out, "start.obj")], check=True,
                   stdout=subprocess.DEVNULL)
    h = {"mesh": "box", "sculpt": ["radius_m = 0.08", "refine = false"], "station": [],
         "toml": ["[tracker.calibration]", "tip_offset = [%g, 0, 0]" % TIP] +
         snippet.splitlines(), "buttons": "sim"}
    cfg = run_scenario.write_config(out, scn, h, "virtual")
    r = subprocess.run([exe("twister-station"), "--config", cfg, "--log-level", "info"],
                       capture_output=True, text=True, timeout=120)
    open(os.path.join(out, "station.log"), "w").write(r.stdout + r.stderr)
    if r.returncode != 0:
        sys.exit("calibrate e2e: the station failed (%d):\n%s" % (r.returncode, r.stderr[-3000:]))
    commits = r.stdout.count("committed as journal record") + r.stderr.count(
        "committed as journal record")
    rep = subprocess.run([exe("twister"), "replay", os.path.join(out, "journal.twj"), "--mesh",
                          os.path.join(out, "start.obj"), "--out",
                          os.path.join(out, "replayed.obj")], capture_output=True, text=True)
    if rep.returncode != 0:
        sys.exit("calibrate e2e: replay failed:\n" + rep.stderr)
    return commits, run_scenario.read_obj(os.path.join(out, "replayed.obj"))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    out = os.path.abspath(a.out)
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    exe = lambda name: os.path.join(a.bin, name)  # noqa: E731
    poses = record_touches(exe, out)
    snippet, problems = calibrate(exe, poses)
    # A +Y point on the X line, and a +X point too close: refused with the reason (exit 2).
    for points, reason in ((["0.5,0,0.3", "0.7,0,0.3", "0.9,0.001,0.3"], "from the X axis"),
                           (["0.5,0,0.3", "0.51,0,0.3", "0.5,0.2,0.3"], "from the origin")):
        r = subprocess.run([exe("twister"), "calibrate"] +
                           [a for p in points for a in ("--point", p)], capture_output=True,
                           text=True)
        ok = r.returncode == 2 and reason in r.stderr
        print("check refused (%s): %s %s" % (reason, r.stderr.strip(), "ok" if ok else "FAILED"))
        if not ok:
            problems.append("refusal " + reason)
    commits, v = sculpt(exe, out, snippet)
    lo = [min(p[i] for p in v) for i in range(3)]
    hi = [max(p[i] for p in v) for i in range(3)]
    print("export bounding box: x %.4f..%.4f, y %.4f..%.4f, z %.4f..%.4f m; commits %d"
          % (lo[0], hi[0], lo[1], hi[1], lo[2], hi[2], commits))
    checks = (("one commit", commits >= 1),
              ("bottom on z = 0", abs(lo[2]) <= 0.005),
              ("centred on x = 0", abs(lo[0] + hi[0]) / 2 <= 0.005),
              ("centred on y = 0", abs(lo[1] + hi[1]) / 2 <= 0.005),
              ("top pulled up 5 cm", abs(hi[2] - 0.15) <= 0.005))
    for name, ok in checks:
        print("check %s: %s" % (name, "ok" if ok else "FAILED"))
        if not ok:
            problems.append(name)
    print("calibrate e2e: %s" % ("ok" if not problems else "FAILED: " + ", ".join(problems)))
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
