#!/usr/bin/env python3
"""plot_scaling.py - time per ray against N from an rt-bench run, as SVG.

    build/release/bin/rt-bench > bench.txt
    tools/bench/plot_scaling.py bench.txt tools/bench/scaling.svg

Reads section 4 of rt-bench's output (the "N = ..." rows: our BVH and
Embree on N random spheres) and draws the time per ray of each against N on
a logarithmic N axis: a tree's cost grows like log N, which is a straight
line there. Standard library only; the SVG is written by hand.
"""
import re
import sys


def read_rows(path):
    rows = []
    for line in open(path, encoding="utf-8"):
        if not re.match(r"\s*N = \d+", line):
            continue
        cells = [c.strip() for c in line.split("|")]
        n = int(cells[0].split("=")[1])
        row = {"N": n, "build_ms_per_M": float(cells[3]), "ours_ns": float(cells[5])}
        if len(cells) > 9 and re.match(r"^[0-9.]+$", cells[9]):
            row["embree_ns"] = float(cells[9])
        rows.append(row)
    return rows


def svg(rows, out):
    import math

    w, h, left, right, top, bottom = 640, 400, 70, 20, 40, 50
    xs = [math.log10(r["N"]) for r in rows]
    series = [("ours (BVH, 32-ray packets)", "ours_ns", "#c0392b"), ("Embree rtcIntersect1", "embree_ns", "#2c3e50")]
    ys = [r[k] for r in rows for _, k, _ in series if k in r]
    x0, x1 = min(xs) - 0.1, max(xs) + 0.1
    y1 = max(ys) * 1.15
    px = lambda x: left + (x - x0) / (x1 - x0) * (w - left - right)
    py = lambda y: h - bottom - y / y1 * (h - top - bottom)
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="12">',
             f'<rect width="{w}" height="{h}" fill="white"/>',
             f'<text x="{w / 2}" y="20" text-anchor="middle" font-size="14">time per primary ray (one thread) against N random spheres</text>',
             f'<line x1="{left}" y1="{h - bottom}" x2="{w - right}" y2="{h - bottom}" stroke="black"/>',
             f'<line x1="{left}" y1="{top}" x2="{left}" y2="{h - bottom}" stroke="black"/>',
             f'<text x="{w / 2}" y="{h - 12}" text-anchor="middle">N (log scale)</text>',
             f'<text x="16" y="{h / 2}" transform="rotate(-90 16 {h / 2})" text-anchor="middle">ns per ray</text>']
    for r, x in zip(rows, xs):
        parts.append(f'<text x="{px(x):.1f}" y="{h - bottom + 16}" text-anchor="middle">{r["N"]:,}</text>')
    for i in range(5):
        y = y1 * i / 4
        parts.append(f'<text x="{left - 6}" y="{py(y) + 4:.1f}" text-anchor="end">{y:.0f}</text>')
        parts.append(f'<line x1="{left}" y1="{py(y):.1f}" x2="{w - right}" y2="{py(y):.1f}" stroke="#ddd"/>')
    for j, (name, key, colour) in enumerate(series):
        pts = [(px(x), py(r[key])) for r, x in zip(rows, xs) if key in r]
        if not pts:
            continue
        parts.append('<polyline fill="none" stroke="%s" stroke-width="2" points="%s"/>'
                     % (colour, " ".join(f"{a:.1f},{b:.1f}" for a, b in pts)))
        parts += [f'<circle cx="{a:.1f}" cy="{b:.1f}" r="3" fill="{colour}"/>' for a, b in pts]
        parts.append(f'<text x="{left + 10}" y="{top + 16 + 16 * j}" fill="{colour}">{name}</text>')
    parts.append("</svg>")
    open(out, "w", encoding="utf-8").write("\n".join(parts) + "\n")


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_scaling.py RT_BENCH_OUTPUT OUT.svg")
    rows = read_rows(sys.argv[1])
    if not rows:
        sys.exit(f"{sys.argv[1]}: no 'N = ...' rows (section 4 of rt-bench's output)")
    svg(rows, sys.argv[2])
    print(f"wrote {sys.argv[2]} ({len(rows)} points)")


if __name__ == "__main__":
    main()
