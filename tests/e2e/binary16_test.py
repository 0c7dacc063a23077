#!/usr/bin/env python3
"""[tracker] format = "binary16" end to end through twister-station (issue 23).

One scenario run twice by the real station on its in-process simulated Fastrak in
virtual time: once with format = "binary" (IEEE floats), once with "binary16" (the
16-bit packed records: the station sends `f`, the simulated unit answers packed).
Both journals are replayed by `twister replay` into meshes, which are compared
vertex by vertex: the same strokes commit (same journal record count) and every
vertex agrees within the 16-bit format's precision, bound = commits x (position
step + 2 x quaternion step x model diagonal), with the steps of fastrak-protocol.md
§3.4 (65.48 in / 32768 = 0.0508 mm, 1 / 32767). Checksums differ by design (the
quantisation); this is the comparison "within the format's precision".

    binary16_test.py SCENARIO --bin BUILD/bin --out DIR
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "sim", "scenarios"))
import run_scenario  # noqa: E402

POSITION_STEP_M = 65.48 * 0.0254 / 32768.0
QUATERNION_STEP = 1.0 / 32767.0


def run_station(exe, scenario, h, out, fmt):
    os.makedirs(out)
    subprocess.run([exe("twister"), "mesh"] + h["mesh"].split() +
                   ["--out", os.path.join(out, "start.obj")], check=True,
                   stdout=subprocess.DEVNULL)
    cfg = run_scenario.write_config(out, scenario, h, "virtual")
    text = open(cfg).read().replace("[tracker]\n", '[tracker]\nformat = "%s"\n' % fmt, 1)
    open(cfg, "w").write(text)
    r = subprocess.run([exe("twister-station"), "--config", cfg, "--log-level", "info"],
                       capture_output=True, text=True)
    open(os.path.join(out, "station.log"), "w").write(r.stdout + r.stderr)
    if r.returncode != 0:
        sys.exit("binary16_test: the %s station failed (%d):\n%s" % (fmt, r.returncode,
                                                                    r.stderr[-2000:]))
    rep = subprocess.run([exe("twister"), "replay", os.path.join(out, "journal.twj"), "--mesh",
                          os.path.join(out, "start.obj"), "--out",
                          os.path.join(out, "replayed.obj")] + h["replay"].split(),
                         capture_output=True, text=True)
    if rep.returncode != 0:
        sys.exit("binary16_test: replay of the %s journal failed:\n%s" % (fmt, rep.stderr))
    # One line per hand of a commit, all naming its record: count the records.
    commits = len(set(re.findall(r"committed as journal record (\d+)", r.stdout + r.stderr)))
    return commits, run_scenario.read_obj(os.path.join(out, "replayed.obj"))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scenario")
    ap.add_argument("--bin", required=True)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    out = os.path.abspath(args.out)
    shutil.rmtree(out, ignore_errors=True)
    h = run_scenario.header(args.scenario)
    exe = lambda name: os.path.join(args.bin, name)  # noqa: E731
    commits, ieee = run_station(exe, args.scenario, h, os.path.join(out, "binary"), "binary")
    commits16, packed = run_station(exe, args.scenario, h, os.path.join(out, "binary16"),
                                    "binary16")
    lo = [min(v[i] for v in ieee) for i in range(3)]
    hi = [max(v[i] for v in ieee) for i in range(3)]
    diagonal = math.dist(lo, hi)
    bound = max(commits, 1) * (POSITION_STEP_M + 2.0 * QUATERNION_STEP * diagonal)
    worst = max(math.dist(a, b) for a, b in zip(ieee, packed)) if len(ieee) == len(packed) else -1
    print("commits: binary %d, binary16 %d; vertices %d / %d; largest difference %.4f mm, "
          "bound %.4f mm" % (commits, commits16, len(ieee), len(packed), worst * 1e3, bound * 1e3))
    # worst > 0: the binary16 run did get the packed records (quantised poses).
    ok = commits > 0 and commits == commits16 and len(ieee) == len(packed) and 0 < worst <= bound
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
