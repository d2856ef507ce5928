#!/usr/bin/python3
"""plot_sampling.py — chapter 11's error against samples and against time, from ch11-sampling-study's CSV.

    tools/study/plot_sampling.py [tools/study/results/ch11-sampling.csv] [--out chapters/11-sampling/figures]

Writes OUT/error_vs_samples.svg: one row per scene (edges, soft shadow), the
RMS error against samples per pixel on the left and against the render's time
per pixel on the right, all axes logarithmic; one colour per sequence (random,
stratified, Halton), solid lines for double and dashed for float, the fitted
slope of log(error) against log(samples) in the legend, and the n^(-1/2) line
for comparison.

Needs matplotlib (Debian's python3-matplotlib). Without it the script says so
and exits with status 0, writing nothing.
"""
import argparse
import csv
import math
import os
import sys

SEQUENCES = ["random", "stratified", "halton"]


def slope(points):
    xs = [math.log(x) for x, _ in points]
    ys = [math.log(y) for _, y in points]
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def main():
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("csv", nargs="?", default=os.path.join(root, "tools", "study", "results", "ch11-sampling.csv"))
    parser.add_argument("--out", default=os.path.join(root, "chapters", "11-sampling", "figures"))
    args = parser.parse_args()
    try:
        import matplotlib
        matplotlib.use("svg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("plot_sampling.py: matplotlib is not installed (Debian: python3-matplotlib); no diagram drawn")
        return 0
    matplotlib.rcParams["svg.hashsalt"] = "ch11-sampling"  # the same file on every run
    matplotlib.rcParams["svg.fonttype"] = "none"

    with open(args.csv, newline="") as f:
        rows = list(csv.DictReader(f))
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, axes = plt.subplots(len(scenes), 2, figsize=(10, 4.2 * len(scenes)), squeeze=False)
    for row_axes, scene in zip(axes, scenes):
        for k, seq in enumerate(SEQUENCES):
            for prec, style in (("double", "-"), ("float", "--")):
                sel = [r for r in rows if r["scene"] == scene and r["sequence"] == seq and r["precision"] == prec]
                if not sel:
                    continue
                spp = [int(r["spp"]) for r in sel]
                err = [float(r["rms_error"]) for r in sel]
                ns = [float(r["ns_per_pixel"]) for r in sel]
                s = slope(list(zip(spp, err)))
                label = f"{seq}, {prec}: slope {s:.2f}"
                row_axes[0].plot(spp, err, style, marker="o", color=f"C{k}", label=label)
                row_axes[1].plot(ns, err, style, marker="o", color=f"C{k}", label=f"{seq}, {prec}")
        first = [r for r in rows if r["scene"] == scene and r["sequence"] == "random" and r["precision"] == "double"]
        if first:
            e1 = float(first[0]["rms_error"])
            spp_max = max(int(r["spp"]) for r in first)
            row_axes[0].plot([1, spp_max], [e1, e1 * spp_max ** -0.5], ":", color="grey", label="n^(-1/2)")
        for ax, xlabel in zip(row_axes, ("samples per pixel", "render time per pixel (ns, both threads, under load)")):
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel(xlabel)
            ax.set_ylabel("RMS error against the reference")
            ax.set_title(f"{scene}")
            ax.grid(True, which="major", alpha=0.3)
        row_axes[0].legend(fontsize=8, frameon=False)
    fig.tight_layout()
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, "error_vs_samples.svg")
    fig.savefig(path, metadata={"Date": None})
    plt.close(fig)
    print(f"plot_sampling.py: wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
