#!/usr/bin/env python3
"""Independent reference of the Twister warp (docs/math.md §2-§6, §10).

Python 3 standard library only, double precision, written from the warp math
(docs/math.md) and not from the C++ code: the screw comes from the skew/symmetric
parts of the rotation matrix (not a quaternion), and S(t) uses the axis point A
directly except for tiny angles. Used by warp_cli_test.py to check `twister warp`.

scodef gets the same squash as the other methods: the basis of a constraint of
hand h at P is phi(sigma_h(P) - C_j) with sigma_h hand h's squash map (§5).
"""
import math

EPS_PURE = 1e-12     # below this angle: pure translation
SMALL_ANGLE = 1e-3   # below this angle A is far away: use the stable form (§3)
HALF_TURN = 1e-9     # within this of pi the axis sense is ambiguous


def add(a, b): return (a[0] + b[0], a[1] + b[1], a[2] + b[2])
def sub(a, b): return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
def mul(s, a): return (s * a[0], s * a[1], s * a[2])
def dot(a, b): return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
def norm(a): return math.sqrt(dot(a, a))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def rotate(k, angle, v):
    c, s = math.cos(angle), math.sin(angle)
    return add(add(mul(c, v), mul(s, cross(k, v))), mul(dot(k, v) * (1 - c), k))


class Hand:
    def __init__(self, o, u, v, o2, u2, v2):
        self.o, self.u, self.v, self.w = o, u, v, cross(u, v)
        self.o2, self.u2, self.v2, self.w2 = o2, u2, v2, cross(u2, v2)


def screw(h, flip=False):
    """(pure, k, a, d, M, X) of the minimal screw; flip picks the other sense at pi."""
    start, end = (h.u, h.v, h.w), (h.u2, h.v2, h.w2)
    R = [[sum(end[m][i] * start[m][j] for m in range(3)) for j in range(3)] for i in range(3)]
    cos_a = max(-1.0, min(1.0, (R[0][0] + R[1][1] + R[2][2] - 1) / 2))
    s = ((R[2][1] - R[1][2]) / 2, (R[0][2] - R[2][0]) / 2, (R[1][0] - R[0][1]) / 2)
    a = math.atan2(norm(s), cos_a)
    oo = sub(h.o2, h.o)
    if a < EPS_PURE:
        return (True, (0.0, 0.0, 1.0), 0.0, 0.0, h.o, oo)
    if cos_a < 0 and norm(s) < 1e-3:
        # Near a half turn the skew part is tiny: axis from the symmetric part,
        # (R + R^T)/2 - cos a I = (1 - cos a) k k^T; sense from the skew part.
        B = [[(R[i][j] + R[j][i]) / 2 - (cos_a if i == j else 0.0) for j in range(3)]
             for i in range(3)]
        c = max(range(3), key=lambda i: B[i][i])
        col = (B[0][c], B[1][c], B[2][c])
        k = mul(1 / norm(col), col)
        if dot(k, s) < 0:
            k = mul(-1, k)
    else:
        k = mul(1 / norm(s), s)
    if flip:
        k = mul(-1, k)
    d = dot(k, oo)
    o3 = sub(h.o2, mul(d, k))
    M = mul(0.5, add(h.o, o3))
    X = sub(o3, h.o)
    return (False, k, a, d, M, X)


def screw_at(sc, t, p):
    pure, k, a, d, M, X = sc
    if pure:
        return add(p, mul(t, X))
    if a > SMALL_ANGLE:
        A = add(M, mul(math.cos(a / 2) / (2 * math.sin(a / 2)), cross(k, X)))
        return add(add(A, rotate(k, t * a, sub(p, A))), mul(t * d, k))
    cot = 1 / math.tan(a / 2)
    c1 = math.sin(t * a / 2) ** 2 * cot
    c2 = math.sin(t * a) * cot / 2
    out = add(M, rotate(k, t * a, sub(p, M)))
    return add(add(add(out, mul(c1, cross(k, X))), mul(c2, X)), mul(t * d, k))


def rottran_at(sc, h, t, p):
    pure, k, a = sc[0], sc[1], sc[2]
    moved = p if pure else add(h.o, rotate(k, t * a, sub(p, h.o)))
    return add(moved, mul(t, sub(h.o2, h.o)))


def decay(dist, r):
    return math.cos(math.pi / 2 * dist / r) ** 2 if dist < r else 0.0


def squash(o, q, r, p):
    oq = sub(q, o)
    s = norm(oq)
    if s >= r:
        return p
    pp = dot(sub(p, o), oq)
    if pp < 0:
        return p
    return add(p, mul((pp / s) * ((r - s) / s) / s, oq))


def weight(hands, i, r, p):
    o = hands[i].o
    if len(hands) == 2:
        p = squash(o, hands[1 - i].o, r, p)
    return decay(norm(sub(p, o)), r)


class Singular(Exception):
    pass


def scodef(hands, r):
    """Returns P -> displacement, or raises Singular."""
    e = 0.1 * r
    pts, tgt, owner = [], [], []
    for i, h in enumerate(hands):
        for a, b in ((h.u, h.u2), (h.v, h.v2), (h.w, h.w2)):
            pts.append(add(h.o, mul(e, a)))
            tgt.append(add(h.o2, mul(e, b)))
            owner.append(i)

    def phi(j, p):
        i = owner[j]
        if len(hands) == 2:
            p = squash(hands[i].o, hands[1 - i].o, r, p)
        return decay(norm(sub(p, pts[j])), r)

    n = len(pts)
    # Gauss-Jordan on [G | rhs] with partial pivoting.
    rows = [[phi(j, pts[i]) for j in range(n)] + list(sub(tgt[i], pts[i])) for i in range(n)]
    for c in range(n):
        piv = max(range(c, n), key=lambda i: abs(rows[i][c]))
        if abs(rows[piv][c]) <= 1e-9:
            raise Singular()
        rows[c], rows[piv] = rows[piv], rows[c]
        for i in range(n):
            if i != c:
                f = rows[i][c] / rows[c][c]
                rows[i] = [x - f * y for x, y in zip(rows[i], rows[c])]
    coef = [tuple(rows[i][n + m] / rows[i][i] for m in range(3)) for i in range(n)]

    def disp(p):
        out = (0.0, 0.0, 0.0)
        for j in range(n):
            out = add(out, mul(phi(j, p), coef[j]))
        return out
    return disp


def warp_points(hands, r, method, points, flips=None):
    flips = flips or [False] * len(hands)
    if method == "scodef":
        disp = scodef(hands, r)
        return [add(p, disp(p)) for p in points]
    screws = [screw(h, f) for h, f in zip(hands, flips)]
    out = []
    for p in points:
        q = p
        for i, h in enumerate(hands):
            t = weight(hands, i, r, p)
            if t <= 0:
                continue
            moved = rottran_at(screws[i], h, t, p) if method == "rottran" else screw_at(screws[i], t, p)
            q = add(q, sub(moved, p))
        out.append(q)
    return out


def near_half_turn(h):
    return math.pi - screw(h)[2] < HALF_TURN
