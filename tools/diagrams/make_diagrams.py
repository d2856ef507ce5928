#!/usr/bin/env python3
"""Draws the lecture figures: plain SVG text, one function per figure.

    tools/diagrams/make_diagrams.py              writes chapters/NN-name/figures/*.svg
    tools/diagrams/make_diagrams.py --out DIR    writes them under DIR instead
    tools/diagrams/make_diagrams.py --check DIR  writes them under DIR and fails
                                                 (exit 1) when a committed figure differs

Python 3 standard library only. The output is deterministic (fixed geometry,
numbers printed with a fixed number of decimals), so the committed figures
are exactly what this script writes; ctest's `docs.figures` test checks that.
To look at a figure: rsvg-convert -o fig.png chapters/01-unit-sphere/figures/roots.svg
"""

import argparse
import math
import os
import struct
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Colours used the same way in every figure.
INK = "#222222"
RAY = "#1f5fbf"
SURFACE = "#444444"
HIT = "#d13b2e"
GUIDE = "#888888"
NORMAL = "#2a8a3e"
LIGHT = "#d99a00"
VIEW = "#7a3fb0"
HALF = "#c2477f"
FILLS = ("#f3c7c2", "#c6dcf5", "#cde9c8", "#f6e2a8")


def num(x):
    """A coordinate as text: two decimals at most, no '-0'."""
    s = f"{x:.2f}".rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def esc(text):
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


class Svg:
    """An SVG document built element by element, in drawing order."""

    def __init__(self, width, height, title):
        self.width, self.height = width, height
        self.items = []
        self.markers = set()
        self.title = title

    def _arrow_id(self, colour):
        self.markers.add(colour)
        return "arrow-" + colour.lstrip("#")

    def line(self, x1, y1, x2, y2, colour=INK, width=2, dash=None, arrow=False):
        extra = f' stroke-dasharray="{dash}"' if dash else ""
        if arrow:
            extra += f' marker-end="url(#{self._arrow_id(colour)})"'
        self.items.append(f'<line x1="{num(x1)}" y1="{num(y1)}" x2="{num(x2)}" y2="{num(y2)}" '
                          f'stroke="{colour}" stroke-width="{num(width)}"{extra}/>')

    def polyline(self, points, colour=INK, width=2, fill="none", opacity=None, dash=None, close=False):
        tag = "polygon" if close else "polyline"
        pts = " ".join(f"{num(x)},{num(y)}" for x, y in points)
        extra = f' fill-opacity="{num(opacity)}"' if opacity is not None else ""
        extra += f' stroke-dasharray="{dash}"' if dash else ""
        stroke = f'stroke="{colour}" stroke-width="{num(width)}"' if colour else 'stroke="none"'
        self.items.append(f'<{tag} points="{pts}" fill="{fill}" {stroke}{extra}/>')

    def circle(self, cx, cy, r, colour=INK, width=2, fill="none", opacity=None):
        extra = f' fill-opacity="{num(opacity)}"' if opacity is not None else ""
        stroke = f'stroke="{colour}" stroke-width="{num(width)}"' if colour else 'stroke="none"'
        self.items.append(f'<circle cx="{num(cx)}" cy="{num(cy)}" r="{num(r)}" fill="{fill}" {stroke}{extra}/>')

    def dot(self, x, y, colour=INK, r=4.5):
        self.circle(x, y, r, colour=None, fill=colour)

    def rect(self, x, y, w, h, colour=INK, width=2, fill="none", opacity=None, dash=None):
        extra = f' fill-opacity="{num(opacity)}"' if opacity is not None else ""
        extra += f' stroke-dasharray="{dash}"' if dash else ""
        stroke = f'stroke="{colour}" stroke-width="{num(width)}"' if colour else 'stroke="none"'
        self.items.append(f'<rect x="{num(x)}" y="{num(y)}" width="{num(w)}" height="{num(h)}" '
                          f'fill="{fill}" {stroke}{extra}/>')

    def path(self, d, colour=INK, width=2, fill="none", arrow=False):
        extra = f' marker-end="url(#{self._arrow_id(colour)})"' if arrow else ""
        self.items.append(f'<path d="{d}" fill="{fill}" stroke="{colour}" stroke-width="{num(width)}"{extra}/>')

    def text(self, x, y, content, size=15, colour=INK, anchor="start", weight=None, italic=False):
        extra = f' font-weight="{weight}"' if weight else ""
        extra += ' font-style="italic"' if italic else ""
        self.items.append(f'<text x="{num(x)}" y="{num(y)}" font-size="{size}" fill="{colour}" '
                          f'text-anchor="{anchor}"{extra}>{esc(content)}</text>')

    def render(self):
        defs = []
        for colour in sorted(self.markers):
            mid = "arrow-" + colour.lstrip("#")
            defs.append(f'<marker id="{mid}" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="7" '
                        f'markerHeight="7" orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" '
                        f'fill="{colour}"/></marker>')
        head = (f'<svg xmlns="http://www.w3.org/2000/svg" width="{self.width}" height="{self.height}" '
                f'viewBox="0 0 {self.width} {self.height}" font-family="DejaVu Sans, Helvetica, Arial, sans-serif">')
        body = [head, f"<title>{esc(self.title)}</title>",
                f'<rect x="0" y="0" width="{self.width}" height="{self.height}" fill="#ffffff"/>']
        if defs:
            body.append("<defs>" + "".join(defs) + "</defs>")
        body.extend(self.items)
        body.append("</svg>")
        return "\n".join(body) + "\n"


class Frame:
    """Maps world coordinates (y up) to the picture (y down): x' = ox + s x, y' = oy - s y."""

    def __init__(self, ox, oy, scale):
        self.ox, self.oy, self.s = ox, oy, scale

    def __call__(self, x, y):
        return self.ox + self.s * x, self.oy - self.s * y


def unit(x, y):
    n = math.hypot(x, y)
    return x / n, y / n


def to_float32(x):
    """x rounded to the nearest 32-bit float (what a float operation does with its exact result)."""
    return struct.unpack("f", struct.pack("f", x))[0]


# ---- chapter 01 -------------------------------------------------------------------


def unit_sphere_roots():
    svg = Svg(900, 395, "A ray meets the unit sphere in 0, 1 or 2 points")
    f = Frame(360, 222, 105)
    svg.text(20, 30, "r(t) = o + t d  substituted into  p · p − 1 = 0:  a quadratic in t", size=17, weight="bold")
    cx, cy = f(0, 0)
    svg.circle(cx, cy, f.s, colour=SURFACE, width=2.5, fill="#eef3fb")
    svg.dot(cx, cy, GUIDE, 3.5)
    svg.text(cx + 8, cy + 18, "0", size=13, colour=GUIDE)
    svg.text(cx - 0.75 * f.s - 8, cy + 0.75 * f.s + 8, "p · p = 1", size=14, colour=SURFACE, anchor="end")
    rays = [
        (1.45, "no real root: the ray misses", "discriminant < 0"),
        (1.0, "one (double) root: a tangent ray", "discriminant = 0"),
        (-0.45, "two roots: enters at t0, leaves at t1", "discriminant > 0"),
    ]
    for y, first, second in rays:
        x0, y0 = f(-3.1, y)
        x1, y1 = f(1.75, y)
        svg.line(x0, y0, x1, y1, RAY, 2.2, arrow=True)
        svg.dot(x0, y0, RAY)
        svg.text(x1 + 14, y1 - 3, first, size=14)
        svg.text(x1 + 14, y1 + 15, second, size=13, colour=GUIDE)
        if abs(y) <= 1:
            half = math.sqrt(max(0.0, 1 - y * y))
            for k, x in enumerate(sorted({-half, half})):
                hx, hy = f(x, y)
                svg.dot(hx, hy, HIT, 5.5)
                if half > 0:
                    svg.text(hx + (-26 if k == 0 else 8), hy - 9, f"t{k}", size=14, colour=HIT, weight="bold")
                else:
                    svg.text(hx + 10, hy - 10, "t0 = t1", size=14, colour=HIT, weight="bold")
    ox, oy = f(-3.1, -0.45)
    svg.text(ox - 4, oy + 22, "o", size=15, colour=RAY, italic=True)
    svg.text(20, 378, "A = d · d,  B = 2 (o · d),  C = o · o − 1;  the roots are t = (−B ± √(B² − 4AC)) / 2A",
             size=14, colour=INK)
    return svg


# ---- chapters 02 and 07: the geometric derivation ----------------------------------


