#!/usr/bin/env python3
"""Runs one scenario of sim/scenarios/ through the real programs.

The scenario's header names its start mesh and station settings:
  # @mesh ARGS        `twister mesh ARGS --out OUT/start.obj`
  # @sculpt KEY = V   a line of the station's [sculpt] section (repeatable)
  # @station KEY = V  a line of its [station] section (repeatable)
  # @toml LINE       a line appended to the station config (e.g. [sculpt.buttons.right])
  # @view ARGS        twister-bridge camera options
  # @buttons stylus  the receiver-1 stylus instead of the scripted button lines
  # @replay ARGS      `twister replay` options (e.g. --spare-vertices N with refinement)
  # @expect-vertex X Y Z -> X' Y' Z' TOL
                    the start vertex nearest X Y Z (metres) ends within TOL of X' Y' Z'
                    in the replayed mesh (a grab point follows its hand exactly)
  # @expect-turn X Y Z -> X' Y' Z' AXIS DEG TOL
                    the start vertices 3 to 12 mm around X Y Z, seen from X' Y' Z' in the
                    replayed mesh, turned by DEG degrees (either sense) about AXIS x|y|z,
                    within TOL degrees (median): the hand's turn reached the surface
twister-station plays it (in-process simulated Fastrak with scripted buttons,
virtual time unless --time real) and, with --bridge, serves a Unix-socket link to
twister-bridge --offscreen, which writes PNG snapshots and exports the final mesh.
Then `twister replay` rebuilds the model from the journal.

    run_scenario.py SCENARIO --bin BUILD/bin --out DIR [--bridge] [--time real]
With --spectators N, N more twister-bridge --spectator displays connect beside the
main one (issue 25) and each prints `spectator-K CHECKSUM`.
Prints `station CHECKSUM`, `display CHECKSUM` (with --bridge), `replay CHECKSUM`
and the station's counters line; exit 0 when the programs succeeded and all
printed checksums agree (the caller compares them with other runs).
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import time


def header(path):
    h = {"mesh": None, "sculpt": [], "station": [], "toml": [], "view": "", "replay": "", "buttons": "sim",
         "expect": []}
    for line in open(path):
        m = re.match(r"#\s*@([\w-]+)\s+(.*)$", line.strip())
        if m and m.group(1) in ("expect-vertex", "expect-turn"):
            h["expect"].append((m.group(1), m.group(2)))
        if m and m.group(1) in ("mesh", "view", "replay", "buttons"):
            h[m.group(1)] = m.group(2)
        elif m and m.group(1) in ("sculpt", "station", "toml"):
            h[m.group(1)].append(m.group(2))
    if not h["mesh"]:
        sys.exit("run_scenario: %s names no @mesh" % path)
    return h


def write_config(out, scenario, h, time_mode):
    cfg = os.path.join(out, "station.toml")
    text = ('[station]\njournal = "%s/journal.twj"\nmesh = "%s/start.obj"\n%s\n'
            '[tracker]\nbackend = "sim"\nleft_station = 1\nright_station = 2\n'
            '[tracker.sim]\nscenario_file = "%s"\ntime = "%s"\n'
            '[buttons]\nbackend = "%s"\ndebounce_ms = 10\n'
            '[systemd]\nnotify = false\nwatchdog = false\n'
            % (out, out, "\n".join(h["station"]), os.path.abspath(scenario), time_mode,
               h["buttons"]))
    if h["sculpt"]:
        text += "[sculpt]\n" + "\n".join(h["sculpt"]) + "\n"
    text += "".join(line + "\n" for line in h["toml"])
    open(cfg, "w").write(text)
    return cfg


def cut_link(out, bridge_cmd, env):
    """A first display, SIGKILLed once the station committed its first stroke: the
    final display then connects to a station whose link lost its peer."""
    with open(os.path.join(out, "bridge-cut.log"), "w") as log:
        first = subprocess.Popen(bridge_cmd, env=env, stdout=log, stderr=log)
        found = False
        for _ in range(1200):
            text = open(os.path.join(out, "station.log")).read()
            if "committed as journal record 0" in text or "stopped (" in text:
                found = True
                break
            time.sleep(0.05)
        first.kill()
        first.wait()
    if not found:
        sys.exit("run_scenario: no commit to cut the link after")


def read_obj(path):
    return [tuple(float(c) for c in line.split()[1:4]) for line in open(path)
            if line.startswith("v ")]


def check_expectations(expect, start_path, final_path):
    """The scenario's @expect-vertex / @expect-turn lines; returns failure messages."""
    if not expect:
        return []
    start, final = read_obj(start_path), read_obj(final_path)
    sub = lambda a, b: tuple(x - y for x, y in zip(a, b))  # noqa: E731
    norm = lambda a: math.sqrt(sum(x * x for x in a))  # noqa: E731
    fails = []
    for kind, text in expect:
        f = text.replace("->", " ").split()
        grab, end = tuple(map(float, f[0:3])), tuple(map(float, f[3:6]))
        i = min(range(len(start)), key=lambda k: norm(sub(start[k], grab)))
        if kind == "expect-vertex":
            miss = norm(sub(final[i], end))
            ok = miss <= float(f[6])
            print("check vertex %d: %.4f m from the hand's end point (tolerance %s) %s"
                  % (i, miss, f[6], "ok" if ok else "FAILED"))
            if not ok:
                fails.append(text)
            continue
        axis, deg, tol = "xyz".index(f[6]), float(f[7]), float(f[8])
        a, b = [k for k in range(3) if k != axis]
        turns = []
        for k, q in enumerate(start):
            d = norm(sub(q, start[i]))
            u, v = sub(q, start[i]), sub(final[k], final[i])
            # around the axis: those straight along it (or nearly) show no turn
            if 0.003 <= d <= 0.012 and math.hypot(u[a], u[b]) >= 0.3 * d:
                turn = math.degrees(math.atan2(u[a] * v[b] - u[b] * v[a], u[a] * v[a] + u[b] * v[b]))
                turns.append(abs(turn))
        turns.sort()
        got = turns[len(turns) // 2] if turns else float("nan")
        ok = abs(got - deg) <= tol
        print("check turn about %s near vertex %d: %.1f degrees (%d vertices; expected %g +- %g) %s"
              % (f[6], i, got, len(turns), deg, tol, "ok" if ok else "FAILED"))
        if not ok:
            fails.append(text)
    return fails


def checksum(pattern, text):
    m = re.findall(pattern, text, re.M)
    return m[-1] if m else None


def bridge_command(args, exe, out, sock, view):
    """twister-bridge's command line and environment: offscreen unless --window."""
    env = dict(os.environ)
    mode = []
    if not args.window:
        env["EGL_PLATFORM"] = "surfaceless"
        env.pop("DISPLAY", None)
        env.pop("WAYLAND_DISPLAY", None)
        mode = ["--offscreen"]
    cmd = [exe("twister-bridge"), "--connect", "unix:" + sock] + mode + [
        "--size", args.size, "--snapshots", os.path.join(out, "pictures"),
        "--export", os.path.join(out, "final.glb"), "--exit-on-disconnect",
        "--timeout", "120"] + view.split() + (["--no-cues", "--no-hud"] if args.plain else
                                              ["--no-hud"] if args.no_hud else []) + (
        ["--movie-every", str(args.movie_every)] if args.movie_every else [])
    return cmd, env


def follow(out, procs, strokes):
    """Waits for the processes; with strokes > 0 prints each commit as it happens."""
    shown = set()
    while any(p.poll() is None for p in procs):
        if strokes:
            text = open(os.path.join(out, "station.log"), errors="replace").read()
            for n in re.findall(r"committed as journal record (\d+)", text):
                if n not in shown:
                    shown.add(n)
                    print("  stroke %d of %d committed (journal record %s)"
                          % (len(shown), strokes, n), flush=True)
        time.sleep(0.1)


def run_programs(args, h, out, exe):
    """Station (and bridge); returns their exit codes (bridge: None without one)."""
    cfg = write_config(out, args.scenario, h, args.time)
    station_cmd = [exe("twister-station"), "--config", cfg, "--log-level", "info"]
    sock = os.path.join(out, "link.sock")
    if args.bridge:
        station_cmd += ["--link", "unix:" + sock, "--link-wait", "30"]
        bridge_cmd, env = bridge_command(args, exe, out, sock, h["view"])
    procs = []
    try:
        with open(os.path.join(out, "station.log"), "w") as slog:
            procs.append(subprocess.Popen(station_cmd, stdout=slog, stderr=subprocess.STDOUT))
            if args.bridge and args.cut_link:
                cut_link(out, bridge_cmd[:3] + ["--offscreen", "-q"], env)
            if args.bridge:
                with open(os.path.join(out, "bridge.log"), "w") as blog, \
                        open(os.path.join(out, "pictures.txt"), "w") as pics:
                    procs.append(subprocess.Popen(bridge_cmd, env=env, stdout=pics,
                                                  stderr=blog))
            for k in range(args.spectators if args.bridge else 0):
                procs.append(start_spectator(out, k, bridge_cmd, env))
            follow(out, procs, args.progress)
    finally:
        for p in procs:
            if p.poll() is None:
                p.kill()
                p.wait()
    return procs[0].returncode, [p.returncode for p in procs[1:]] or None


def start_spectator(out, k, bridge_cmd, env):
    """A read-only display (twister-bridge --spectator, issue 25) with its own export and
    log (spectator-K.log); no pictures (the main display's are the run's)."""
    cmd = list(bridge_cmd) + ["--spectator"]
    i = cmd.index("--snapshots")
    del cmd[i:i + 2]
    cmd[cmd.index("--export") + 1] = os.path.join(out, "final-spectator-%d.glb" % k)
    with open(os.path.join(out, "spectator-%d.log" % k), "w") as log:
        return subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=log)


