#!/usr/bin/env python3
"""twister-station on a real, full tmpfs (issue 11, item 2).

Mounts a small tmpfs in a private mount namespace (`unshare --user --map-root-user
--mount`, or `unshare --mount` as root), fills it so that the journal runs out of
space in the middle of freeze chains, and runs the station on it:
  1. disk full mid-session: strokes are reported "stroke not saved: disk full", the
     exit status is 1, every "committed as journal record N" is on disk, sequences
     have no gaps and no chain step is skipped, the journal is clean;
  2. restart while still full: it starts (no refusal);
  3. space freed, restart: exit 0, and `twister replay` of the journal builds the
     very model the station ends with.
Where no tmpfs can be mounted (no user namespaces and not root), the test says so and
exits 77 (CTest: skipped); the RLIMIT_FSIZE test in station_integrity_test covers a
real kernel write limit everywhere.
    tmpfs_full_test.py --station BIN --cli BIN --deploy DIR
"""
import argparse
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

SKIP = 77
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from crash_test import chain_scenario  # noqa: E402


def records(path):
    data = open(path, "rb").read()
    # Format version 2 (docs/interaction.md): a 16-byte file header, the journal id
    # after each 8-byte record header; version 1: 8 and none.
    v2 = len(data) >= 8 and struct.unpack_from("<I", data, 4)[0] == 2
    pos, out = (16, []) if v2 else (8, [])
    head = 12 if v2 else 8
    while pos + head <= len(data):
        (length,) = struct.unpack_from("<I", data, pos)
        if length > 512 or pos + head + length + 4 > len(data):
            break
        (crc,) = struct.unpack_from("<I", data, pos + head + length)
        if zlib.crc32(data[pos:pos + head + length]) != crc:
            break
        seq = struct.unpack_from("<I", data, pos + head)[0]
        rtype = data[pos + 5]
        chain = struct.unpack_from("<H", data, pos + head + 6)[0] if rtype == 1 else None
        out.append((seq, chain))
        pos += head + length + 4
    return out, pos == len(data)


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    return r.returncode, r.stdout + r.stderr