def geometric_derivation(notation):
    """The right-angled triangles behind the sphere test, in chapter 02's or chapter 07's names."""
    svg = Svg(900, 470, "The sphere test from geometry: the foot of the perpendicular")
    f = Frame(560, 190, 62)
    R = 2.0
    o = (-7.6, -1.25)  # the ray runs along +x, 1.25 below the centre C = (0, 0)
    foot = (0.0, o[1])
    half = math.sqrt(R * R - foot[1] * foot[1])
    t0, t1 = (-half, o[1]), (half, o[1])
    ch02 = notation == "ch02"
    title = ("t = tc ∓ thc:  how far along the ray, then half the chord" if ch02 else
             "Fix 1: the foot of the perpendicular, found by subtracting vectors")
    svg.text(20, 30, title, size=17, weight="bold")
    C = f(0, 0)
    svg.circle(C[0], C[1], R * f.s, SURFACE, 2.5, fill="#eef3fb")
    svg.line(*f(*o), *f(4.3, o[1]), RAY, 2.2, arrow=True)
    O = f(*o)
    svg.dot(*O, RAY)
    svg.text(O[0] - 4, O[1] - 12, "o", size=16, colour=RAY, italic=True)
    svg.text(O[0] + 20, O[1] - 12, "d, unit length" if ch02 else "d, any length", size=13, colour=RAY)
    svg.dot(*C, INK)
    svg.text(C[0] + 9, C[1] - 8, "C", size=16, italic=True)
    F = f(*foot)
    svg.line(*C, *F, INK, 2, dash="6 4")
    svg.dot(*F, INK, 4)
    s = 0.25
    svg.polyline([f(s, foot[1]), f(s, foot[1] + s), f(0, foot[1] + s)], INK, 1.5)
    svg.text(C[0] + 10, (C[1] + F[1]) / 2 + 8, "l" if ch02 else "l = |foot|", size=16, italic=True)
    T0, T1 = f(*t0), f(*t1)
    svg.line(*C, *T0, SURFACE, 1.8)
    svg.text((C[0] + T0[0]) / 2 - 18, (C[1] + T0[1]) / 2 - 6, "R" if ch02 else "r", size=16, italic=True)
    for P, label in ((T0, "t0"), (T1, "t1")):
        svg.dot(*P, HIT, 5.5)
        svg.text(P[0] + 6, P[1] - 10, label, size=15, colour=HIT, weight="bold")

    def bracket(x_from, x_to, depth, label, colour):
        A, Z = f(x_from, o[1] - depth), f(x_to, o[1] - depth)
        svg.line(*A, *Z, colour, 1.6)
        for X in (A, Z):
            svg.line(X[0], X[1] - 7, X[0], X[1] + 7, colour, 1.6)
        svg.text((A[0] + Z[0]) / 2, A[1] + 22, label, size=14, colour=colour, anchor="middle")

    if ch02:
        bracket(o[0], 0.0, 1.05, "tc = ec · d,   ec = C − o", INK)
        bracket(0.0, half, 1.05, "thc = √(R² − l²)", HIT)
        svg.text(20, 400, "Pythagoras twice:  l² = ec · ec − tc²  (origin, closest point, centre)", size=14)
        svg.text(20, 424, "and  thc² = R² − l²  (centre, closest point, surface).  The ray crosses at  "
                 "t = tc ∓ thc.", size=14)
        svg.text(20, 448, "l > R: the ray passes beside the sphere (a negative discriminant).", size=14,
                 colour=GUIDE)
    else:
        bracket(o[0], 0.0, 1.05, "the foot at t = −(f · d) / (d · d)", INK)
        bracket(0.0, half, 1.05, "√(r² − l²) / |d|", HIT)
        svg.text(20, 400, "f = o − C,   foot = f − (f · d / d · d) d:  a vector subtraction, so the large parts "
                 "of f", size=14)
        svg.text(20, 424, "cancel before anything is squared.   discriminant / 4 = a (r² − foot · foot).", size=14)
        svg.text(20, 448, "Pythagoras instead, l² = f · f − (f · d)² / (d · d), squares first, then subtracts: the digits "
                 "are lost.", size=14, colour=GUIDE)
    return svg


# ---- chapter 03 ---------------------------------------------------------------------


def shrinking_tmax():
    svg = Svg(900, 470, "The closest-hit loop shrinks tmax")
    # tmin = 1 as for a primary ray (the image plane); every wall lies beyond it.
    walls = [5.0, 3.0, 8.0, 2.0]
    tmin, tend = 1.0, 10.0
    x0, x1 = 150, 560

    def X(t):
        return x0 + (x1 - x0) * t / tend

    svg.text(20, 30, "The loop asks object i about (tmin, closest t so far): farther hits cannot win", size=17,
             weight="bold")
    # the ray and the objects on it
    y = 95
    svg.line(X(0), y, X(tend) + 20, y, RAY, 2.2, arrow=True)
    svg.dot(X(0), y, RAY)
    svg.text(X(0) - 8, y + 26, "o", size=16, colour=RAY, italic=True)
    svg.text(20, y - 32, "object #", size=14)
    svg.text(X(tend) + 30, y + 5, "in list order 0, 1, 2, 3", size=13, colour=GUIDE)
    for i, t in enumerate(walls):
        svg.line(X(t), y - 28, X(t), y + 28, SURFACE, 4)
        svg.text(X(t), y - 36, f"#{i}", size=14, anchor="middle", weight="bold")
        svg.text(X(t), y + 46, f"t = {num(t)}", size=13, anchor="middle", colour=GUIDE)
    # the interval each object is asked about
    rows = [("start", tend, None, "(tmin, tmax) from the caller")]
    tmax = tend
    for i, t in enumerate(walls):
        asked = tmax
        if tmin < t < tmax:
            tmax = t
            rows.append((f"object {i}", asked, t, f"hit at {num(t)}: tmax becomes {num(t)}"))
        else:
            rows.append((f"object {i}", asked, None, f"its t = {num(t)} is not below tmax = {num(asked)}: no hit"))
    top = 185
    for k, (label, hi, hit, note) in enumerate(rows):
        yy = top + 50 * k
        svg.text(20, yy + 5, label, size=14, weight="bold" if k == 0 else None)
        svg.line(X(0), yy, X(tend), yy, "#dddddd", 1)
        open_end = hi >= tend
        svg.rect(X(tmin), yy - 9, X(hi) - X(tmin), 18, colour=RAY, width=1.2, fill="#c6dcf5")
        svg.text(X(tmin) - 4, yy + 26, "tmin", size=12, colour=GUIDE, anchor="middle")
        svg.text(X(hi), yy + 26, "∞" if open_end else f"tmax = {num(hi)}", size=12, colour=GUIDE,
                 anchor="middle")
        if hit is not None:
            svg.dot(X(hit), yy, HIT, 6)
        svg.text(X(tend) + 30, yy + 5, note, size=13, colour=HIT if hit is not None else GUIDE)
    nearest = min(range(len(walls)), key=lambda i: walls[i])
    svg.text(20, 455, f"The answer: object {nearest} at t = {num(walls[nearest])}, whatever the order of the list.",
             size=14)
    return svg


# ---- chapter 04 -----------------------------------------------------------------


