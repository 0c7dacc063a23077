#!/usr/bin/env python3
"""Soak test of the whole chain (issue 16): twister-sim on a PTY -> twister-station
-> Unix-socket link -> twister-bridge (offscreen), for --minutes of real time.

Faults: every tracker fault of the scenario (noise, drop, truncate, corrupt, stall,
wrong baud, hang-up = unplug; soak_scenario.py), stylus button bounce at every press
and release, link cuts (the bridge is SIGKILLed at random and started again) and
station crashes (SIGKILL at random, restarted on the same journal). The RSS of the
station, the bridge and the simulator is sampled every --sample seconds.

Checks:
  * nothing committed is lost: every "committed as journal record N" line any station
    life printed is a record of the journal; the journal is never corrupt;
  * every restart starts from the model `twister replay` builds from the journal, and
    the last station's "mesh checksum" at its clean stop (SIGTERM) equals it too;
  * memory stays flat: per process kind, the largest RSS of the last quarter of the
    samples is at most the largest of the first quarter + max(4 MiB, 10 %).

    soak.py --bin BUILD/bin --deploy DIR --minutes M [--out DIR] [--seed N]
Prints progress, a summary line and writes OUT/result.json. Exit 0 when all held.
"""
import argparse
import json
import os
import random
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "hal", "twister-station"))
import soak_scenario  # noqa: E402
from crash_test import journal_sequences, replay_checksum  # noqa: E402
from soak_support import Proc, commits_in, rss_kib, start_checksum, wait_for_line  # noqa: E402


