#!/usr/bin/env python3
"""Writes the scenarios of the paper's Figures 2, 3 and 9 (sim/scenarios/figures/):
    python3 sim/scenarios/gen_figures.py sim/scenarios/figures

Inches and degrees in the tracker frame (+X forward, +Z down: "up" is -Z); the
Fastrak's angles are azimuth (about Z), elevation (about Y), roll (about X). Hand 0
is receiver 1 (grab line 0, radius line 1), hand 1 receiver 2 (lines 3, 4). A hand
that does not grab in a stroke stays where it is. Every press and release happens
with both hands still for 0.5 s on each side, as in the other scenarios.

Headers read by run_scenario.py: @mesh, @sculpt, @view, and the checks
  # @expect-vertex X Y Z -> X' Y' Z' TOL   (metres: the start vertex nearest X Y Z
                                          ends within TOL of X' Y' Z')
  # @expect-turn X Y Z -> X' Y' Z' AXIS DEG TOL
                                          (the vertices 3 to 12 mm around it turned
                                          by DEG degrees about AXIS x|y|z, within TOL)
"""
import math
import os
import sys

IN = 0.0254
Z = (0, 0, 0)
# The sheet of Figures 2 and 3: 0.6 m square in the XY plane at (0.55, 0, 0.10) m.
SHEET = "plane -n 101 --size 0.30 --center 0.55 0 0.10"
SPHERE = "sphere -n 80 --segments 128 --size 0.30 --center 0.55 0 0.10"
C = (21.65, 0.0, 3.94)  # the centre of both, in inches
R = 11.81  # the sphere's radius, in inches
AWAY = (21.65, 60.0, -30.0)  # a hand that takes no part: far outside the view


def p(dx, dy, dz):
    return (round(C[0] + dx, 2), round(C[1] + dy, 2), round(C[2] + dz, 2))


def m(q):  # inches -> metres, as the station reads the tracker
    return tuple(round(c * IN, 4) for c in q)


def key(t, station, pos, ang):
    return "key %.2f %d %.2f %.2f %.2f %g %g %g" % ((t, station) + tuple(pos) + tuple(ang))


def scenario(title, header, steps):
    """steps: ("stroke", label, hand0, hand1) with hand = (start, end, end angles) or None
    (that hand does not grab); ("radius", label, separation at press, at release)."""
    out = ["# " + line for line in title] + header + ["seed 1", "receivers 2"]
    lines = {1: [], 2: []}
    buttons = []
    where = {1: AWAY, 2: AWAY}
    for s in (1, 2):
        lines[s].append(key(0, s, where[s], Z))
    t = 1.0
    for step in steps:
        buttons.append("# " + step[1])
        if step[0] == "radius":
            a, b = step[2], step[3]
            for s, sign in ((1, -1), (2, 1)):
                q0, q1 = p(0, sign * a / 2, -20), p(0, sign * b / 2, -20)
                lines[s] += [key(t + 1.0, s, q0, Z), key(t + 2.0, s, q0, Z),
                             key(t + 3.5, s, q1, Z), key(t + 4.5, s, q1, Z)]
                where[s] = q1
            buttons += ["button %.2f 1 1" % (t + 1.5), "button %.2f 4 1" % (t + 1.5),
                        "button %.2f 1 0" % (t + 4.0), "button %.2f 4 0" % (t + 4.0)]
            t += 4.5
            continue
        for s, hand, line in ((1, step[2], 0), (2, step[3], 3)):
            if hand is None:  # stays where it is (or goes away) and does not grab
                lines[s] += [key(t + 1.0, s, AWAY, Z), key(t + 5.0, s, AWAY, Z)]
                continue
            q0, q1, ang = hand
            lines[s] += [key(t + 1.0, s, q0, Z), key(t + 2.0, s, q0, Z),
                         key(t + 4.0, s, q1, ang), key(t + 5.0, s, q1, ang)]
            buttons += ["button %.2f %d 1" % (t + 1.5, line), "button %.2f %d 0" % (t + 4.5, line)]
        t += 5.0
    for s in (1, 2):  # both hands leave: the display's final.png shows the model alone
        lines[s] += [key(t + 1.0, s, AWAY, Z), key(t + 1.5, s, AWAY, Z)]
    out.append("duration %g" % (t + 2.0))
    for s in (1, 2):
        out += lines[s]
    return "\n".join(out + buttons) + "\n"


def vertex_check(start, end, tol=0.004):
    return "# @expect-vertex %g %g %g -> %g %g %g %g" % (m(start) + m(end) + (tol,))


def turn_check(start, end, axis, deg, tol=12):
    return "# @expect-turn %g %g %g -> %g %g %g %s %g %g" % (m(start) + m(end) + (axis, deg, tol))


def figure2():
    """One hand grabs the middle of a flat sheet and lifts it 5 in."""
    o, o2 = p(0, 0, 0), p(0, 0, -5)
    # A ball of influence wider than the sheet's half: its edges show the turn.
    view = ["# @mesh " + SHEET.replace("0.30", "0.20"), "# @sculpt radius_m = 0.35",
            "# @view --azimuth 30 --elevation 28 --zoom-out 0.8"]
    cases = {
        "figure2_translate": ("translation along OO'", Z, None),
        "figure2_twist": ("translation and a 90-degree rotation about OO' (a screw along it)",
                          (90, 0, 0), ("z", 90)),
        "figure2_screw": ("translation and a 60-degree screw about an axis perpendicular to OO'",
                          (0, 0, 60), ("x", 60)),
    }
    out = {}
    for name, (what, ang, turn) in cases.items():
        checks = [vertex_check(o, o2)] + ([turn_check(o, o2, *turn)] if turn else [])
        out[name] = scenario(
            ["The paper's Figure 2 (" + name.split("_")[1] + "): a flat sheet, one hand: " + what + ".",
             "Generated by sim/scenarios/gen_figures.py."],
            view + checks, [("stroke", what, (o, o2, ang), None)])
    return out