def plane_figure():
    svg = Svg(900, 400, "A plane in point-and-normal form, and the parallel case")
    svg.text(20, 30, "(x − p0) · n = 0:  substitute x = o + t d", size=17, weight="bold")
    svg.text(620, 30, "d · n = 0: parallel", size=17, weight="bold")
    f = Frame(90, 300, 60)
    # the plane (a line in this cross-section), tilted slightly
    u = unit(1.0, 0.18)
    n = (-u[1], u[0])
    p0 = (1.5, 0.27)
    a = (p0[0] - 1.5 * u[0], p0[1] - 1.5 * u[1])
    z = (p0[0] + 6.6 * u[0], p0[1] + 6.6 * u[1])
    svg.line(*f(*a), *f(*z), SURFACE, 3)
    svg.text(*f(a[0] + 0.1, a[1] + 0.3), "plane", size=14, colour=SURFACE)
    svg.dot(*f(*p0), INK)
    P0 = f(*p0)
    svg.text(P0[0] - 6, P0[1] + 24, "p0", size=16, italic=True)
    svg.line(*P0, *f(p0[0] + 1.3 * n[0], p0[1] + 1.3 * n[1]), NORMAL, 2.5, arrow=True)
    N = f(p0[0] + 1.3 * n[0], p0[1] + 1.3 * n[1])
    svg.text(N[0] - 22, N[1] + 4, "n", size=16, colour=NORMAL, italic=True, weight="bold")
    x = (p0[0] + 2.2 * u[0], p0[1] + 2.2 * u[1])
    svg.line(*P0, *f(*x), GUIDE, 2, arrow=True)
    X = f(*x)
    svg.dot(*X, GUIDE, 4)
    svg.text(X[0] - 40, X[1] + 26, "x − p0 ⟂ n", size=14, colour=GUIDE)
    # a ray from above hitting the plane
    o = (6.8, 3.6)
    d = unit(-0.55, -1.0)
    # t where (o + t d - p0) . n = 0
    t = ((p0[0] - o[0]) * n[0] + (p0[1] - o[1]) * n[1]) / (d[0] * n[0] + d[1] * n[1])
    hit = (o[0] + t * d[0], o[1] + t * d[1])
    svg.line(*f(*o), *f(o[0] + (t + 0.9) * d[0], o[1] + (t + 0.9) * d[1]), RAY, 2.2, arrow=True)
    svg.dot(*f(*o), RAY)
    O = f(*o)
    svg.text(O[0] + 10, O[1] + 4, "o", size=16, colour=RAY, italic=True)
    H = f(*hit)
    svg.dot(*H, HIT, 6)
    svg.text(H[0] - 16, H[1] - 16, "t = (p0 − o) · n / (d · n)", size=15, colour=HIT, anchor="end")
    # right panel: a parallel ray
    g = Frame(600, 300, 60)
    svg.line(*g(0, 0), *g(4.6, 0), SURFACE, 3)
    svg.line(*g(1.2, 0), *g(1.2, 1.3), NORMAL, 2.5, arrow=True)
    Ng = g(1.2, 1.3)
    svg.text(Ng[0] + 8, Ng[1] + 6, "n", size=16, colour=NORMAL, italic=True, weight="bold")
    svg.line(*g(0.2, 1.9), *g(4.6, 1.9), RAY, 2.2, arrow=True)
    svg.dot(*g(0.2, 1.9), RAY)
    svg.text(*g(0.1, 2.15), "o", size=16, colour=RAY, italic=True)
    svg.text(*g(0.2, 2.7), "d · n = 0: the ray never comes nearer", size=14)
    svg.text(*g(0.2, -0.5), "(p0 − o) · n / 0: no t, a miss", size=14, colour=HIT)
    svg.text(20, 385, "The numerator is how far o is from the plane along n; the denominator how fast the ray "
             "approaches it.", size=14)
    return svg


# ---- chapter 05 ---------------------------------------------------------------------


def triangle_figure():
    svg = Svg(900, 450, "Edge half-planes and barycentric areas")
    svg.text(20, 30, "Inside = on the inner side of all three edges", size=17, weight="bold")
    svg.text(470, 30, "Barycentric coordinates are area fractions", size=17, weight="bold")
    f = Frame(30, 392, 58)
    A, B, C = (1.0, 0.6), (5.6, 1.3), (2.6, 4.6)
    corners = (A, B, C)
    names = ("a", "b", "c")
    # each edge's inner half-plane, clipped to the left panel by drawing a large polygon
    box = [(0.0, 0.0), (6.3, 0.0), (6.3, 5.0), (0.0, 5.0)]

    def clip(poly, p, q):
        """Sutherland-Hodgman: keep the part of poly to the left of the directed line p->q."""
        def side(v):
            return (q[0] - p[0]) * (v[1] - p[1]) - (q[1] - p[1]) * (v[0] - p[0])
        out = []
        for i in range(len(poly)):
            cur, nxt = poly[i], poly[(i + 1) % len(poly)]
            sc, sn = side(cur), side(nxt)
            if sc >= 0:
                out.append(cur)
            if (sc >= 0) != (sn >= 0):
                k = sc / (sc - sn)
                out.append((cur[0] + k * (nxt[0] - cur[0]), cur[1] + k * (nxt[1] - cur[1])))
        return out

    for i in range(3):
        p, q = corners[i], corners[(i + 1) % 3]
        region = clip(box, p, q)
        svg.polyline([f(*v) for v in region], colour=None, fill=FILLS[i], opacity=0.45, close=True)
    svg.polyline([f(*v) for v in box], colour="#bbbbbb", width=1, close=True)
    svg.polyline([f(*v) for v in corners], colour=INK, width=2.5, close=True)
    for i in range(3):
        p, q = corners[i], corners[(i + 1) % 3]
        m = ((p[0] + q[0]) / 2, (p[1] + q[1]) / 2)
        e = unit(q[0] - p[0], q[1] - p[1])
        svg.line(*f(m[0] - 0.35 * e[0], m[1] - 0.35 * e[1]), *f(m[0] + 0.35 * e[0], m[1] + 0.35 * e[1]),
                 INK, 2.5, arrow=True)
    offsets = ((-20, 18), (10, 16), (-6, -10))
    for (x, y), name, (dx, dy) in zip(corners, names, offsets):
        P = f(x, y)
        svg.dot(*P, INK, 4.5)
        svg.text(P[0] + dx, P[1] + dy, name, size=17, italic=True, weight="bold")
    inside = (3.0, 2.0)
    outside = (4.9, 3.6)
    svg.dot(*f(*inside), HIT, 5.5)
    svg.text(f(*inside)[0] + 9, f(*inside)[1] + 5, "p: inside all three", size=13, colour=HIT)
    svg.dot(*f(*outside), RAY, 5.5)
    svg.text(f(*outside)[0] - 4, f(*outside)[1] - 10, "q: outside edge b→c", size=13, colour=RAY,
             anchor="middle")
    svg.text(20, 420, "Each tint: one edge's inner side, ((next − this) × (p − this)) · n ≥ 0;", size=13)
    svg.text(20, 440, "the triangle is where all three overlap.", size=13)
    # right panel: the three sub-triangles
    g = Frame(520, 392, 58)
    p = (2.7, 1.9)
    labels = (("alpha", "area(p, b, c)"), ("beta", "area(a, p, c)"), ("gamma", "area(a, b, p)"))
    for i in range(3):
        # the sub-triangle opposite corner i replaces that corner by p
        tri = [p if k == i else corners[k] for k in range(3)]
        svg.polyline([g(*v) for v in tri], colour=INK, width=1.5, fill=FILLS[i], opacity=0.9, close=True)
        cx = sum(v[0] for v in tri) / 3
        cy = sum(v[1] for v in tri) / 3
        Q = g(cx, cy)
        svg.text(Q[0], Q[1] + 5, labels[i][0], size=14, anchor="middle", weight="bold")
    svg.polyline([g(*v) for v in corners], colour=INK, width=2.5, close=True)
    for (x, y), name, (dx, dy) in zip(corners, names, offsets):
        P = g(x, y)
        svg.dot(*P, INK, 4.5)
        svg.text(P[0] + dx, P[1] + dy, name, size=17, italic=True, weight="bold")
    svg.dot(*g(*p), HIT, 5.5)
    svg.text(g(*p)[0] + 8, g(*p)[1] - 8, "p", size=17, colour=HIT, italic=True, weight="bold")
    svg.text(470, 58, "alpha = area(p, b, c) / area(a, b, c)", size=13)
    svg.text(470, 76, "beta = area(a, p, c) / area(a, b, c)", size=13)
    svg.text(470, 94, "gamma = area(a, b, p) / area(a, b, c)", size=13)
    svg.text(470, 430, "p = alpha a + beta b + gamma c,   alpha + beta + gamma = 1", size=13)
    return svg


# ---- chapter 06 ---------------------------------------------------------------------


