#!/usr/bin/env python3
"""The display's camera after `twister calibrate` (issue 23): both hands' working space.

1. As in calibrate_test.py: twister-sim's stylus rests on the origin, +X and +Y points
   of a table 0.30 m below the transmitter, fastrak-dump records it over a PTY, and
   `twister calibrate` prints the work frame.
2. A two-hand scenario on the calibrated station (in-process simulator, virtual time,
   scripted buttons) through twister-bridge --offscreen (run_scenario.py --bridge,
   --movie-every): both hands come to a box standing on the origin, grab its left and
   right faces and pull them apart, then hand 2 is raised far out of the working volume
   (to z = 0.85 m, 0.45 m above the default volume's top) and comes back.
3. From every movie frame's `.cues` (the bridge's projection: cursors, picture size,
   view-projection matrix):
   - both hands' cursors are in the picture with a margin (5 % of its height) in every
     frame (the framing grew to keep hand 2: without the growth it leaves the picture);
   - the working volume (the station's default with a work frame: x, y -0.3..0.3 m,
     z 0..0.4 m) projects inside the picture in the first frame;
   - the model's up is up on screen: the box's vertical edges (model +Z) project within
     5 degrees of vertical, pointing up (without the station's up they point down);
   - the framing grew smoothly: between two frames the projected box centre moves
     less than 10 % of the picture's height.

    calibrate_camera_test.py --bin BUILD/bin --out DIR [--picture FILE.png]

--picture also writes the calibration picture of docs/hardware.md (calibration_picture.py).
"""
import argparse
import glob
import math
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import calibrate_test as cal  # noqa: E402

MARGIN = 0.05  # of the picture's height
BOX_HALF, BOX_HEIGHT = 0.05, 0.10
VOLUME = ((-0.30, -0.30, 0.0), (0.30, 0.30, 0.40))
PICTURE_VIEW = "--azimuth 300 --elevation 30 --zoom-out 0.9"


def to_transmitter(m):
    """A model-frame point (metres) where the touched frame puts it (transmitter frame)."""
    return cal.add(cal.add(cal.add(cal.ORIGIN, cal.mul(m[0], cal.X_DIR)), cal.mul(m[1], cal.Y_DIR)),
                   cal.mul(m[2], cal.UP))


def key2(t, m, roll=0.0):
    """Receiver 2 (no tip offset) at model point m."""
    p = to_transmitter(m)
    return "key %g 2 %.4f %.4f %.4f 0 0 %g\n" % ((t,) + cal.mul(1 / cal.INCH, p) + (roll,))


def key1(t, m):
    """The stylus tip (receiver 1, tip offset) at model point m."""
    return cal.key(t, 1, to_transmitter(m))


def scenario(out, snippet, view="", name="two_hands.scn"):
    left, right = (-BOX_HALF, 0.0, 0.05), (BOX_HALF, 0.0, 0.05)
    left_pulled, right_pulled = (-0.08, 0.0, 0.07), (0.08, 0.0, 0.07)
    far = (0.10, 0.35, 0.85)  # raised high above the working volume
    toml = ["[tracker.calibration]", "tip_offset = [%g, 0, 0]" % cal.TIP] + [
        ln for ln in snippet.splitlines() if ln.strip() and not ln.startswith("#")]
    text = ("# Two hands on a calibrated station: grab the box's side faces, pull them apart,\n"
            "# then hand 2 is raised high out of the working volume and back.\n"
            "# @mesh box -n 6 --size %g --center 0 0 %g\n" % (BOX_HALF, BOX_HEIGHT / 2) +
            "# @sculpt radius_m = 0.06\n# @sculpt refine = false\n" +
            "# @view --log-level debug %s\n" % view +
            "".join("# @toml %s\n" % ln for ln in toml) +
            "receivers 2\nduration 12\n" +
            key1(0, (-0.20, -0.10, 0.25)) + key1(2, left) + key1(3, left) +
            key1(5, left_pulled) + key1(6, left_pulled) + key1(8, (-0.25, -0.20, 0.30)) +
            key1(12, (-0.20, -0.10, 0.25)) +
            key2(0, (0.20, 0.10, 0.25)) + key2(2, right) + key2(3, right) +
            key2(5, right_pulled, 20) + key2(6, right_pulled, 20) + key2(8.5, far) +
            key2(9.5, far) + key2(11.5, (0.20, 0.10, 0.25)) +
            "button 3 0 1\nbutton 3 3 1\nbutton 5.5 0 0\nbutton 5.5 3 0\n")
    path = os.path.join(out, name)
    open(path, "w").write(text)
    return path


def read_cues(path):
    cues = {"cursor": [], "size": None, "viewproj": None}
    for line in open(path):
        w = line.split()
        if not w or w[0].startswith("#"):
            continue
        if w[0] == "cursor":
            cues["cursor"].append((float(w[1]), float(w[2])))
        elif w[0] == "size":
            cues["size"] = (int(w[1]), int(w[2]))
        elif w[0] == "viewproj":
            cues["viewproj"] = [float(v) for v in w[1:17]]
    return cues