def inside(args):
    """Runs in the private mount namespace: the tmpfs exists only here."""
    mnt = args.mnt
    subprocess.check_call(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", mnt])
    journal = os.path.join(mnt, "journal.twj")
    scenario = os.path.join(args.work, "chains.scn")
    open(scenario, "w").write(chain_scenario(8, 3))
    config = os.path.join(args.work, "station.toml")
    open(config, "w").write(
        '[station]\njournal = "%s"\nmesh = "%s/sim_sphere.obj"\n[tracker]\nbackend = "sim"\n'
        '[tracker.sim]\nscenario_file = "%s"\ntime = "virtual"\n[buttons]\nbackend = "sim"\n'
        '[systemd]\nnotify = false\nwatchdog = false\n'
        % (journal, os.path.abspath(args.deploy), scenario))
    # Leave one page free: the journal (about 170 bytes a record) fills it mid-chain.
    filler = os.path.join(mnt, "filler")
    fd = os.open(filler, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    try:
        while os.write(fd, b"\1" * 4096) > 0:
            pass
    except OSError:
        pass
    os.close(fd)
    st = os.statvfs(mnt)
    free = st.f_bavail * st.f_frsize
    os.truncate(filler, max(0, os.path.getsize(filler) - (4096 - free)))
    failures = []
    rc, out = run([args.station, "--config", config, "--log-level", "info"])
    print("run 1 (disk fills): exit %d; %d 'stroke not saved: disk full' lines"
          % (rc, out.count("stroke not saved: disk full")))
    committed = {int(n) for n in re.findall(r"committed as journal record (\d+)", out)}
    on_disk, clean = records(journal)
    seqs = [s for s, _ in on_disk]
    if rc != 1 or "stroke not saved: disk full" not in out:
        failures.append("run 1 should report strokes not saved and exit 1:\n" + out)
    if set(seqs) != committed or seqs != list(range(len(seqs))) or not clean:
        failures.append("journal %s vs committed %s (clean %s)" % (seqs, sorted(committed), clean))
    for (_, a), (_, b) in zip(on_disk, on_disk[1:]):
        if b is not None and b > 0 and (a is None or b != a + 1):
            failures.append("chain step %s after %s" % (b, a))
    print("  %d records on disk, %d commits reported, sequences 0..%d"
          % (len(seqs), len(committed), len(seqs) - 1))
    rc, out = run([args.station, "--config", config, "-q"])
    print("run 2 (still full): exit %d" % rc)
    if "refusing" in out or "running (" not in out:
        failures.append("run 2 refused to start on a full disk:\n" + out)
    # A new journal on the full disk (issue 21): its header cannot be written; the
    # station says "disk full" (not just io_error) and leaves no partial header.
    rest = os.path.join(mnt, "rest")
    fd = os.open(rest, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    try:
        while os.write(fd, b"\1" * 512) > 0:
            pass
    except OSError:
        pass
    os.close(fd)
    new_journal = os.path.join(mnt, "new.twj")
    new_config = os.path.join(args.work, "new.toml")
    open(new_config, "w").write(open(config).read().replace(journal, new_journal))
    rc, out = run([args.station, "--config", new_config, "-q"])
    print("run 2b (new journal, disk full): exit %d" % rc)
    if rc != 1 or "disk full" not in out or (
            os.path.exists(new_journal) and os.path.getsize(new_journal) != 0):
        failures.append("a new journal on a full disk should say disk full:\n" + out)
    os.unlink(rest)
    os.unlink(filler)
    rc, out = run([args.station, "--config", config, "-q"])
    print("run 3 (space freed): exit %d" % rc)
    m = re.search(r"mesh checksum ([0-9a-f]{16})", out)
    r = subprocess.run([args.cli, "replay", journal, "--mesh",
                        os.path.join(os.path.abspath(args.deploy), "sim_sphere.obj"),
                        "--out", os.path.join(args.work, "o.obj"), "-q"],
                       capture_output=True, text=True)
    if rc != 0 or not m or ("checksum " + m.group(1)) not in r.stdout:
        failures.append("run 3 / replay disagree:\n" + out + r.stdout + r.stderr)
    for f in failures:
        print("FAIL: " + f)
    print("tmpfs full test: %s" % ("passed" if not failures else "FAILED"))
    return 1 if failures else 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--station", required=True)
    ap.add_argument("--cli", required=True)
    ap.add_argument("--deploy", required=True)
    ap.add_argument("--inside", action="store_true")
    ap.add_argument("--work")
    ap.add_argument("--mnt")
    args = ap.parse_args()
    if args.inside:
        sys.exit(inside(args))
    work = tempfile.mkdtemp(prefix="twister_tmpfs_")
    mnt = os.path.join(work, "mnt")
    os.mkdir(mnt)
    rest = ["--station", os.path.abspath(args.station), "--cli", os.path.abspath(args.cli),
            "--deploy", os.path.abspath(args.deploy), "--inside", "--work", work, "--mnt", mnt]
    me = [sys.executable, os.path.abspath(__file__)] + rest
    for prefix in (["unshare", "--user", "--map-root-user", "--mount"], ["unshare", "--mount"]):
        probe = subprocess.run(prefix + ["sh", "-c", "mount -t tmpfs -o size=4k tmpfs %s" % mnt],
                               capture_output=True, text=True)
        if probe.returncode == 0:
            print("mounting a tmpfs with: " + " ".join(prefix))
            rc = subprocess.run(prefix + me).returncode
            shutil.rmtree(work)
            sys.exit(rc)
    shutil.rmtree(work)
    print("SKIPPED: cannot mount a tmpfs here (no unprivileged user namespaces and not root: "
          "%s); the RLIMIT_FSIZE test (station_integrity_test) covers a real write limit"
          % probe.stderr.strip())
    sys.exit(SKIP)


if __name__ == "__main__":
    main()