def shading_vectors():
    svg = Svg(900, 400, "Light, normal, viewer and half vector")
    svg.text(20, 30, "Lambert uses the angle between n and l; Blinn-Phong the angle between n and h", size=17,
             weight="bold")
    f = Frame(330, 320, 70)
    svg.line(*f(-4.2, 0), *f(4.2, 0), SURFACE, 3)
    svg.polyline([f(-4.2, 0), f(4.2, 0), f(4.2, -0.5), f(-4.2, -0.5)], colour=None, fill="#dddddd",
                 close=True)
    svg.text(*f(-4.1, -0.35), "surface", size=13, colour=SURFACE)
    P = f(0, 0)
    svg.dot(*P, INK, 5)
    svg.text(P[0] - 6, P[1] + 24, "point", size=14, anchor="middle")
    L = 3.2
    n = (0.0, 1.0)
    l = unit(2.2, 1.7)
    v = unit(-1.3, 2.0)
    h = unit(l[0] + v[0], l[1] + v[1])
    for vec, colour, name, length, (dx, dy) in ((n, NORMAL, "n", L * 0.95, (10, -4)), (l, LIGHT, "l", L, (4, 24)),
                                                (v, VIEW, "v", L, (-22, -4)), (h, HALF, "h", L * 0.8, (10, -4))):
        E = f(vec[0] * length, vec[1] * length)
        svg.line(*P, *E, colour, 2.8, arrow=True)
        svg.text(E[0] + dx, E[1] + dy, name, size=18, colour=colour, italic=True, weight="bold")
    # the light and the eye at the ends
    Lp = f(l[0] * (L + 0.5), l[1] * (L + 0.5))
    svg.circle(*Lp, 13, LIGHT, 2, fill="#fff0b3")
    svg.text(Lp[0] + 18, Lp[1] + 5, "light", size=14, colour=LIGHT)
    Vp = f(v[0] * (L + 0.5), v[1] * (L + 0.5))
    svg.path(f"M{num(Vp[0] - 16)},{num(Vp[1])} Q{num(Vp[0])},{num(Vp[1] - 12)} {num(Vp[0] + 16)},{num(Vp[1])} "
             f"Q{num(Vp[0])},{num(Vp[1] + 12)} {num(Vp[0] - 16)},{num(Vp[1])} z", VIEW, 2, fill="#eadcf7")
    svg.dot(*Vp, VIEW, 4)
    svg.text(Vp[0] - 24, Vp[1] + 5, "eye", size=14, colour=VIEW, anchor="end")
    # the angle between n and l
    r = 1.1
    a0, a1 = math.atan2(n[1], n[0]), math.atan2(l[1], l[0])
    S, E = f(r * math.cos(a0), r * math.sin(a0)), f(r * math.cos(a1), r * math.sin(a1))
    svg.path(f"M{num(S[0])},{num(S[1])} A{num(r * f.s)},{num(r * f.s)} 0 0 1 {num(E[0])},{num(E[1])}", LIGHT, 1.6)
    T = f(1.25 * math.cos((a0 + a1) / 2), 1.25 * math.sin((a0 + a1) / 2))
    svg.text(T[0] + 2, T[1], "θ", size=16, colour=LIGHT, italic=True)
    x = 620
    svg.text(x, 90, "l: towards the light", size=14, colour=LIGHT)
    svg.text(x, 112, "v: towards the eye", size=14, colour=VIEW)
    svg.text(x, 134, "n: the surface normal", size=14, colour=NORMAL)
    svg.text(x, 156, "h = l/|l| + v/|v|, normalised", size=14, colour=HALF)
    svg.text(x, 200, "diffuse:  max(0, cos θ)", size=14)
    svg.text(x, 222, "  = max(0, n · l / (|n| |l|))", size=14)
    svg.text(x, 250, "highlight:  max(0, n · h / (|n| |h|))^s", size=14)
    svg.text(x, 272, "  1 when v is the mirror of l", size=14)
    svg.text(x, 300, "each light:  intensity / d²", size=14)
    svg.text(20, 388, "Make l, v and h unit length (or divide by their lengths): only the angles count.", size=14)
    return svg


def shadow_offset():
    svg = Svg(900, 410, "The shadow ray starts a little off the surface")
    svg.text(20, 30, "Shadow acne, and the offset that avoids it", size=17, weight="bold")
    f = Frame(60, 240, 70)
    svg.polyline([f(0, 0), f(11.4, 0), f(11.4, -0.6), f(0, -0.6)], colour=None, fill="#dddddd", close=True)
    svg.line(*f(0, 0), *f(11.4, 0), SURFACE, 3)
    svg.text(*f(8.6, -0.4), "inside the object", size=13, colour=SURFACE)
    light = (10.2, 2.7)
    Lp = f(*light)
    svg.circle(*Lp, 13, LIGHT, 2, fill="#fff0b3")
    svg.text(Lp[0] + 18, Lp[1] + 5, "light", size=14, colour=LIGHT)
    # left: the computed point lies a rounding error below; its shadow ray hits the surface
    bad = (2.0, -0.25)
    B = f(*bad)
    d = unit(light[0] - bad[0], light[1] - bad[1])
    t_exit = -bad[1] / d[1]
    X = f(bad[0] + t_exit * d[0], bad[1] + t_exit * d[1])
    svg.line(*B, *f(bad[0] + (t_exit + 0.5) * d[0], bad[1] + (t_exit + 0.5) * d[1]), HIT, 2, dash="6 4")
    svg.dot(*B, HIT, 5)
    svg.text(20, 300, "computed hit point, a rounding error below the surface", size=13, colour=HIT)
    svg.line(X[0] - 8, X[1] - 8, X[0] + 8, X[1] + 8, HIT, 3)
    svg.line(X[0] - 8, X[1] + 8, X[0] + 8, X[1] - 8, HIT, 3)
    svg.text(30, 170, "its shadow ray hits its own surface:", size=13, colour=HIT)
    svg.text(30, 186, "a dark speck in a lit area (shadow acne)", size=13, colour=HIT)
    # right: offset along the normal, on the light's side
    good = (6.0, -0.25)
    G = f(*good)
    origin = (good[0], 0.6)
    Og = f(*origin)
    svg.dot(*G, GUIDE, 5)
    svg.line(*G, *Og, NORMAL, 2.5, arrow=True)
    svg.dot(*Og, RAY, 5)
    svg.text(Og[0] - 12, Og[1] + 4, "offset along n / |n|,", size=13, colour=NORMAL, anchor="end")
    svg.text(Og[0] - 12, Og[1] + 20, "on the light's side", size=13, colour=NORMAL, anchor="end")
    svg.line(*Og, *f(light[0] - 0.3, light[1] - 0.2), RAY, 2.2, arrow=True)
    mid = f((origin[0] + light[0]) / 2, (origin[1] + light[1]) / 2)
    svg.text(mid[0] - 14, mid[1] - 12, "shadow ray: 0 < t < distance to the light", size=13, colour=RAY,
             anchor="end")
    svg.text(20, 340, "offset = 128 · ε · max(1, |x|, |y|, |z|):  rounding errors grow with the coordinates, "
             "so the step does too.", size=14)
    svg.text(20, 364, "A fixed step (say 1e-4) is lost in float far from the origin, and larger than a "
             "millimetre-sized scene.", size=14)
    svg.text(20, 388, "The normal may have any length: it gives only the direction of the step.", size=14,
             colour=GUIDE)
    return svg


# ---- chapter 07: float spacing and the lost radius ---------------------------------


def float_spacing():
    svg = Svg(900, 500, "Float spacing and the lost radius")
    svg.text(20, 30, "A unit sphere at distance D:  c = D² − 1, each step rounded to a float", size=17,
             weight="bold")
    cases = [
        (4000.0, "D = 4000: D² < 2^24, floats 1 apart: fl(D²) − 1 is a float, c is exact"),
        (4098.5, "D = 4098.5: floats 2 apart: fl(D²) − 1 is a tie, rounded to even: here c = fl(D²) − 2"),
        (4097.0, "D = 4097: the same tie, rounded the other way: c = fl(D²), the radius is lost"),
        (6000.0, "D = 6000: D² > 2^25, floats 4 apart: fl(D²) − 1 always rounds back to fl(D²)"),
    ]
    x0, x1 = 110, 790
    for k, (D, note) in enumerate(cases):
        y = 108 + 100 * k
        sq = to_float32(D * D)
        c = to_float32(sq - 1)
        # the gap between fl(D²) and the float just below it
        below = struct.unpack("f", struct.pack("I", struct.unpack("I", struct.pack("f", sq))[0] - 1))[0]
        gap = sq - below
        lo, hi = sq - 6.5, sq + 2.5

        def X(v):
            return x0 + (x1 - x0) * (v - lo) / (hi - lo)

        svg.text(20, y - 42, note, size=14)
        svg.line(x0, y, x1, y, INK, 1.5)
        v = sq - gap * math.floor((sq - lo) / gap)
        while v <= hi:
            svg.line(X(v), y - 9, X(v), y + 9, INK, 1.5)
            v += gap
        exact = sq - 1
        svg.line(X(exact), y - 26, X(exact), y - 6, RAY, 2, arrow=True)
        svg.text(X(exact), y + 42, "fl(D²) − 1, exact", size=12, colour=RAY, anchor="middle")
        svg.dot(X(sq), y, INK, 5)
        svg.text(X(sq), y + 26, "fl(D²)", size=12, anchor="middle")
        svg.circle(X(c), y, 9, HIT, 2.5)
        svg.text(X(c) + 12, y - 12, "c", size=15, colour=HIT, weight="bold")
        svg.text(x1 + 12, y + 5, f"spacing {num(gap)}", size=12, colour=GUIDE)
    svg.text(20, 488, "Ticks: the floats near D².  Black dot: D² rounded to a float.  Red ring: c = "
             "fl(fl(D²) − 1).", size=13, colour=GUIDE)
    return svg


