#!/usr/bin/env python3
"""Crash test of twister-station (issue 11): SIGKILL at random points of a scripted
session, restart, repeat.

Each round starts the station on the same journal (simulator in virtual time, freeze
chains with both hands' buttons, a checkpoint every 3 records), kills it with SIGKILL
after a random delay spread over its whole life (start-up and recovery, strokes and
appends, in-loop checkpoints, the final checkpoint at stop), then checks:
  * no committed stroke is lost: every "committed as journal record N" line the
    station printed before it died is a record of the journal (sequence N);
  * the journal is never corrupt (at most a torn tail, which the next start cuts);
  * every restart works (never a refusal), and the model it starts from (the "mesh
    ... checksum" line, from the checkpoint plus the records after it) equals what
    `twister replay` builds from the whole journal.
A last round runs to the end and must exit 0.

    crash_test.py --station BIN --cli BIN --deploy DIR [--kills 60] [--seed 1]
Prints one line per round and a summary: kills, lost committed strokes, refusals.
Exit 0 when there were 0 lost and 0 refusals.
"""
import argparse
import os
import random
import re
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time
import zlib


def chain_scenario(strokes, freezes):
    """Hand 1 (receiver 2) grabs (line 3), freezes (line 5) while twisting."""
    end = 3.0 + 3.0 * strokes + 1.0
    lines = ["seed 7", "receivers 2", "duration %g" % end,
             "key 0 1 11.81 -14.00 1.97 0 0 0", "key %g 1 11.81 -14.00 1.97 0 0 0" % end,
             "key 0 2 11.81 -3.15 1.97 0 0 0"]
    for k in range(strokes):
        t0 = 3.0 + 3.0 * k
        lines.append("key %g 2 11.81 -3.15 1.97 0 0 0" % t0)
        lines.append("button %g 3 1" % (t0 + 0.05))
        step = 2.0 / (freezes + 1)
        for f in range(1, freezes + 2):
            lines.append("key %g 2 11.81 %g 1.97 0 0 %d" % (t0 + step * f, -3.15 + 0.2 * f, 40 * f))
            if f <= freezes:
                lines.append("button %g 5 1" % (t0 + step * f + 0.05))
                lines.append("button %g 5 0" % (t0 + step * f + 0.15))
        lines.append("button %g 3 0" % (t0 + 2.2))
        lines.append("key %g 2 11.81 -3.15 1.97 0 0 0" % (t0 + 2.9))
    lines.append("key %g 2 11.81 -3.15 1.97 0 0 0" % end)
    return "\n".join(lines) + "\n"


def journal_sequences(path):
    """Sequences of the journal's good prefix, and whether damage follows it."""
    try:
        data = open(path, "rb").read()
    except FileNotFoundError:
        return [], False
    if len(data) < 8:
        return [], len(data) > 0
    # Format version 2 (docs/interaction.md): a 16-byte file header, the journal id
    # after each 8-byte record header; version 1: 8 and none.
    v2 = struct.unpack_from("<I", data, 4)[0] == 2
    if v2 and len(data) < 16:
        return [], True
    pos, seqs = (16 if v2 else 8), []
    head = 12 if v2 else 8
    while pos < len(data):
        if len(data) - pos < head:
            return seqs, True
        (length,) = struct.unpack_from("<I", data, pos)
        total = head + length + 4
        if length > 512 or len(data) - pos < total:
            return seqs, True
        (crc,) = struct.unpack_from("<I", data, pos + head + length)
        if zlib.crc32(data[pos:pos + head + length]) != crc:
            return seqs, True
        seqs.append(struct.unpack_from("<I", data, pos + head)[0])
        pos += total
    return seqs, False


def replay_checksum(cli, journal, mesh, out):
    r = subprocess.run([cli, "replay", journal, "--mesh", mesh, "--out", out, "--force", "-q"],
                       capture_output=True, text=True)
    m = re.search(r"checksum ([0-9a-f]{16})", r.stdout)
    return m.group(1) if m else None


def round_once(args, config, log_path, delay):
    with open(log_path, "w") as log:
        p = subprocess.Popen([args.station, "--config", config, "--log-level", "info"],
                             stdout=log, stderr=subprocess.STDOUT)
        if delay is None:
            return p.wait()
        time.sleep(delay)
        p.send_signal(signal.SIGKILL)
        p.wait()
        return p.returncode


