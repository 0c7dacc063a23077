#!/usr/bin/env python3
"""Writes the demo's UV sphere as OBJ: radius 0.30 m, centre (0.55, 0, 0.10) m
(in front of the simulated transmitter; the default grab radius 0.25 m
then moves part of it, as in the paper)."""
import math
import sys

rings, segments, r = 80, 128, 0.30
cx, cy, cz = 0.55, 0.0, 0.10
out = ["# twister-bridge demo sphere (metres)"]
out.append(f"v {cx:.6f} {cy:.6f} {cz + r:.6f}")
for i in range(1, rings):
    th = math.pi * i / rings
    for j in range(segments):
        ph = 2 * math.pi * j / segments
        out.append(f"v {cx + r * math.sin(th) * math.cos(ph):.6f} "
                   f"{cy + r * math.sin(th) * math.sin(ph):.6f} {cz + r * math.cos(th):.6f}")
out.append(f"v {cx:.6f} {cy:.6f} {cz - r:.6f}")
south = 1 + (rings - 1) * segments + 1
def ring(i, j):  # 1-based OBJ index of ring i (1..rings-1), segment j
    return 2 + (i - 1) * segments + (j % segments)
for j in range(segments):
    out.append(f"f 1 {ring(1, j)} {ring(1, j + 1)}")
for i in range(1, rings - 1):
    for j in range(segments):
        a, b, c, d = ring(i, j), ring(i, j + 1), ring(i + 1, j), ring(i + 1, j + 1)
        out.append(f"f {a} {c} {b}")
        out.append(f"f {b} {c} {d}")
for j in range(segments):
    out.append(f"f {ring(rings - 1, j)} {south} {ring(rings - 1, j + 1)}")
with open(sys.argv[1], "w") as f:
    f.write("\n".join(out) + "\n")