def project(cues, p):
    """Pixel of world point p through the cues' view-projection (column-major)."""
    m = cues["viewproj"]
    v = (p[0], p[1], p[2], 1.0)
    clip = [sum(m[c * 4 + r] * v[c] for c in range(4)) for r in range(4)]
    if clip[3] <= 0:
        return None
    w, h = cues["size"]
    return ((clip[0] / clip[3] + 1) * 0.5 * w, (1 - clip[1] / clip[3]) * 0.5 * h)


def inside(p, size, margin):
    return (p is not None and margin <= p[0] <= size[0] - margin and
            margin <= p[1] <= size[1] - margin)


def check_frames(frames):
    problems = []
    if len(frames) < 20:
        return ["only %d movie frames" % len(frames)]
    worst_cursor, worst_tilt, worst_step = 1e9, 0.0, 0.0
    both = 0
    previous = None
    for path in frames:
        c = read_cues(path)
        size = c["size"]
        margin = MARGIN * size[1]
        if len(c["cursor"]) == 2:
            both += 1
        for x, y in c["cursor"]:
            worst_cursor = min(worst_cursor, x, y, size[0] - x, size[1] - y)
            if not inside((x, y), size, margin):
                problems.append("%s: a cursor at (%.0f, %.0f) is outside the picture's %.0f px "
                                "margin" % (os.path.basename(path), x, y, margin))
        for ex, ey in ((BOX_HALF, BOX_HALF), (-BOX_HALF, BOX_HALF), (BOX_HALF, -BOX_HALF),
                       (-BOX_HALF, -BOX_HALF)):
            a, b = project(c, (ex, ey, 0.0)), project(c, (ex, ey, BOX_HEIGHT))
            if a is None or b is None:
                problems.append("%s: the box is behind the camera" % os.path.basename(path))
                break
            # Screen y grows downwards: up on screen is -y.
            tilt = math.degrees(math.atan2(b[0] - a[0], a[1] - b[1]))
            worst_tilt = max(worst_tilt, abs(tilt))
            if abs(tilt) > 5.0:
                problems.append("%s: a vertical edge of the box is %.1f degrees from up on "
                                "screen" % (os.path.basename(path), tilt))
        centre = project(c, (0.0, 0.0, BOX_HEIGHT / 2))
        if previous is not None and centre is not None:
            step = math.dist(centre, previous) / size[1]
            worst_step = max(worst_step, step)
            if step > 0.10:
                problems.append("%s: the framing jumped (the box moved %.0f %% of the "
                                "picture's height)" % (os.path.basename(path), 100 * step))
        previous = centre
    first = read_cues(frames[0])
    lo, hi = VOLUME
    corners = [(x, y, z) for x in (lo[0], hi[0]) for y in (lo[1], hi[1]) for z in (lo[2], hi[2])]
    out = [p for p in corners if not inside(project(first, p), first["size"], 0)]
    if out:
        problems.append("the working volume's corners %s are outside the first frame" % out)
    print("frames %d (both cursors in %d); closest cursor to an edge %.0f px (margin %.0f); "
          "largest tilt of a vertical edge %.2f deg; largest framing step %.1f %% of the height"
          % (len(frames), both, worst_cursor, MARGIN * first["size"][1], worst_tilt,
             100 * worst_step))
    if both < len(frames) // 2:
        problems.append("both cursors in only %d of %d frames" % (both, len(frames)))
    return problems


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bin", required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--picture", help="also write the calibration picture (PNG) here")
    a = ap.parse_args()
    out = os.path.abspath(a.out)
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    exe = lambda name: os.path.join(a.bin, name)  # noqa: E731
    snippet, problems = cal.calibrate(exe, cal.record_touches(exe, out))
    scn = scenario(out, snippet)
    run = os.path.join(out, "run")
    r = subprocess.run([sys.executable, os.path.join(HERE, "..", "..", "sim", "scenarios",
                                                     "run_scenario.py"), scn, "--bin", a.bin,
                        "--out", run, "--bridge", "--movie-every", "6", "--no-hud"],
                       capture_output=True, text=True, timeout=600)
    print(r.stdout + r.stderr, end="")
    if r.returncode != 0:
        problems.append("the station-to-bridge run failed (%d)" % r.returncode)
    frames = sorted(glob.glob(os.path.join(run, "pictures", "frame-*.cues")))
    problems += check_frames(frames)
    if a.picture and not problems:
        # The picture: the same run seen from the front right and closer, so the +X point
        # lies across the picture and the labels stay apart (the test's checks hold for
        # any view; this one is for reading).
        pic_run = os.path.join(out, "picture-run")
        subprocess.run([sys.executable, os.path.join(HERE, "..", "..", "sim", "scenarios",
                                                     "run_scenario.py"),
                        scenario(out, snippet, PICTURE_VIEW, "picture.scn"), "--bin", a.bin,
                        "--out", pic_run, "--bridge", "--movie-every", "6", "--no-hud"],
                       check=True, capture_output=True, timeout=600)
        subprocess.run([sys.executable, os.path.join(HERE, "calibration_picture.py"), "--run",
                        pic_run, "--snippet", snippet, "--out", a.picture], check=True)
    for p in problems[:20]:
        print("FAILED: " + p)
    print("calibrate camera e2e: %s" % ("ok" if not problems else "FAILED (%d)" % len(problems)))
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