# ---- chapter 08 -----------------------------------------------------------------


def slabs():
    svg = Svg(960, 470, "The slab test for a box")
    svg.text(20, 30, "A box is the overlap of two slabs; a ray is inside the box while it is inside both", size=17,
             weight="bold")
    f = Frame(70, 330, 55)
    bx0, bx1, by0, by1 = 4.0, 8.0, 2.0, 4.0
    top, bottom, left, right = 5.2, -0.6, -0.8, 13.0
    svg.rect(*f(bx0, top), (bx1 - bx0) * f.s, (top - bottom) * f.s, colour=None, fill=FILLS[1], opacity=0.6)
    svg.rect(*f(left, by1), (right - left) * f.s, (by1 - by0) * f.s, colour=None, fill=FILLS[2], opacity=0.6)
    svg.rect(*f(bx0, by1), (bx1 - bx0) * f.s, (by1 - by0) * f.s, colour=INK, width=2.5)
    for x, name in ((bx0, "x0"), (bx1, "x1")):
        svg.text(*f(x, top + 0.1), name, size=13, colour=RAY, anchor="middle")
    for y, name in ((by0, "y0"), (by1, "y1")):
        svg.text(*f(right + 0.1, y - 0.08), name, size=13, colour=NORMAL)
    svg.text(*f(bx0 + 0.1, bottom + 0.15), "x slab", size=13, colour=RAY)
    svg.text(*f(left + 0.1, by1 - 0.35), "y slab", size=13, colour=NORMAL)

    # The black ray hits: it enters the x slab, then the y slab, leaves the x slab, then the y slab.
    o, d = (0.0, -0.2), (1.0, 0.4)
    at = lambda t: (o[0] + t * d[0], o[1] + t * d[1])
    tx = ((bx0 - o[0]) / d[0], (bx1 - o[0]) / d[0])
    ty = ((by0 - o[1]) / d[1], (by1 - o[1]) / d[1])
    near, far = max(tx[0], ty[0]), min(tx[1], ty[1])
    svg.dot(*f(*o))
    svg.text(*f(o[0] - 0.1, o[1] - 0.45), "o", size=14, italic=True)
    svg.line(*f(*o), *f(*at(12.6)), INK, 2.2, arrow=True)
    svg.line(*f(*at(near)), *f(*at(far)), HIT, 5)
    labels = ((tx[0], RAY, "t_x0: enters x slab", (0.15, -0.55)), (ty[0], NORMAL, "t_y0: enters y slab = t_near", (0.2, -0.5)),
              (tx[1], RAY, "t_x1: leaves x slab = t_far", (0.2, -0.5)), (ty[1], NORMAL, "t_y1: leaves y slab", (-0.3, 0.35)))
    for t, ring, text, (dx, dy) in labels:
        x, y = at(t)
        svg.circle(*f(x, y), 6, ring, 2.2, fill="#ffffff")
        svg.text(*f(x + dx, y + dy), text, size=13, colour=ring)

    # The grey ray misses: it leaves the y slab before it enters the x slab.
    o2, d2 = (0.0, 2.4), (1.0, 0.6)
    at2 = lambda t: (o2[0] + t * d2[0], o2[1] + t * d2[1])
    svg.dot(*f(*o2), GUIDE)
    svg.line(*f(*o2), *f(*at2(4.6)), GUIDE, 2.2, arrow=True)
    for t, ring, text, (dx, dy) in (((by1 - o2[1]) / d2[1], NORMAL, "leaves y slab", (-2.6, 0.15)),
                                    ((bx0 - o2[0]) / d2[0], RAY, "then enters x slab: a miss", (0.3, -0.1))):
        x, y = at2(t)
        svg.circle(*f(x, y), 6, ring, 2.2, fill="#ffffff")
        svg.text(*f(x + dx, y + dy), text, size=13, colour=GUIDE)

    # The black ray's two intervals of t, and their overlap.
    t0, s = 40, 52
    axis_y = 400
    svg.line(t0, axis_y + 22, t0 + 12 * s, axis_y + 22, GUIDE, 1.2, arrow=True)
    svg.text(t0 + 12 * s + 8, axis_y + 26, "t", size=14, italic=True)
    svg.line(t0 + tx[0] * s, axis_y, t0 + tx[1] * s, axis_y, RAY, 6)
    svg.text(t0 + tx[0] * s - 6, axis_y + 5, "x interval", size=13, colour=RAY, anchor="end")
    svg.line(t0 + ty[0] * s, axis_y + 12, t0 + ty[1] * s, axis_y + 12, NORMAL, 6)
    svg.text(t0 + ty[1] * s + 6, axis_y + 17, "y interval", size=13, colour=NORMAL)
    svg.line(t0 + near * s, axis_y + 22, t0 + far * s, axis_y + 22, HIT, 5)
    svg.text(t0 + (near + far) / 2 * s, axis_y + 40, "overlap = inside the box", size=13, colour=HIT, anchor="middle")
    svg.text(20, 460, "t_near = max(entries), t_far = min(exits); a hit when t_near ≤ t_far and [t_near, t_far] "
             "meets the ray's range.", size=13)
    return svg


