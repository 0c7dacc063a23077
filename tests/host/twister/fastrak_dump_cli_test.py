#!/usr/bin/env python3
"""`twister fastrak-dump --file`: streams written from docs/fastrak-protocol.md, exact
output lines, error lines for rejected stretches, stdin, and exit codes (0 read, 1 unreadable,
2 bad options). Usage: fastrak_dump_cli_test.py TWISTER_BINARY"""
import math
import struct
import subprocess
import sys
import tempfile

TWISTER = sys.argv[1]
failures = []


def run(args, data=None):
    p = subprocess.run([TWISTER, "fastrak-dump"] + args, input=data,
                       capture_output=True, timeout=30)
    return p.returncode, p.stdout.decode().splitlines(), p.stderr.decode()


def check(name, cond, detail=""):
    if not cond:
        failures.append(f"{name}: {detail}")


def f32(*vals):
    return b"".join(struct.pack("<f", v) for v in vals)


def axes_line(station, pos, az, el, roll):
    """Independent Rz*Ry*Rx (docs/fastrak-protocol.md §4); columns are the receiver axes."""
    cp, sp = math.cos(math.radians(az)), math.sin(math.radians(az))
    ct, st = math.cos(math.radians(el)), math.sin(math.radians(el))
    cf, sf = math.cos(math.radians(roll)), math.sin(math.radians(roll))
    u = (cp * ct, sp * ct, -st)
    v = (cp * st * sf - sp * cf, sp * st * sf + cp * cf, ct * sf)
    w = (cp * st * cf + sp * sf, sp * st * cf - cp * sf, ct * cf)
    return [station] + list(pos) + list(u) + list(v) + list(w)


def close(line, expect, tol=1e-5):
    parts = line.split()
    if len(parts) != 13 or int(parts[0]) != expect[0]:
        return False
    return all(abs(float(a) - b) <= tol for a, b in zip(parts[1:], expect[1:]))


with tempfile.NamedTemporaryFile(suffix=".bin") as tmp:
    # ASCII default list 2,4,1 (47 bytes), a truncated record, an out-of-range one.
    good = b"01   12.50  -3.21-123.45  30.00 -20.00  10.00\r\n"
    assert len(good) == 47
    trunc = good[:20]
    bad_el = b"01    1.00   2.00   3.00   0.00  95.00   0.00\r\n"
    tmp.write(b"noise" + good + trunc + good + bad_el)
    tmp.flush()
    rc, out, err = run(["--file", tmp.name])
    check("ascii rc", rc == 0, err)
    check("ascii lines", len(out) == 5, out)
    if len(out) == 5:
        exp = axes_line(1, (12.5, -3.21, -123.45), 30, -20, 10)
        check("ascii resync 1", out[0] == "error resync 5 bytes", out[0])
        check("ascii pose 1", close(out[1], exp), out[1])
        check("ascii resync 2", out[2] == "error resync 20 bytes", out[2])
        check("ascii pose 2", close(out[3], exp), out[3])
        check("ascii range", out[4] == "error station 1 angle_range", out[4])
        check("format %.6g", out[1].split()[1:4] == ["12.5", "-3.21", "-123.45"], out[1])

    # The same from stdin.
    rc, out2, err = run(["--file", "-"], data=b"noise" + good)
    check("stdin", rc == 0 and len(out2) == 2 and close(out2[1], exp), out2)

# Binary, two stations with different lists: -O 1,2,11,1 -O 2,2,5,6,7,0 -f -u.
rec1 = b"01 " + f32(10.0, -20.0, 30.0, 0.70710677, 0.0, 0.0, 0.70710677) + b"\r\n"
rec2 = b"02y" + f32(1.5, 2.5, 3.5, 0, -1, 0, 1, 0, 0, 0, 0, 1) + b" "
nan = b"01 " + f32(float("nan"), 0, 0, 1, 0, 0, 0) + b"\r\n"
with tempfile.NamedTemporaryFile(suffix=".bin") as tmp:
    tmp.write(rec1 + rec2 + nan + rec1[:10] + rec2)
    tmp.flush()
    rc, out, err = run(["--file", tmp.name, "-f", "-u", "-O", "1,2,11,1", "-O", "2,2,5,6,7,0"])
    check("binary rc", rc == 0, err)
    check("binary lines", len(out) == 5, out)
    if len(out) == 5:
        check("binary quat", close(out[0], axes_line(1, (10, -20, 30), 90, 0, 0)), out[0])
        check("binary dcm", close(out[1], axes_line(2, (1.5, 2.5, 3.5), 90, 0, 0)), out[1])
        check("binary nan", out[2] == "error station 1 nonfinite", out[2])
        check("binary resync", out[3] == "error resync 10 bytes", out[3])
        check("binary last", out[4].startswith("2 1.5 2.5 3.5"), out[4])

# 16-bit packed format (docs/fastrak-protocol.md §3.4): 7 logical bytes per group with
# bit 7 stripped, then one byte of the stripped bits; the record's first byte carries
# bit 7 (sync).
def pack16(logical):
    wire = bytearray()
    for g in range(0, len(logical), 7):
        group, high = logical[g:g + 7], 0
        for i, b in enumerate(group):
            high |= ((b >> 7) & 1) << i
            wire.append(b & 0x7F)
        wire.append(high)
    wire[0] |= 0x80
    return bytes(wire)


def i16(*counts):
    return b"".join(struct.pack("<h", c) for c in counts)


p16 = pack16(b"01 " + i16(5000, -5000, 32767) + i16(23170, 0, 0, 23170))
check("packed length", len(p16) == 20, len(p16))
bad16 = bytearray(p16)
bad16[12] |= 0x80  # a high bit inside the record: lost sync
rc, out, err = run(["--file", "-", "--binary16", "-O", "1,2,11"], data=bytes(bad16) + p16)
check("binary16 rc", rc == 0, err)
check("binary16 lines", len(out) == 2, out)
if len(out) == 2:
    scale = 65.48 / 32768
    check("binary16 resync", out[0] == "error resync 20 bytes", out[0])
    check("binary16 pose", close(out[1], axes_line(1, (5000 * scale, -5000 * scale, 32767 * scale),
                                                   90, 0, 0), 1e-4), out[1])
check("binary16 ext item", run(["--file", "-", "--binary16", "-O", "1,52,1"], b"")[0] == 2)

# Exit codes.
check("no input", run([])[0] == 2)
check("bad item", run(["--file", "-", "-O", "1,2,99"], b"")[0] == 2)
check("bad station", run(["--file", "-", "-O", "5,2,1"], b"")[0] == 2)
check("F and f", run(["--file", "-", "-F", "-f"], b"")[0] == 2)
check("unknown option", run(["--file", "-", "--bogus"], b"")[0] == 2)
check("unreadable", run(["--file", "/nonexistent/rec.bin"])[0] == 1)
check("empty file", run(["--file", "-"], b"")[0:2] == (0, []))

if failures:
    print("\n".join(failures))
    sys.exit(1)
print("fastrak-dump CLI: all checks passed")
