#!/usr/bin/env python3
"""End-to-end test of one scenario of sim/scenarios/ (issue 16).

1. Reference: twister-station alone on the in-process simulated Fastrak in virtual
   time (no link): its final model checksum.
2. The chain, real processes: twister-station (simulator in real time with
   --time real, else virtual) -> Unix-socket link -> twister-bridge --offscreen with
   snapshots and the exported mesh; with --cut-link a first display is SIGKILLed
   after the first commit and a second one connects.
Checks: station = display = `twister replay` of the journal = reference; the
station's "poses:" line reports no conversion error (no invalid pose reached a hand;
rejected and held-back ones never do) and, with --min-caught, that the faults did
produce bad poses that were caught; at least --min-commits strokes; the rest and
final snapshots are not blank: the model covers 3-90 % of the picture and the final
picture differs from the rest picture.

    e2e_test.py SCENARIO --bin BUILD/bin --out DIR [--time real] [--cut-link]
"""
import argparse
import os
import re
import subprocess
import sys
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
RUNNER = os.path.join(HERE, "..", "..", "sim", "scenarios", "run_scenario.py")


def png_pixels(path):
    """(width, height, rows of RGB(A) bytes) of an 8-bit RGB or RGBA PNG."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        length = int.from_bytes(data[pos:pos + 4], "big")
        kind = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height = int.from_bytes(body[:4], "big"), int.from_bytes(body[4:8], "big")
            depth, colour = body[8], body[9]
            assert depth == 8 and colour in (2, 6), "%s: depth %d colour %d" % (path, depth, colour)
            bpp = 3 if colour == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * bpp
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return width, height, rows, bpp


def coverage(path):
    """Fraction of pixels that differ from the background (the corner pixel); the
    chain's snapshots are taken without cues and HUD (--plain), so this is the model."""
    w, h, rows, bpp = png_pixels(path)
    bg = rows[0][:3]
    model = sum(1 for r in rows for x in range(0, w * bpp, bpp) if r[x:x + 3] != bg)
    return model / float(w * h), b"".join(r for r in rows)


def run(runner_args):
    r = subprocess.run([sys.executable, RUNNER] + runner_args, capture_output=True, text=True)
    sums = dict(re.findall(r"^(station|display|replay) ([0-9a-f]{16}|None)$", r.stdout, re.M))
    return r, sums


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scenario")
    ap.add_argument("--bin", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--time", default="virtual", choices=["virtual", "real"])
    ap.add_argument("--cut-link", action="store_true")
    ap.add_argument("--min-commits", type=int, default=1)
    ap.add_argument("--min-caught", type=int, default=0,
                    help="at least this many poses rejected or held back (fault scenarios)")
    ap.add_argument("--checksum", default=None,
                    help="the station's final model checksum must be this (16 hex digits)")
    a = ap.parse_args()
    problems = []
    ref, ref_sums = run([a.scenario, "--bin", a.bin, "--out", os.path.join(a.out, "reference")])
    if ref.returncode != 0:
        sys.exit("e2e: the reference run failed:\n" + ref.stdout + ref.stderr)
    chain_out = os.path.join(a.out, "chain")
    args = [a.scenario, "--bin", a.bin, "--out", chain_out, "--bridge", "--time", a.time,
            "--size", "320x240", "--plain"] + (["--cut-link"] if a.cut_link else [])
    chain, sums = run(args)
    print(chain.stdout)
    if chain.returncode != 0:
        problems.append("the chain run failed (exit %d): %s" % (chain.returncode, chain.stderr))
    if a.checksum is not None and ref_sums.get("station") != a.checksum:
        problems.append("station checksum %s, fixed %s" % (ref_sums.get("station"), a.checksum))
    for k in ("station", "display", "replay"):
        if sums.get(k) != ref_sums.get("station"):
            problems.append("%s checksum %s, reference %s" % (k, sums.get(k), ref_sums["station"]))
    log = open(os.path.join(chain_out, "station.log")).read()
    m = re.search(r"poses: applied (\d+), conversion errors (\d+), rejected (\d+), "
                  r"held back (\d+)", log)
    if not m or int(m.group(1)) == 0 or int(m.group(2)) != 0:
        problems.append("poses line: %s" % (m.group(0) if m else "missing"))
    elif int(m.group(3)) + int(m.group(4)) < a.min_caught:
        problems.append("%s: fewer than %d bad poses caught" % (m.group(0), a.min_caught))
    commits = len(re.findall(r"committed as journal record", log))
    if commits < a.min_commits:
        problems.append("%d commits, at least %d expected" % (commits, a.min_commits))
    pictures = sorted(os.listdir(os.path.join(chain_out, "pictures")))
    finals = [p for p in pictures if p.startswith(("commit-", "mesh-"))]
    if "rest.png" not in pictures or not finals:
        problems.append("snapshots missing: %s" % pictures)
    else:
        last = max(finals, key=lambda p: int(re.sub(r"\D", "", p)))
        rest_cov, rest_px = coverage(os.path.join(chain_out, "pictures", "rest.png"))
        last_cov, last_px = coverage(os.path.join(chain_out, "pictures", last))
        print("coverage: rest %.3f, %s %.3f" % (rest_cov, last, last_cov))
        for name, cov in (("rest.png", rest_cov), (last, last_cov)):
            if not 0.03 <= cov <= 0.90:
                problems.append("%s: the model covers %.1f %% of the picture" % (name, 100 * cov))
        if rest_px == last_px:
            problems.append("%s is the rest picture: nothing was sculpted" % last)
    for p in problems:
        print("PROBLEM: " + p)
    print("e2e %s: %s" % (os.path.basename(a.scenario), "ok" if not problems else "FAILED"))
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