def bvh():
    svg = Svg(960, 470, "A ray's walk through a bounding volume hierarchy")
    svg.text(20, 30, "A ray's walk through the tree: numbered boxes are opened in that order, the rest skipped",
             size=17, weight="bold")
    f = Frame(30, 436, 40)
    prims = [(1.5, 1.5, 0.6), (2.8, 2.8, 0.5), (1.6, 6.4, 0.6), (3.0, 7.4, 0.5),
             (6.8, 2.0, 0.6), (8.2, 1.2, 0.5), (7.5, 6.0, 0.6), (9.0, 7.0, 0.6)]
    # node: (name, children or object list)
    tree = {"root": ["L", "R"], "L": ["LA", "LB"], "R": ["RA", "RB"],
            "LA": [0, 1], "LB": [2, 3], "RA": [4, 5], "RB": [6, 7]}

    def objects(name):
        kids = tree[name]
        return kids if isinstance(kids[0], int) else [i for k in kids for i in objects(k)]

    def box(name, pad):
        ids = objects(name)
        return (min(prims[i][0] - prims[i][2] for i in ids) - pad, max(prims[i][0] + prims[i][2] for i in ids) + pad,
                min(prims[i][1] - prims[i][2] for i in ids) - pad, max(prims[i][1] + prims[i][2] for i in ids) + pad)

    pads = {"root": 0.95, "L": 0.55, "R": 0.55, "LA": 0.08, "LB": 0.08, "RA": 0.08, "RB": 0.08}
    boxes = {n: box(n, p) for n, p in pads.items()}
    o, d = (-0.3, 0.55), unit(1.0, 0.39)

    def slab(b, t_max):
        tx = sorted(((b[0] - o[0]) / d[0], (b[1] - o[0]) / d[0]))
        ty = sorted(((b[2] - o[1]) / d[1], (b[3] - o[1]) / d[1]))
        near, far = max(tx[0], ty[0], 0.0), min(tx[1], ty[1], t_max)
        return near if near <= far else None

    def sphere(i):
        cx, cy, r = prims[i]
        b = d[0] * (o[0] - cx) + d[1] * (o[1] - cy)
        c = (o[0] - cx) ** 2 + (o[1] - cy) ** 2 - r * r
        disc = b * b - c
        return -b - math.sqrt(disc) if disc >= 0 else None

    # The walk of the chapter's closest_hit: nearer child first, a node skipped when it starts beyond the best hit.
    best, order, fate, asked = math.inf, [], {}, []
    stack = [("root", slab(boxes["root"], math.inf))]
    while stack:
        name, entry = stack.pop()
        if entry > best:
            fate[name] = "skipped: starts beyond the hit"
            continue
        order.append(name)
        kids = tree[name]
        if isinstance(kids[0], int):
            for i in kids:
                t = sphere(i)
                asked.append((i, t is not None and t < best))
                if t is not None and t < best:
                    best = t
            continue
        entries = [(slab(boxes[k], best), k) for k in kids]
        for e, k in entries:
            if e is None:
                fate[k] = "missed"
        hit = sorted((e, k) for e, k in entries if e is not None)
        for e, k in reversed(hit):
            stack.append((k, e))
    number = {n: k + 1 for k, n in enumerate(order)}

    def colour_of(name):
        return HIT if name in number else GUIDE

    for name, (x0, x1, y0, y1) in boxes.items():
        opened = name in number
        svg.rect(*f(x0, y1), (x1 - x0) * f.s, (y1 - y0) * f.s, colour=colour_of(name), width=2.4 if opened else 1.6,
                 dash=None if opened else "6 4")
        label = f"{number[name]} {name}" if opened else name
        svg.text(*f(x0 + 0.1, y1 - 0.4), label, size=13, colour=colour_of(name), weight="bold")
    for i, (x, y, r) in enumerate(prims):
        c = f(x, y)
        was_asked = any(a == i for a, _ in asked)
        svg.circle(*c, r * f.s, SURFACE, 1.8, fill=FILLS[0] if was_asked else "#eeeeee")
        svg.text(c[0], c[1] + 5, str(i), size=14, anchor="middle")
    svg.dot(*f(*o))
    svg.line(*f(*o), *f(o[0] + 11 * d[0], o[1] + 11 * d[1]), INK, 2.2, arrow=True)
    hx, hy = o[0] + best * d[0], o[1] + best * d[1]
    svg.circle(*f(hx, hy), 5, HIT, 2, fill=HIT)

    # The tree, with each node's fate.
    pos = {"root": (700, 90), "L": (590, 180), "R": (810, 180),
           "LA": (535, 270), "LB": (645, 270), "RA": (755, 270), "RB": (865, 270)}
    for parent in ("root", "L", "R"):
        for k in tree[parent]:
            svg.line(*pos[parent], *pos[k], colour_of(k), 2 if k in number else 1.4, dash=None if k in number else "6 4")
    for leaf in ("LA", "LB", "RA", "RB"):
        for j, i in enumerate(tree[leaf]):
            x = pos[leaf][0] + (j - 0.5) * 44
            svg.line(*pos[leaf], x, 345, GUIDE, 1.2)
            was_asked = any(a == i for a, _ in asked)
            svg.circle(x, 345, 15, SURFACE, 1.6, fill=FILLS[0] if was_asked else "#eeeeee")
            svg.text(x, 350, str(i), size=13, anchor="middle")
    for name, (x, y) in pos.items():
        svg.rect(x - 34, y - 15, 68, 30, colour=colour_of(name), width=2.2, fill="#ffffff",
                 dash=None if name in number else "6 4")
        svg.text(x, y + 5, name, size=13, anchor="middle", colour=colour_of(name), weight="bold")
        if name in number:
            svg.circle(x - 34, y - 15, 11, None, fill=HIT)
            svg.text(x - 34, y - 10, str(number[name]), size=13, anchor="middle", colour="#ffffff", weight="bold")
    lines = [f"{number[n]}. {n}" + (": asks " + ", ".join(f"{i} ({'hit' if h else 'missed'})" for i, h in asked
                                                        if i in tree[n]) if isinstance(tree[n][0], int) else "")
             for n in order]
    lines += [f"{n}: {why}" for n, why in fate.items()]
    lines.append("below R: never tested")
    for k, line in enumerate(lines):
        svg.text(520, 385 + 16 * k, line, size=13, colour=HIT if line[0].isdigit() else GUIDE)
    return svg


# ---- chapter 09: mirror and glass, and where a secondary ray starts ----------------


def reflect_refract():
    svg = Svg(900, 430, "Reflection, refraction and total internal reflection")
    svg.text(20, 30, "At a smooth surface: the mirror direction r, the transmitted direction t", size=17, weight="bold")
    for panel, (ox, eta, degrees, title) in enumerate(((230, 1 / 1.5, 40.0, "air into glass (eta = 1 / 1.5)"),
                                                       (670, 1.5, 50.0, "glass into air past the critical angle"))):
        f = Frame(ox, 230, 60)
        svg.text(ox, 62, title, size=15, anchor="middle", weight="bold")
        dense_below = panel == 0
        svg.polyline([f(-3.3, 0), f(3.3, 0), f(3.3, -2.6), f(-3.3, -2.6)], colour=None,
                     fill="#dcebf7" if dense_below else "#f4f4f4", close=True)
        if not dense_below:
            svg.polyline([f(-3.3, 0), f(3.3, 0), f(3.3, 2.6), f(-3.3, 2.6)], colour=None, fill="#dcebf7", close=True)
        svg.line(*f(-3.3, 0), *f(3.3, 0), SURFACE, 3)
        svg.text(*f(-3.2, -0.4) if dense_below else f(-3.2, 0.3), "glass" if dense_below else "glass (above)",
                 size=13, colour=SURFACE)
        a = math.radians(degrees)
        # The ray arrives from above in panel 0 (air), from above in panel 1 as well (inside the glass).
        d = (math.sin(a), -math.cos(a))
        start = (-2.4 * d[0], -2.4 * d[1])
        svg.line(*f(*start), *f(0, 0), RAY, 2.8, arrow=True)
        svg.text(*f(start[0] - 0.1, start[1] + 0.15), "d", size=18, colour=RAY, italic=True, weight="bold")
        svg.line(*f(0, 0), *f(0, 2.3), NORMAL, 2.5, arrow=True)
        svg.text(*f(0.12, 2.2), "n", size=18, colour=NORMAL, italic=True, weight="bold")
        svg.line(*f(0, 0), *f(0, -2.3), GUIDE, 1.2, dash="4 4")
        r = (d[0], -d[1])
        svg.line(*f(0, 0), *f(2.4 * r[0], 2.4 * r[1]), HALF, 2.8, arrow=True)
        svg.text(*f(2.4 * r[0] + 0.1, 2.4 * r[1]), "r = d − 2 (d·n) n" if panel == 0 else "r", size=14 if panel == 0 else 18,
                 colour=HALF, italic=panel == 1, weight="bold" if panel == 1 else None)
        # the angle of incidence
        arc = 0.8
        S, E = f(0, arc), f(-arc * math.sin(a), arc * math.cos(a))
        svg.path(f"M{num(S[0])},{num(S[1])} A{num(arc * f.s)},{num(arc * f.s)} 0 0 0 {num(E[0])},{num(E[1])}", RAY, 1.5)
        svg.text(*f(-0.45, 1.05), "θi", size=15, colour=RAY, italic=True)
        sin_t = eta * math.sin(a)
        if sin_t <= 1:
            b = math.asin(sin_t)
            t = (math.sin(b), -math.cos(b))
            svg.line(*f(0, 0), *f(2.4 * t[0], 2.4 * t[1]), LIGHT, 2.8, arrow=True)
            svg.text(*f(2.4 * t[0] + 0.1, 2.4 * t[1] - 0.1), "t", size=18, colour=LIGHT, italic=True, weight="bold")
            S, E = f(0, -arc), f(arc * math.sin(b), -arc * math.cos(b))
            svg.path(f"M{num(S[0])},{num(S[1])} A{num(arc * f.s)},{num(arc * f.s)} 0 0 0 {num(E[0])},{num(E[1])}",
                     LIGHT, 1.5)
            svg.text(*f(0.2, -1.15), "θt", size=15, colour=LIGHT, italic=True)
            svg.text(ox, 400, "sin θt = eta sin θi: bent towards the normal", size=14, anchor="middle")
        else:
            svg.text(*f(0.3, -1.0), "no t: eta² (1 − cos² θi) > 1", size=14, colour=HIT)
            svg.text(ox, 400, "past sin θc = 1 / eta all light is reflected", size=14, anchor="middle")
    svg.text(20, 424, "t = eta u + (eta cos θi − cos θt) n,   cos θt = sqrt(1 − eta² (1 − cos² θi)),   "
             "u = d / |d|,  eta = n_i / n_t", size=13, colour=GUIDE)
    return svg


