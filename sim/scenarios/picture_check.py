#!/usr/bin/env python3
"""Structural checks of a showcase picture (no pixel-exact comparison):
    picture_check.py IMAGE [--min-model F] [--pink N] [--yellow N]

Reads the PNG through ImageMagick (`convert IMAGE rgb:-`). Fails (exit 1) when the
picture is uniform, when less than F of it (default 0.02) differs from its
background (the colour of its corner), or when it has fewer than N pixels of the
display's screw-axis pink (1.0, 0.41, 0.71) or trajectory yellow.
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


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("image")
    ap.add_argument("--min-model", type=float, default=0.02)
    ap.add_argument("--pink", type=int, default=0)
    ap.add_argument("--yellow", type=int, default=0)
    a = ap.parse_args()
    w, h, rs, gs, bs = pixels(a.image)
    n = len(rs)
    bg = (rs[0], gs[0], bs[0])
    model = sum(1 for r, g, b in zip(rs, gs, bs)
                if abs(r - bg[0]) + abs(g - bg[1]) + abs(b - bg[2]) > 30) / n
    colours = len(set(zip(rs, gs, bs)))
    pink = sum(1 for r, g, b in zip(rs, gs, bs) if r > 200 and b - g > 40 and r - b > 30)
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
    print("%s: %dx%d, %d colours, model %.2f, pink %d, yellow %d%s"
          % (a.image, w, h, colours, model, pink, yellow, "" if not fails else ": " + "; ".join(fails)))
    sys.exit(1 if fails else 0)


if __name__ == "__main__":
    main()