def check_round(args, work, journal, mesh, log_text, problems):
    """The journal after a kill: every printed commit is in it; it is not corrupt."""
    seqs, damaged = journal_sequences(journal)
    on_disk = set(seqs)
    committed = {int(n) for n in re.findall(r"committed as journal record (\d+)", log_text)}
    lost = sorted(committed - on_disk)
    if lost:
        problems["lost"] += len(lost)
        print("  LOST committed records %s" % lost)
    r = subprocess.run([args.cli, "journal", "check", journal], capture_output=True, text=True)
    if "verdict: corrupt" in r.stdout:
        problems["corrupt"] += 1
        print("  CORRUPT journal:\n" + r.stdout)
    return len(seqs), damaged, len(committed)


def check_restart(args, mesh, journal, work, log_text, expected, problems):
    """A restart's log: it started (no refusal) from the model the journal builds."""
    if "refusing" in log_text or re.search(r"error: journal", log_text):
        problems["refusals"] += 1
        print("  REFUSED:\n" + log_text)
        return
    m = re.search(r"twister-station: mesh .*checksum ([0-9a-f]{16})", log_text)
    if m and expected and m.group(1) != expected:
        problems["mismatch"] += 1
        print("  MODEL MISMATCH at start: %s, replay gives %s" % (m.group(1), expected))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--station", required=True)
    ap.add_argument("--cli", required=True)
    ap.add_argument("--deploy", required=True)
    ap.add_argument("--kills", type=int, default=60)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--keep", action="store_true", help="keep the work folder")
    args = ap.parse_args()
    rng = random.Random(args.seed)
    work = tempfile.mkdtemp(prefix="twister_crash_")
    journal = os.path.join(work, "journal.twj")
    mesh = os.path.join(os.path.abspath(args.deploy), "sim_sphere.obj")
    scenario = os.path.join(work, "chains.scn")
    open(scenario, "w").write(chain_scenario(6, 3))
    config = os.path.join(work, "station.toml")
    open(config, "w").write(
        '[station]\njournal = "%s"\nmesh = "%s"\ncheckpoint_interval = 3\n'
        '[tracker]\nbackend = "sim"\n[tracker.sim]\nscenario_file = "%s"\ntime = "virtual"\n'
        '[buttons]\nbackend = "sim"\n[systemd]\nnotify = false\nwatchdog = false\n'
        % (journal, mesh, scenario))
    log_path = os.path.join(work, "log.txt")
    # How long one whole run lives, to spread the kills over it (and a bit beyond).
    t = time.monotonic()
    if round_once(args, config, log_path, None) != 0:
        print(open(log_path).read())
        sys.exit("crash_test: the uninterrupted run failed")
    life = time.monotonic() - t
    print("one uninterrupted run: %.3f s; %d kills at random points of it" % (life, args.kills))
    problems = {"lost": 0, "corrupt": 0, "refusals": 0, "mismatch": 0}
    expected = replay_checksum(args.cli, journal, mesh, os.path.join(work, "o.obj"))
    committed_total = 0
    for k in range(args.kills):
        delay = rng.uniform(0.0, life * 1.1)
        round_once(args, config, log_path, delay)
        text = open(log_path, errors="replace").read()
        check_restart(args, mesh, journal, work, text, expected, problems)
        records, damaged, committed = check_round(args, work, journal, mesh, text, problems)
        committed_total += committed
        expected = replay_checksum(args.cli, journal, mesh, os.path.join(work, "o.obj"))
        print("kill %3d at %.3f s: %d records on disk%s, %d commits printed"
              % (k + 1, delay, records, " + torn tail" if damaged else "", committed))
    rc = round_once(args, config, log_path, None)
    text = open(log_path).read()
    check_restart(args, mesh, journal, work, text, expected, problems)
    if rc != 0:
        problems["refusals"] += 1
        print("final run exit %d:\n%s" % (rc, text))
    print("crash test: %d kills, %d committed strokes printed before the kills, "
          "%d lost committed strokes, %d refusals, %d corrupt journals, %d model mismatches"
          % (args.kills, committed_total, problems["lost"], problems["refusals"],
             problems["corrupt"], problems["mismatch"]))
    if args.keep:
        print("work folder: " + work)
    else:
        shutil.rmtree(work)
    sys.exit(0 if not any(problems.values()) else 1)


if __name__ == "__main__":
    main()