def spawn_offset():
    svg = Svg(900, 440, "Where a secondary ray starts")
    svg.text(20, 30, "The error box of a hit point, pushed off the surface along n to the side the ray leaves by",
             size=16, weight="bold")
    f = Frame(300, 250, 70)
    svg.polyline([f(-4, 0), f(4, 0), f(4, -2.2), f(-4, -2.2)], colour=None, fill="#dcebf7", close=True)
    svg.line(*f(-4, 0), *f(4, 0), SURFACE, 3)
    svg.text(*f(-3.9, -1.1), "inside (glass)", size=13, colour=SURFACE)
    svg.text(*f(-3.9, 0.25), "outside", size=13, colour=SURFACE)
    # the computed point and its error box (exaggerated)
    p = (-0.4, -0.15)
    e = (0.55, 0.45)
    svg.rect(*f(p[0] - e[0], p[1] + e[1]), 2 * e[0] * f.s, 2 * e[1] * f.s, HIT, 1.6, fill="#f3c7c2", opacity=0.5)
    svg.dot(*f(*p), HIT, 5)
    svg.text(*f(p[0] - e[0] - 0.15, p[1] - 0.05), "computed point ± error", size=13, colour=HIT, anchor="end")
    n = unit(0.35, 1.0)
    reach = abs(n[0]) * e[0] + abs(n[1]) * e[1]
    up = (p[0] + reach * n[0], p[1] + reach * n[1])
    down = (p[0] - reach * n[0], p[1] - reach * n[1])
    svg.line(*f(*p), *f(*up), NORMAL, 2.4, arrow=True)
    svg.line(*f(*p), *f(*down), NORMAL, 2.4, arrow=True)
    svg.text(*f(up[0] + 0.1, up[1] + 0.1), "+ dot(|n|, error) n", size=13, colour=NORMAL)
    svg.text(*f(down[0] + 0.15, down[1] - 0.1), "− dot(|n|, error) n", size=13, colour=NORMAL)
    # the reflected ray from the upper origin, the refracted one from the lower
    svg.line(*f(*up), *f(up[0] + 2.6, up[1] + 1.6), HALF, 2.5, arrow=True)
    svg.text(*f(up[0] + 2.2, up[1] + 1.75), "reflected: starts outside", size=13, colour=HALF)
    svg.line(*f(*down), *f(down[0] + 1.9, down[1] - 1.6), LIGHT, 2.5, arrow=True)
    svg.text(*f(down[0] + 0.75, down[1] - 1.0), "refracted: starts inside", size=13, colour=LIGHT, anchor="end")
    # a thin shell: a second surface just below
    y2 = -1.55
    svg.line(*f(-4, y2), *f(4, y2), SURFACE, 2, dash="8 5")
    svg.text(*f(1.75, y2 + 0.12), "a thin shell's far wall: the refracted", size=13, colour=SURFACE)
    svg.text(*f(1.75, y2 - 0.3), "ray must still meet it", size=13, colour=SURFACE)
    x = 640
    svg.text(x, 90, "Not along the ray: a grazing", size=14)
    svg.text(x, 110, "ray slides along the surface", size=14)
    svg.text(x, 130, "and stays inside the error box.", size=14)
    svg.text(x, 170, "Not a fixed epsilon: too small", size=14)
    svg.text(x, 190, "at 1e6, too large for a 1e-4", size=14)
    svg.text(x, 210, "thick pane.", size=14)
    svg.text(x, 250, "The error box comes from the", size=14)
    svg.text(x, 270, "rounding of putting the point", size=14)
    svg.text(x, 290, "back on the surface: gamma(n)", size=14)
    svg.text(x, 310, "times the sizes involved.", size=14)
    svg.text(20, 428, "dot(|n|, error) is the box projected on the normal: how far along n the exact surface "
             "may be from the computed point.", size=13, colour=GUIDE)
    return svg


# ---- chapter 10 -------------------------------------------------------------------

def normals_figure():
    """Chapter 10: a circle stretched into an ellipse; at one point the tangent maps to A t, the
    normal by A n leans off the surface, the inverse transpose stays perpendicular."""
    svg = Svg(640, 300, "Normals under a non-uniform scale: A n against (A^-1)^T n")
    left, right = Frame(140, 160, 80), Frame(430, 160, 80)
    sx, sy = 2.2, 0.7
    pts = [(math.cos(2 * math.pi * k / 96), math.sin(2 * math.pi * k / 96)) for k in range(97)]
    svg.polyline([left(x, y) for x, y in pts], colour=SURFACE)
    svg.polyline([right(sx * x, sy * y) for x, y in pts], colour=SURFACE)
    a = math.radians(50)
    p, n, t = (math.cos(a), math.sin(a)), (math.cos(a), math.sin(a)), (-math.sin(a), math.cos(a))
    svg.dot(*left(*p))
    svg.line(*left(*p), *left(p[0] + 0.7 * n[0], p[1] + 0.7 * n[1]), colour=NORMAL, arrow=True)
    svg.line(*left(p[0] - 0.6 * t[0], p[1] - 0.6 * t[1]), *left(p[0] + 0.6 * t[0], p[1] + 0.6 * t[1]),
             colour=GUIDE, dash="5,4")
    svg.text(*left(p[0] + 0.75 * n[0], p[1] + 0.8 * n[1]), "n", colour=NORMAL)
    svg.text(140, 285, "object space: the unit circle", anchor="middle")
    q = (sx * p[0], sy * p[1])
    at = unit(sx * t[0], sy * t[1])
    wrong = unit(sx * n[0], sy * n[1])
    right_n = unit(n[0] / sx, n[1] / sy)
    svg.dot(*right(*q))
    svg.line(*right(q[0] - 0.8 * at[0], q[1] - 0.8 * at[1]), *right(q[0] + 0.8 * at[0], q[1] + 0.8 * at[1]),
             colour=GUIDE, dash="5,4")
    svg.line(*right(*q), *right(q[0] + 0.8 * wrong[0], q[1] + 0.8 * wrong[1]), colour=HIT, arrow=True)
    svg.line(*right(*q), *right(q[0] + 0.8 * right_n[0], q[1] + 0.8 * right_n[1]), colour=NORMAL, arrow=True)
    svg.text(*right(q[0] + 0.85 * wrong[0] + 0.05, q[1] + 0.85 * wrong[1]), "A n (wrong)", colour=HIT)
    svg.text(*right(q[0] + 0.85 * right_n[0] - 0.1, q[1] + 0.85 * right_n[1] + 0.12), "(A⁻¹)ᵀ n",
             colour=NORMAL, anchor="end")
    svg.text(*right(q[0] + 0.8 * at[0] + 0.05, q[1] + 0.8 * at[1] - 0.1), "A t", colour=GUIDE)
    svg.text(430, 285, "world: scaled by (2.2, 0.7)", anchor="middle")
    return svg


def instance_box_figure():
    """Chapter 10: a box turned by 30 degrees: the box of the images of lo and hi alone, and the box
    of all four (in 3D: eight) corners' images."""
    svg = Svg(640, 300, "The box of a placed box: all corners, not lo and hi alone")
    f = Frame(320, 150, 52)
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    corners = [(-1.6, -0.8), (1.6, -0.8), (1.6, 0.8), (-1.6, 0.8)]
    turned = [(c * x - s * y, s * x + c * y) for x, y in corners]
    svg.polyline([f(*q) for q in turned], colour=SURFACE, fill=FILLS[1], opacity=0.6, close=True)
    lo, hi = turned[0], turned[2]
    xs, ys = [q[0] for q in turned], [q[1] for q in turned]
    svg.rect(*f(min(xs), max(ys)), (max(xs) - min(xs)) * 52, (max(ys) - min(ys)) * 52, colour=NORMAL, width=2.5)
    x0, x1, y0, y1 = min(lo[0], hi[0]), max(lo[0], hi[0]), min(lo[1], hi[1]), max(lo[1], hi[1])
    svg.rect(*f(x0, y1), (x1 - x0) * 52, (y1 - y0) * 52, colour=HIT, dash="7,5")
    for q, name in ((lo, "A lo + b"), (hi, "A hi + b")):
        svg.dot(*f(*q), colour=HIT)
        svg.text(*f(q[0] + 0.1, q[1] - 0.3 if q is lo else q[1] + 0.15), name, colour=HIT)
    for q in (turned[1], turned[3]):
        svg.dot(*f(*q), colour=NORMAL)
    svg.text(20, 30, "dashed: the box of lo and hi only (two corners stick out)", colour=HIT)
    svg.text(20, 285, "solid: the box of every corner's image, then widened against rounding", colour=NORMAL)
    return svg


# Every figure: where it goes (relative to the repository) and what draws it.
# ---- chapter 11: where the samples go, the light's cone, the thin lens ------------------------------