def figure3():
    """Two hands on the sheet: translation only, with screws, bending."""
    view = ["# @mesh " + SHEET, "# @view --azimuth 30 --elevation 28 --zoom-out 0.8"]
    a0, b0 = p(0, -5.5, 0), p(0, 5.5, 0)
    a1, b1 = p(0, -5.5, -5), p(0, 5.5, -5)
    out = {}
    out["figure3_translate"] = scenario(
        ["The paper's Figure 3 (left): two hands lift two points of a sheet: translation only.",
         "Generated by sim/scenarios/gen_figures.py."],
        view + ["# @sculpt radius_m = 0.18", vertex_check(a0, a1), vertex_check(b0, b1)],
        [("stroke", "both hands lift 5 in", (a0, a1, Z), (b0, b1, Z))])
    out["figure3_screws"] = scenario(
        ["The paper's Figure 3 (middle): the same lift with screws: each hand turns",
         "40 degrees about X (perpendicular to the line joining them), in the same sense.",
         "Generated by sim/scenarios/gen_figures.py."],
        view + ["# @sculpt radius_m = 0.18", vertex_check(a0, a1), vertex_check(b0, b1),
                turn_check(a0, a1, "x", 40), turn_check(b0, b1, "x", 40)],
        [("stroke", "both hands lift 5 in and turn 40 degrees about X",
          (a0, a1, (0, 0, 40)), (b0, b1, (0, 0, 40)))])
    c0, d0 = p(0, -10, 0), p(0, 10, 0)
    c1, d1 = p(0, -8.5, -5), p(0, 8.5, -5)
    out["figure3_bend"] = scenario(
        ["The paper's Figure 3 (right): bending the sheet with two hands: each end lifted",
         "and turned 45 degrees about X (perpendicular to the line joining the hands),",
         "in opposite senses. Generated by sim/scenarios/gen_figures.py."],
        view + ["# @sculpt radius_m = 0.30", vertex_check(c0, c1), vertex_check(d0, d1),
                turn_check(c0, c1, "x", 45), turn_check(d0, d1, "x", 45)],
        [("stroke", "both ends lifted 5 in and turned +45 / -45 degrees about X",
          (c0, c1, (0, 0, 45)), (d0, d1, (0, 0, -45)))])
    return out


def figure9():
    """Three objects from a sphere in a few steps each."""
    head = ["# @mesh " + SPHERE, "# @view --azimuth 35 --elevation 25 --zoom-out 1.2"]
    out = {}
    # A horn: the +Y side pulled out far while turning 150 degrees about X (a screw
    # that curls it), the other hand holding the -Y side; then a narrower pull at the tip.
    out["figure9_horn"] = scenario(
        ["The paper's Figure 9 (1 of 3): a horn from a sphere in two strokes.",
         "Generated by sim/scenarios/gen_figures.py."],
        head + ["# @sculpt radius_m = 0.30"],
        [("stroke", "pull the +Y side out 22 in, curling it (150 degrees about X)",
          (p(0, R - 0.5, 0), p(0, R + 16, -14), (0, 0, -150)), (p(0, -R + 0.5, 0), p(0, -R + 0.5, 0), Z)),
         ("stroke", "flatten the base: both sides of the -Y end pressed in",
          (p(-R + 1, -4, 0), p(-R + 5, -4, 0), Z), (p(R - 1, -4, 0), p(R - 5, -4, 0), Z))])
    # A mushroom: the bottom pulled down into a stem, the cap pressed flat.
    out["figure9_mushroom"] = scenario(
        ["The paper's Figure 9 (2 of 3): a mushroom from a sphere in three strokes.",
         "Generated by sim/scenarios/gen_figures.py."],
        ["# @mesh " + SPHERE, "# @view --azimuth 35 --elevation 15 --zoom-out 1.2",
         "# @sculpt radius_m = 0.45"],
        [("stroke", "press the cap: the bottom pushed up and the top down a little",
          (p(0, 0, -R), p(0, 0, -R + 3), Z), (p(0, 0, R), p(0, 0, R - 9), Z)),
         ("radius", "radius x 0.45", 24.0, 10.8),
         ("stroke", "pull the stem down out of the middle of the bottom, twisting it 60 degrees",
          (p(0, 0, R - 9.5), p(0, 0, R + 9), (60, 0, 0)), (p(0, 0, -R + 3), p(0, 0, -R + 3), Z))])
    # A boat: the sphere flattened, then both ends pulled out and turned up about X.
    out["figure9_boat"] = scenario(
        ["The paper's Figure 9 (3 of 3): a boat from a sphere in two strokes.",
         "Generated by sim/scenarios/gen_figures.py."],
        head + ["# @sculpt radius_m = 0.45"],
        [("stroke", "flatten: the top and the bottom pressed together",
          (p(0, 0, -R), p(0, 0, -R + 7.5), Z), (p(0, 0, R), p(0, 0, R - 7.5), Z)),
         ("radius", "radius x 0.6", 24.0, 14.4),
         ("stroke", "pull both ends out 8 in and up 7 in, each turned 70 degrees about X (a bend)",
          (p(0, -R + 0.5, 0), p(0, -R - 8, -7), (0, 0, 70)), (p(0, R - 0.5, 0), p(0, R + 8, -7), (0, 0, -70)))])
    return out


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "figures")
    os.makedirs(folder, exist_ok=True)
    for group in (figure2(), figure3(), figure9()):
        for name, text in group.items():
            with open(os.path.join(folder, name + ".scn"), "w") as f:
                f.write(text)


if __name__ == "__main__":
    main()