class Soak:
    def __init__(self, args):
        self.args = args
        self.rng = random.Random(args.seed)
        self.out = os.path.abspath(args.out)
        os.makedirs(self.out, exist_ok=True)
        self.journal = os.path.join(self.out, "journal.twj")
        self.mesh = os.path.join(os.path.abspath(args.deploy), "sim_sphere.obj")
        self.link = os.path.join(self.out, "fastrak")
        self.sock = os.path.join(self.out, "link.sock")
        self.samples = []  # (t, kind, rss KiB)
        self.problems = []
        self.kills = self.link_cuts = self.lives = self.printed = self.lost = 0
        self.station = self.bridge = self.sim = None
        for f in (self.journal, self.journal + ".ckpt", self.link, self.sock):
            if os.path.lexists(f):
                os.unlink(f)

    def exe(self, name):
        return os.path.join(self.args.bin, name)

    def write_inputs(self, duration):
        text, self.faults, self.strokes = soak_scenario.scenario(
            self.rng, duration, self.args.fault_cycle)
        self.scenario = os.path.join(self.out, "soak.scn")
        open(self.scenario, "w").write(text)
        self.config = os.path.join(self.out, "station.toml")
        open(self.config, "w").write(
            '[station]\njournal = "%s"\nmesh = "%s"\ncheckpoint_interval = 16\n'
            '[tracker]\nbackend = "serial"\nreconnect_interval_ms = 200\n'
            '[tracker.serial]\ndevice = "%s"\n[buttons]\nbackend = "stylus"\n'
            'debounce_ms = 30\n[systemd]\nnotify = false\nwatchdog = false\n'
            % (self.journal, self.mesh, self.link))

    def start_sim(self, duration):
        log = os.path.join(self.out, "sim.log")
        self.sim = Proc([self.exe("twister-sim"), "--scenario", self.scenario, "--link",
                         self.link, "--reset-time", "0.5", "--duration", "%g" % duration], log, stdout_pipe=True)
        if wait_for_line(self.sim.popen.stdout, 10.0) is None:
            raise SystemExit("soak: twister-sim printed no link path")

    def start_station(self):
        self.expected = replay_checksum(self.exe("twister"), self.journal, self.mesh,
                                        os.path.join(self.out, "replayed.obj"))
        self.lives += 1
        log = os.path.join(self.out, "station-%03d.log" % self.lives)
        self.station = Proc([self.exe("twister-station"), "--config", self.config,
                             "--log-level", "info", "--link", "unix:" + self.sock], log)

    def start_bridge(self):
        env = dict(os.environ, EGL_PLATFORM="surfaceless")
        env.pop("DISPLAY", None)
        env.pop("WAYLAND_DISPLAY", None)
        self.bridge = Proc([self.exe("twister-bridge"), "--connect", "unix:" + self.sock,
                            "--offscreen", "--size", "160x120", "-q"],
                           os.path.join(self.out, "bridge.log"), env=env, append=True)

    def end_station_life(self, sig):
        """Stop (SIGKILL or SIGTERM) the station and check what its life printed."""
        self.station.stop(sig)
        text = self.station.text()
        started = start_checksum(text)
        if started is not None and self.expected and started != self.expected:
            self.problems.append("life %d started from %s, replay gives %s"
                                 % (self.lives, started, self.expected))
        seqs, _ = journal_sequences(self.journal)
        committed = commits_in(text)
        self.printed += len(committed)
        lost = sorted(committed - set(seqs))
        self.lost += len(lost)
        if lost:
            self.problems.append("life %d: committed records lost: %s" % (self.lives, lost))
        r = subprocess.run([self.exe("twister"), "journal", "check", self.journal],
                           capture_output=True, text=True)
        if "verdict: corrupt" in r.stdout:
            self.problems.append("life %d: corrupt journal\n%s" % (self.lives, r.stdout))
        return text

    def sample(self, t):
        for kind, proc in (("station", self.station), ("bridge", self.bridge),
                           ("sim", self.sim)):
            kib = rss_kib(proc.popen.pid) if proc and proc.alive() else None
            if kib:
                self.samples.append((round(t, 1), kind, kib))

    def run(self):
        a = self.args
        duration = a.minutes * 60.0
        self.write_inputs(duration + 30.0)
        self.start_sim(duration + 30.0)
        self.start_station()
        self.start_bridge()
        t0 = time.monotonic()
        next_kill = self.rng.uniform(*a.kill_every)
        next_cut = self.rng.uniform(*a.cut_every)
        next_sample = next_report = 0.0
        while (t := time.monotonic() - t0) < duration:
            if not self.sim.alive():
                raise SystemExit("soak: twister-sim ended early:\n" + self.sim.text())
            if not self.station.alive():
                self.problems.append("station life %d exited by itself (%s):\n%s"
                                     % (self.lives, self.station.popen.returncode,
                                        self.station.text()[-3000:]))
                self.end_station_life(signal.SIGKILL)
                self.start_station()
            if t >= next_kill:
                self.end_station_life(signal.SIGKILL)
                self.kills += 1
                self.start_station()
                next_kill = t + self.rng.uniform(*a.kill_every)
            if t >= next_cut:
                self.bridge.stop(signal.SIGKILL)
                self.link_cuts += 1
                self.start_bridge()
                next_cut = t + self.rng.uniform(*a.cut_every)
            if t >= next_sample:
                self.sample(t)
                next_sample = t + a.sample
            if t >= next_report:
                print("soak: %5.0f s: %d station lives, %d kills, %d link cuts, %d commits"
                      " printed, %d problems" % (t, self.lives, self.kills, self.link_cuts,
                                                 self.printed, len(self.problems)), flush=True)
                next_report = t + a.report
            time.sleep(0.2)
        return self.finish(time.monotonic() - t0)

    def finish(self, elapsed):
        text = self.end_station_life(signal.SIGTERM)
        self.bridge.stop(signal.SIGTERM)
        self.sim.stop(signal.SIGTERM)
        final = replay_checksum(self.exe("twister"), self.journal, self.mesh,
                                os.path.join(self.out, "replayed.obj"))
        stopped = [ln.split()[-1] for ln in text.splitlines()
                   if ln.startswith("twister-station: mesh checksum ")]
        if not stopped or stopped[-1] != final:
            self.problems.append("final station checksum %s, replay %s" % (stopped, final))
        seqs, _ = journal_sequences(self.journal)
        if self.printed < self.args.min_commits:
            self.problems.append("only %d commits printed (at least %d expected)"
                                 % (self.printed, self.args.min_commits))
        result = {"seconds": round(elapsed, 1), "station_lives": self.lives,
                  "station_kills": self.kills, "link_cuts": self.link_cuts,
                  "tracker_faults": self.faults_before(elapsed),
                  "button_bounces": 2 * min(self.strokes, int(elapsed / 3.0)),
                  "commits_printed": self.printed, "journal_records": len(seqs),
                  "checksum": final, "rss": self.rss_report(),
                  "problems": self.problems}
        result["lost"] = self.lost
        json.dump(result, open(os.path.join(self.out, "result.json"), "w"), indent=1)
        return result

    def faults_before(self, elapsed):
        counts = {}
        for t, kind, _ in self.faults:
            if t < elapsed:
                counts[kind] = counts.get(kind, 0) + 1
        return counts

    def rss_report(self):
        """Per kind: first, last, max RSS (MiB); problem when the last quarter grew."""
        report = {}
        for kind in ("station", "bridge", "sim"):
            s = [(t, k) for t, kk, k in self.samples if kk == kind]
            if len(s) < 8:
                continue
            q = len(s) // 4
            first_max = max(k for _, k in s[:q])
            last_max = max(k for _, k in s[-q:])
            report[kind] = {"first_mib": round(s[0][1] / 1024, 1),
                            "last_mib": round(s[-1][1] / 1024, 1),
                            "max_mib": round(max(k for _, k in s) / 1024, 1),
                            "first_quarter_max_mib": round(first_max / 1024, 1),
                            "last_quarter_max_mib": round(last_max / 1024, 1),
                            "samples": len(s)}
            if last_max > first_max + max(4096, first_max // 10):
                self.problems.append("%s RSS grew: first quarter max %d KiB, last %d KiB"
                                     % (kind, first_max, last_max))
        return report


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True, help="folder with twister-sim, twister-station, "
                    "twister-bridge and twister")
    ap.add_argument("--deploy", required=True)
    ap.add_argument("--minutes", type=float, default=60.0)
    ap.add_argument("--out", default="/tmp/twister-soak")
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--fault-cycle", type=float, default=120.0,
                    help="each tracker fault kind once per this many seconds")
    ap.add_argument("--kill-every", type=float, nargs=2, default=[120.0, 360.0])
    ap.add_argument("--cut-every", type=float, nargs=2, default=[30.0, 90.0])
    ap.add_argument("--sample", type=float, default=5.0)
    ap.add_argument("--report", type=float, default=60.0)
    ap.add_argument("--min-commits", type=int, default=1)
    args = ap.parse_args()
    soak = Soak(args)
    try:
        r = soak.run()
    finally:
        for p in (soak.station, soak.bridge, soak.sim):
            if p:
                p.stop(signal.SIGKILL)
    print("soak: %.0f s, %d station kills, %d link cuts, tracker faults %s, %d button "
          "bounces, %d commits printed, %d journal records, lost %d, RSS %s"
          % (r["seconds"], r["station_kills"], r["link_cuts"], r["tracker_faults"],
             r["button_bounces"], r["commits_printed"], r["journal_records"], r["lost"],
             json.dumps(r["rss"])))
    for p in r["problems"]:
        print("PROBLEM: " + p)
    sys.exit(0 if not r["problems"] else 1)


if __name__ == "__main__":
    main()