def _lcg_points(count, seed):
    """Deterministic pseudo-random numbers in [0, 1) for the figure (a 32-bit LCG, Numerical Recipes' constants)."""
    state, out = seed, []
    for _ in range(count):
        state = (1664525 * state + 1013904223) % 2 ** 32
        out.append(state / 2 ** 32)
    return out


def _radical_inverse(base, i):
    inverse, scale = 0.0, 1.0 / base
    while i > 0:
        inverse += (i % base) * scale
        i //= base
        scale /= base
    return inverse


def sample_patterns():
    svg = Svg(900, 380, "Sixteen samples of a pixel: random, stratified, Halton")
    svg.text(20, 30, "Sixteen samples of one pixel, three ways", size=17, weight="bold")
    side, top = 240, 70
    u = _lcg_points(64, 11)
    panels = [
        ("random: clumps and holes", [(u[2 * k], u[2 * k + 1]) for k in range(16)], False),
        ("stratified: one per cell of 4 x 4", [((k % 4 + u[32 + 2 * k]) / 4, (k // 4 + u[33 + 2 * k]) / 4)
                                               for k in range(16)], True),
        ("Halton (bases 2, 3): fills every gap", [(_radical_inverse(2, k), _radical_inverse(3, k))
                                                  for k in range(16)], False),
    ]
    for p, (title, points, grid) in enumerate(panels):
        x0 = 40 + p * (side + 45)
        svg.rect(x0, top, side, side, SURFACE, 2)
        if grid:
            for i in range(1, 4):
                svg.line(x0 + i * side / 4, top, x0 + i * side / 4, top + side, GUIDE, 1, dash="4 4")
                svg.line(x0, top + i * side / 4, x0 + side, top + i * side / 4, GUIDE, 1, dash="4 4")
        for x, y in points:
            svg.dot(x0 + x * side, top + y * side, RAY, 5)
        svg.text(x0 + side / 2, top + side + 28, title, size=14, anchor="middle")
    svg.text(20, 368, "Same count, same cost: the stratified and Halton points leave no region of the pixel "
             "unsampled, which is why their error falls faster.", size=13, colour=GUIDE)
    return svg


def light_cone_and_lens():
    svg = Svg(900, 420, "The cone a sphere light fills, and the thin lens")
    svg.text(20, 30, "Left: a sphere light seen from x.  Right: a thin lens focused at distance f.", size=17,
             weight="bold")
    # left: the cone
    f = Frame(60, 250, 60)
    x = (0.0, 0.0)
    c, r = (5.0, 1.2), 1.0
    X, C = f(*x), f(*c)
    d = math.hypot(c[0] - x[0], c[1] - x[1])
    theta_max = math.asin(r / d)
    axis = math.atan2(c[1] - x[1], c[0] - x[0])
    svg.circle(*C, r * f.s, LIGHT, 2.5, fill="#fff0b3")
    svg.text(C[0] + r * f.s + 8, C[1] + 5, "light (r)", size=14, colour=LIGHT)
    for sgn in (-1, 1):
        a = axis + sgn * theta_max
        t = d * math.cos(theta_max)
        svg.line(*X, *f(x[0] + t * math.cos(a), x[1] + t * math.sin(a)), GUIDE, 1.5, dash="6 4")
    svg.line(*X, *C, GUIDE, 1.5)
    svg.text((X[0] + C[0]) / 2 - 10, (X[1] + C[1]) / 2 + 22, "d", size=15, italic=True, colour=GUIDE)
    a = axis + 0.45 * theta_max
    e = 1 - math.cos(0.45 * theta_max)
    tt = d * math.cos(0.45 * theta_max) - math.sqrt(max(0.0, r * r - d * d * e * (2 - e)))
    P = f(x[0] + tt * math.cos(a), x[1] + tt * math.sin(a))
    svg.line(*X, *P, RAY, 2.5, arrow=True)
    svg.dot(*P, HIT, 5)
    svg.text(P[0] - 6, P[1] - 12, "sample point", size=13, colour=HIT, anchor="end")
    svg.dot(*X, INK, 5)
    svg.text(X[0] - 8, X[1] + 22, "x", size=15, italic=True)
    svg.text(30, 330, "sin² θmax = (r / d)²,  solid angle 2π (1 − cos θmax)", size=14)
    svg.text(30, 352, "pdf = 1 / (2π (1 − cos θmax)) per steradian", size=14)
    svg.text(30, 374, "1 − cos θmax = s / (1 + √(1 − s)), s = (r/d)²: no cancellation", size=14, colour=GUIDE)
    # right: the thin lens
    g = Frame(500, 200, 55)
    lens_h = 1.1
    svg.line(*g(0, -lens_h), *g(0, lens_h), VIEW, 4)
    svg.text(*g(-0.2, lens_h + 0.35), "lens (aperture)", size=13, colour=VIEW)
    focus = (5.5, 0.6)
    F = g(*focus)
    svg.line(*g(5.5, -1.8), *g(5.5, 1.8), GUIDE, 1.5, dash="6 4")
    svg.text(*g(5.4, -2.2), "plane in focus", size=13, colour=GUIDE, anchor="end")
    for y0 in (-lens_h * 0.9, 0.0, lens_h * 0.7):
        svg.line(*g(0, y0), *F, RAY, 2, arrow=False)
        svg.dot(*g(0, y0), RAY, 4)
    svg.dot(*F, HIT, 5)
    svg.text(F[0] - 6, F[1] - 12, "eye + f · d (in focus)", size=13, colour=HIT, anchor="end")
    svg.text(*g(0.2, -1.6), "eye + offset", size=13, colour=RAY)
    svg.text(480, 352, "direction = d − offset / f: every lens ray", size=14)
    svg.text(480, 374, "meets the point in focus at t = f;", size=14)
    svg.text(480, 396, "offset = aperture · √u.x · (cos 2πu.y, sin 2πu.y)", size=14, colour=GUIDE)
    return svg


FIGURES = {
    "chapters/01-unit-sphere/figures/roots.svg": unit_sphere_roots,
    "chapters/02-sphere/figures/geometric_derivation.svg": lambda: geometric_derivation("ch02"),
    "chapters/03-scene-loop/figures/shrinking_tmax.svg": shrinking_tmax,
    "chapters/04-plane/figures/plane.svg": plane_figure,
    "chapters/05-triangle/figures/half_planes_and_areas.svg": triangle_figure,
    "chapters/06-shading/figures/shading_vectors.svg": shading_vectors,
    "chapters/06-shading/figures/shadow_offset.svg": shadow_offset,
    "chapters/07-precision/figures/foot_of_perpendicular.svg": lambda: geometric_derivation("ch07"),
    "chapters/07-precision/figures/float_spacing.svg": float_spacing,
    "chapters/08-acceleration/figures/slabs.svg": slabs,
    "chapters/08-acceleration/figures/bvh.svg": bvh,
    "chapters/09-reflection/figures/reflect_refract.svg": reflect_refract,
    "chapters/09-reflection/figures/spawn_offset.svg": spawn_offset,
    "chapters/10-transforms/figures/normals.svg": normals_figure,
    "chapters/10-transforms/figures/instance_box.svg": instance_box_figure,
    "chapters/11-sampling/figures/sample_patterns.svg": sample_patterns,
    "chapters/11-sampling/figures/light_cone_and_lens.svg": light_cone_and_lens,
}


def write_all(root):
    written = []
    for rel, draw in FIGURES.items():
        path = os.path.join(root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8", newline="\n") as out:
            out.write(draw().render())
        written.append(rel)
    return written


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", help="write the figures under this folder instead of the repository")
    parser.add_argument("--check", metavar="DIR",
                        help="write the figures under DIR and compare them with the committed ones")
    args = parser.parse_args()
    if args.check:
        written = write_all(args.check)
        stale = []
        for rel in written:
            committed = os.path.join(REPO, rel)
            with open(os.path.join(args.check, rel), encoding="utf-8") as a:
                fresh = a.read()
            if not os.path.exists(committed):
                stale.append(f"{rel}: not committed")
                continue
            with open(committed, encoding="utf-8") as b:
                if b.read() != fresh:
                    stale.append(f"{rel}: differs from what the script draws")
        for line in stale:
            print(f"make_diagrams: {line}", file=sys.stderr)
        if stale:
            print("make_diagrams: run tools/diagrams/make_diagrams.py and commit the figures", file=sys.stderr)
            return 1
        print(f"make_diagrams: all {len(written)} figures match the script")
        return 0
    for rel in write_all(args.out or REPO):
        print(rel)
    return 0


if __name__ == "__main__":
    sys.exit(main())
