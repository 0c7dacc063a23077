#!/usr/bin/env python3
"""Independent reference of the Twister warp (docs/math.md §2-§6, §10).

Python 3 standard library only, double precision, written from the warp math
(docs/math.md) and not from the C++ code: the screw comes from the skew/symmetric
parts of the rotation matrix (not a quaternion), and S(t) uses the axis point A
directly except for tiny angles. Used by warp_cli_test.py to check `twister warp`.

scodef gets the same squash as the other methods: the basis of a constraint of
hand h at P is phi(sigma_h(P) - C_j) with sigma_h hand h's squash map (§5).
"""
import functools
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


# --- Symmetry (docs/math.md §11) -------------------------------------------------------
# Group elements as 3x3 row lists; built here from reflections and axis rotations
# (Householder reflections for the mirrors through an axis), independently of the C++.

def mat_vec(m, v):
    return tuple(dot(row, v) for row in m)


def transpose(m):
    return [[m[j][i] for j in range(3)] for i in range(3)]


def rotation_matrix(k, angle):
    cols = [rotate(k, angle, e) for e in ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0))]
    return [[cols[j][i] for j in range(3)] for i in range(3)]


def householder(n):
    return [[(1.0 if i == j else 0.0) - 2 * n[i] * n[j] for j in range(3)] for i in range(3)]


def symmetry_group(words):
    """The elements for a case file's `symmetry` words (identity first)."""
    unit = [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]
    ident = [[1.0 if i == j else 0.0 for j in range(3)] for i in range(3)]
    if words == ["none"]:
        return [ident]
    if words[0] == "rotation":
        a = "xyz".index(words[1])
        n = int(words[2])
        out = [rotation_matrix(unit[a], 2 * math.pi * j / n) for j in range(n)]
        if len(words) == 4:
            c = unit[(a + 2) % 3]
            out += [householder(rotate(unit[a], math.pi * j / n, c)) for j in range(n)]
        return out
    out = [ident]
    for ch in words[0]:
        refl = householder(unit["xyz".index(ch)])
        out = out + [[[sum(refl[i][m] * g[m][j] for m in range(3)) for j in range(3)]
                      for i in range(3)] for g in out]
    return out


def symmetric_warp_points(group, hands, r, method, points, flips=None):
    """F(P) = P + sum_h (1/|G_h|) sum_g g (X_h(w_k(P), g^T P) - g^T P) with the
    min-of-squashes weights of §11.3 and the snap of §11.4."""
    flips = flips or [False] * len(hands)
    same = 1e-9 * r
    snapped, stab = [], []
    for h in hands:
        fixed = [mat_vec(g, h.o) for g in group if norm(sub(mat_vec(g, h.o), h.o)) <= same]
        o = mul(1.0 / len(fixed), functools.reduce(add, fixed))
        shift = sub(o, h.o)
        snapped.append(Hand(o, h.u, h.v, add(h.o2, shift), h.u2, h.v2))
        stab.append(len(fixed))
    grab, image = [], []  # image[h][g] = index of g.O_h in grab
    for h in snapped:
        row = []
        for g in group:
            p = mat_vec(g, h.o)
            k = next((i for i, q in enumerate(grab) if norm(sub(q, p)) <= same), None)
            if k is None:
                grab.append(p)
                k = len(grab) - 1
            row.append(k)
        image.append(row)

    def w(k, p):
        near = [q for j, q in enumerate(grab) if j != k and norm(sub(q, grab[k])) < r]
        if not near:
            return decay(norm(sub(p, grab[k])), r)
        return min(decay(norm(sub(squash(grab[k], q, r, p), grab[k])), r) for q in near)

    screws = [screw(h, f) for h, f in zip(snapped, flips)]
    out = []
    for p in points:
        weights = [w(k, p) for k in range(len(grab))]
        q = p
        for i, h in enumerate(snapped):
            for gi, g in enumerate(group):
                t = weights[image[i][gi]]
                if t <= 0:
                    continue
                x = mat_vec(transpose(g), p)
                moved = (rottran_at(screws[i], h, t, x) if method == "rottran"
                         else screw_at(screws[i], t, x))
                q = add(q, mul(1.0 / stab[i], mat_vec(g, sub(moved, x))))
        out.append(q)
    return out