def run(args):
    out = os.path.abspath(args.out)
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(os.path.join(out, "pictures"))
    h = header(args.scenario)
    exe = lambda name: os.path.join(args.bin, name)  # noqa: E731
    subprocess.run([exe("twister"), "mesh"] + h["mesh"].split() +
                   ["--out", os.path.join(out, "start.obj")], check=True,
                   stdout=subprocess.DEVNULL)
    station_rc, bridge_rcs = run_programs(args, h, out, exe)
    stext = open(os.path.join(out, "station.log")).read()
    result = {"station": checksum(r"^twister-station: mesh checksum ([0-9a-f]+)$", stext)}
    ok = station_rc == 0
    exported = r"exported mesh version \d+ \(checksum ([0-9a-f]+)\)"
    if bridge_rcs is not None:
        btext = open(os.path.join(out, "bridge.log")).read()
        result["display"] = checksum(exported, btext)
        ok = ok and all(rc == 0 for rc in bridge_rcs)
        for k in range(len(bridge_rcs) - 1):
            text = open(os.path.join(out, "spectator-%d.log" % k)).read()
            result["spectator-%d" % k] = checksum(exported, text)
    r = subprocess.run([exe("twister"), "replay", os.path.join(out, "journal.twj"), "--mesh",
                        os.path.join(out, "start.obj"), "--out",
                        os.path.join(out, "replayed.obj")] + h["replay"].split(),
                       capture_output=True, text=True)
    result["replay"] = checksum(r"checksum ([0-9a-f]{16})", r.stdout)
    for k, v in result.items():
        print("%s %s" % (k, v))
    summary = [ln for ln in stext.splitlines() if "stopped (" in ln]
    print(summary[-1] if summary else "station: no summary")
    if result["replay"]:
        ok = not check_expectations(h["expect"], os.path.join(out, "start.obj"),
                                    os.path.join(out, "replayed.obj")) and ok
    return ok and len(set(result.values())) == 1 and None not in result.values()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scenario")
    ap.add_argument("--bin", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--bridge", action="store_true")
    ap.add_argument("--time", default="virtual", choices=["virtual", "real"])
    ap.add_argument("--size", default="640x480")
    ap.add_argument("--window", action="store_true",
                    help="with --bridge: a window on $DISPLAY instead of offscreen")
    ap.add_argument("--progress", type=int, default=0, metavar="STROKES",
                    help="print each commit as 'stroke k of STROKES' while it runs")
    ap.add_argument("--plain", action="store_true",
                    help="snapshots of the model alone (twister-bridge --no-cues --no-hud)")
    ap.add_argument("--no-hud", action="store_true",
                    help="snapshots with the cues but without the heads-up text")
    ap.add_argument("--movie-every", type=int, default=0, metavar="N",
                    help="with --bridge: also frame-<n>.png every N-th hands update")
    ap.add_argument("--spectators", type=int, default=0, metavar="N",
                    help="with --bridge: N read-only displays (--spectator) beside the main one")
    ap.add_argument("--cut-link", action="store_true",
                    help="with --bridge: a first display is killed after the first commit")
    args = ap.parse_args()
    sys.exit(0 if run(args) else 1)


if __name__ == "__main__":
    main()
