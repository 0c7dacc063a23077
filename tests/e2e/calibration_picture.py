#!/usr/bin/env python3
"""The calibration picture of docs/hardware.md, from a calibrate_camera_test.py run.

Takes the bridge's first movie frame of the calibrated station (the box standing on
the work frame's origin, both hands, the camera framing the working volume) and
draws over it, projected with that frame's own camera (its `.cues` viewproj): the
working volume's outline, the three touched points labelled origin / +X / +Y (the
test's touches moved into the work frame by the calibrated numbers), the work
frame's axes, and where the transmitter is. ImageMagick's `convert` draws.

    calibration_picture.py --run RUN_DIR --snippet TEXT --out FILE.png
"""
import argparse
import glob
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import calibrate_camera_test as t  # noqa: E402
import calibrate_test as cal  # noqa: E402


def work_frame(snippet):
    v = {}
    for line in snippet.splitlines():
        if "=" in line and not line.startswith("#"):
            k, val = line.split("=")
            v[k.strip()] = tuple(float(x) for x in val.strip(" []").split(","))
    x = v["x_axis"]
    n = math.sqrt(sum(c * c for c in x))
    x = tuple(c / n for c in x)
    y = v["y_axis"]
    d = sum(a * b for a, b in zip(x, y))
    y = tuple(b - d * a for a, b in zip(x, y))
    n = math.sqrt(sum(c * c for c in y))
    y = tuple(c / n for c in y)
    z = (x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0])
    origin = v["origin"]
    return lambda p: tuple(sum((p[i] - origin[i]) * a[i] for i in range(3)) for a in (x, y, z))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--run", required=True)
    ap.add_argument("--snippet", required=True)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    frame = sorted(glob.glob(os.path.join(a.run, "pictures", "frame-*.png")))[0]
    cues = t.read_cues(frame[:-4] + ".cues")
    to_model = work_frame(a.snippet)
    px = lambda p: t.project(cues, p)  # noqa: E731
    draw = []

    def line(p, q, colour, width=2, dash=False):
        a_, b_ = px(p), px(q)
        draw.extend(["-stroke", colour, "-strokewidth", str(width), "-fill", "none", "-draw",
                     ("stroke-dasharray 6 4 " if dash else "") +
                     "line %.1f,%.1f %.1f,%.1f" % (a_ + b_)])

    def dot(p, colour, r=5):
        c = px(p)
        draw.extend(["-stroke", "white", "-strokewidth", "1.5", "-fill", colour, "-draw",
                     "circle %.1f,%.1f %.1f,%.1f" % (c + (c[0] + r, c[1]))])

    def text(p, s, colour, dx=8, dy=-8, size=15):
        c = px(p) if len(p) == 3 else p
        draw.extend(["-stroke", "none", "-fill", colour, "-pointsize", str(size), "-annotate",
                     "+%d+%d" % (c[0] + dx, c[1] + dy), s])

    lo, hi = t.VOLUME
    # The working volume: its floor (the table) and its upright edges, dashed.
    floor = [(lo[0], lo[1], 0), (hi[0], lo[1], 0), (hi[0], hi[1], 0), (lo[0], hi[1], 0)]
    for i in range(4):
        line(floor[i], floor[(i + 1) % 4], "#8a93a6", 1)
        top = (floor[i][0], floor[i][1], hi[2])
        line(floor[i], top, "#5c6477", 1, dash=True)
        nxt = floor[(i + 1) % 4]
        line(top, (nxt[0], nxt[1], hi[2]), "#5c6477", 1, dash=True)
    w, h = cues["size"]
    seen = [c for c in floor if px(c) and 0 <= px(c)[0] < w - 280 and 20 < px(c)[1] < h - 10]
    if seen:
        corner = max(seen, key=lambda c: px(c)[1])
        text(corner, "working volume (the display frames it)", "#aab3c5", 6, 16, 13)
    # The work frame's axes from the origin.
    for d, colour, name in (((0.3, 0, 0), "#ff5a5a", "+X"), ((0, 0.2, 0), "#5ad65a", "+Y"),
                            ((0, 0, 0.22), "#6aa8ff", "up (+Z)")):
        line((0, 0, 0), d, colour, 3)
        text(d, name, colour, 4, -4, 16)
    # The three touched points, moved into the work frame by the calibrated numbers.
    for p, name, dx, dy in ((cal.ORIGIN, "1 origin", -78, 20), (cal.X_POINT, "2 +X point", -30, 28),
                            (cal.Y_POINT, "3 +Y point", 9, 16)):
        m = to_model(p)
        dot(m, "#ffd23c")
        text(m, name, "#ffd23c", dx, dy, 15)
    # The transmitter, where the work frame puts it.
    tx = to_model((0.0, 0.0, 0.0))
    c = px(tx)
    if c is not None and 0 <= c[0] < w and 0 <= c[1] < h:
        draw.extend(["-stroke", "white", "-strokewidth", "1.5", "-fill", "#c08040", "-draw",
                     "rectangle %.0f,%.0f %.0f,%.0f" % (c[0] - 7, c[1] - 7, c[0] + 7, c[1] + 7)])
        line(tx, (tx[0], tx[1], 0.0), "#c08040", 1, dash=True)  # it hangs above the table
        text(tx, "transmitter", "#e0a060", 10, 4, 14)
    text((10, 22), "twister calibrate: the stylus touched 1, 2, 3 on the table", "white", 0, 0, 15)
    text((10, 42), "the model stands on the origin, +Z up; the camera frames the hands' space",
         "#c8cfdc", 0, 0, 13)
    subprocess.run(["convert", frame, "-font", "DejaVu-Sans"] + draw +
                   ["-strip", "-define", "png:compression-level=9", a.out], check=True)
    print(a.out)


if __name__ == "__main__":
    main()