def symmetric_scodef(group, hands, r):
    """scodef under a group (docs/math.md §11.8), as the FULL system: every image of every
    constraint point (coincident ones merged, their targets averaged, their bases the
    average over the (element, constraint) pairs that land there), solved as one
    N x N system by Gauss-Jordan (the C++ solves one representative per orbit).
    Returns P -> displacement, or raises Singular."""
    same = 1e-9 * r
    e = 0.1 * r
    snapped, stabs = [], []
    for h in hands:
        stab = [g for g in group if norm(sub(mat_vec(g, h.o), h.o)) <= same]
        o = mul(1.0 / len(stab), functools.reduce(add, [mat_vec(g, h.o) for g in stab]))
        shift = sub(o, h.o)
        snapped.append(Hand(o, h.u, h.v, add(h.o2, shift), h.u2, h.v2))
        stabs.append(stab)

    def target_of(i, x):
        """Hand i's motion of O + x, averaged over its stabiliser's conjugates (§11.4)."""
        h = snapped[i]
        out = (0.0, 0.0, 0.0)
        for s in stabs[i]:
            y = mat_vec(transpose(s), x)
            turned = add(add(mul(dot(h.u, y), h.u2), mul(dot(h.v, y), h.v2)), mul(dot(h.w, y), h.w2))
            out = add(out, mat_vec(s, add(h.o2, turned)))
        return mul(1.0 / len(stabs[i]), out)
    grab = []
    for h in snapped:
        for g in group:
            p = mat_vec(g, h.o)
            if not any(norm(sub(q, p)) <= same for q in grab):
                grab.append(p)
    pairs = []  # (point, target, owner grab point, hand)
    for i, h in enumerate(snapped):
        for a in (h.u, h.v, h.w):
            c, t = add(h.o, mul(e, a)), target_of(i, mul(e, a))
            for g in group:
                pairs.append((mat_vec(g, c), mat_vec(g, t), mat_vec(g, h.o), i))
    points = []  # [position, [pairs]]
    for pr in pairs:
        hit = next((pt for pt in points if norm(sub(pt[0], pr[0])) <= 3 * same), None)
        if hit is None:
            points.append([pr[0], [pr]])
        else:
            hit[1].append(pr)
    for pt in points:
        if len(set(pr[3] for pr in pt[1])) > 1:
            raise Singular()  # constraint points of the two hands coincide (§6)
        pt[0] = mul(1.0 / len(pt[1]), functools.reduce(add, [pr[0] for pr in pt[1]]))

    def beta(owner, q, p):
        near = [x for x in grab if same < norm(sub(x, owner)) < r]  # not its own
        if not near:
            return decay(norm(sub(p, q)), r)
        return min(decay(norm(sub(squash(owner, x, r, p), q)), r) for x in near)

    def basis(j, p):
        q, prs = points[j]
        if norm(sub(p, q)) >= 1.2 * r:
            return 0.0
        return sum(beta(pr[2], q, p) for pr in prs) / len(prs)

    n = len(points)
    rows = []
    for i in range(n):
        q, prs = points[i]
        target = mul(1.0 / len(prs), functools.reduce(add, [pr[1] for pr in prs]))
        rows.append([basis(j, q) for j in range(n)] + list(sub(target, q)) +
                    [1.0 if k == i else 0.0 for k in range(n)])
    norm_b = max(sum(abs(rows[i][j]) for i in range(n)) for j in range(n))
    system = [row[:n + 3] for row in rows]
    for c in range(n):
        piv = max(range(c, n), key=lambda i: abs(rows[i][c]))
        if abs(rows[piv][c]) <= 1e-12:
            raise Singular()
        rows[c], rows[piv] = rows[piv], rows[c]
        pivot_row = rows[c]
        for i in range(n):
            if i != c and rows[i][c] != 0.0:
                f = rows[i][c] / pivot_row[c]
                rows[i] = [x - f * y for x, y in zip(rows[i], pivot_row)]
    inv = [[rows[i][n + 3 + k] / rows[i][i] for k in range(n)] for i in range(n)]
    # Ill-conditioned (points crowding together): the full system does not determine the
    # solution in double; the C++ solves the better-conditioned orbit system.
    norm_inv = max(sum(abs(inv[i][k]) for i in range(n)) for k in range(n))
    if norm_b * norm_inv > 1e10:
        raise Singular()
    # x = B^-1 rhs, then iterative refinement with exactly summed residuals.
    coef = []
    for m in range(3):
        rhs = [system[i][n + m] for i in range(n)]
        x = [math.fsum(inv[i][k] * rhs[k] for k in range(n)) for i in range(n)]
        for _ in range(3):
            res = [math.fsum([rhs[i]] + [-system[i][j] * x[j] for j in range(n)]) for i in range(n)]
            x = [x[i] + math.fsum(inv[i][k] * res[k] for k in range(n)) for i in range(n)]
        coef.append(x)
    coef = [(coef[0][i], coef[1][i], coef[2][i]) for i in range(n)]

    def disp(p):
        out = (0.0, 0.0, 0.0)
        for j in range(n):
            b = basis(j, p)
            if b != 0.0:
                out = add(out, mul(b, coef[j]))
        return out
    return disp
