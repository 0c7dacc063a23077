#!/usr/bin/env python3
"""Structural checks of a showcase picture (no pixel-exact comparison):
    picture_check.py IMAGE [--min-model F] [--pink N] [--yellow N] [--cues FILE]

Reads the PNG through ImageMagick (`convert IMAGE rgb:-`). Fails (exit 1) when the
picture is uniform, when less than F of it (default 0.02) differs from its
background (the colour of its corner), or when it has fewer than N pixels of the
display's screw-axis pink (1.0, 0.41, 0.71) or trajectory yellow. With --cues (the
.cues file twister-bridge writes beside a live picture: each screw axis projected,
the hand cursors, the HUD panel), every axis must be pink along itself: of the points
sampled every 4 px along it, inside the picture and away from the cursors and the
panel, at least --axis-pink (default 0.6) have a pink pixel within 2 px.
"""
import argparse
import subprocess
import sys


def pixels(path):
    size = subprocess.run(["identify", "-format", "%w %h", path], check=True,
                          capture_output=True, text=True).stdout.split()
    w, h = int(size[0]), int(size[1])
    raw = subprocess.run(["convert", path, "-depth", "8", "rgb:-"], check=True,
                         capture_output=True).stdout
    return w, h, raw[0:3 * w * h:3], raw[1:3 * w * h:3], raw[2:3 * w * h:3]


def read_cues(path):
    axes, cursors, panel = [], [], None
    with open(path) as f:
        for line in f:
            words = line.split()
            if not words or words[0].startswith("#"):
                continue
            numbers = [float(v) for v in words[1:]]
            if words[0] == "axis":
                axes.append(tuple(numbers))
            elif words[0] == "cursor":
                cursors.append(tuple(numbers))
            elif words[0] == "panel":
                panel = tuple(numbers)
    return axes, cursors, panel


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("image")
    ap.add_argument("--min-model", type=float, default=0.02)
    ap.add_argument("--pink", type=int, default=0)
    ap.add_argument("--yellow", type=int, default=0)
    ap.add_argument("--cues")
    ap.add_argument("--axis-pink", type=float, default=0.6)
    a = ap.parse_args()
    w, h, rs, gs, bs = pixels(a.image)
    n = len(rs)
    bg = (rs[0], gs[0], bs[0])
    model = sum(1 for r, g, b in zip(rs, gs, bs)
                if abs(r - bg[0]) + abs(g - bg[1]) + abs(b - bg[2]) > 30) / n
    colours = len(set(zip(rs, gs, bs)))
    def is_pink(r, g, b):
        return r > 200 and b - g > 40 and r - b > 30
    pink = sum(1 for r, g, b in zip(rs, gs, bs) if is_pink(r, g, b))
    yellow = sum(1 for r, g, b in zip(rs, gs, bs)
                 if r > 170 and g > 150 and r - b > 80 and g - b > 60)
    fails = []
    if colours < 50:
        fails.append("nearly uniform (%d colours)" % colours)
    if model < a.min_model:
        fails.append("model covers %.3f of the picture (< %g)" % (model, a.min_model))
    if pink < a.pink:
        fails.append("%d pink (screw axis) pixels (< %d)" % (pink, a.pink))
    if yellow < a.yellow:
        fails.append("%d yellow (trajectory) pixels (< %d)" % (yellow, a.yellow))
    axes_text = ""
    if a.cues:
        axes, cursors, panel = read_cues(a.cues)
        if not axes:
            fails.append("no screw axis in %s" % a.cues)
        for k, (x0, y0, x1, y1) in enumerate(axes):
            hits, used = 0, 0
            steps = max(2, int(((x1 - x0) ** 2 + (y1 - y0) ** 2) ** 0.5 / 4))
            for i in range(steps + 1):
                x = x0 + (x1 - x0) * i / steps
                y = y0 + (y1 - y0) * i / steps
                if not (2 <= x < w - 2 and 2 <= y < h - 2):
                    continue
                if any((x - cx) ** 2 + (y - cy) ** 2 < 20 ** 2 for cx, cy in cursors):
                    continue
                if panel and panel[0] - 2 <= x <= panel[0] + panel[2] + 2 and \
                        panel[1] - 2 <= y <= panel[1] + panel[3] + 2:
                    continue
                used += 1
                if any(is_pink(rs[j], gs[j], bs[j])
                       for j in (int(y + dy) * w + int(x + dx)
                                 for dy in (-2, -1, 0, 1, 2) for dx in (-2, -1, 0, 1, 2))):
                    hits += 1
            share = hits / used if used else 0.0
            axes_text += ", axis %d pink at %d of %d points" % (k + 1, hits, used)
            if used < 10:
                fails.append("axis %d: only %d points in view" % (k + 1, used))
            elif share < a.axis_pink:
                fails.append("axis %d: pink at %.2f of its points (< %g)" % (k + 1, share, a.axis_pink))
    print("%s: %dx%d, %d colours, model %.2f, pink %d, yellow %d%s%s"
          % (a.image, w, h, colours, model, pink, yellow, axes_text,
             "" if not fails else ": " + "; ".join(fails)))
    sys.exit(1 if fails else 0)


if __name__ == "__main__":
    main()
