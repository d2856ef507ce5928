#!/usr/bin/python3
"""plot_path_tracing.py — chapter 12's error against time for the four estimators, from ch12-path-study's CSV.

    tools/study/plot_path_tracing.py [tools/study/results/ch12-path-study.csv] [--out chapters/12-path-tracing/figures]

Writes OUT/error_vs_time.svg: the RMS error against the render's processor
time per pixel on the left and against paths per pixel on the right, all axes
logarithmic; one colour per estimator (uniform, cosine, next-event
estimation, both), solid lines for double and dashed for float, the fitted
slope of log(error) against log(paths) in the legend, and a slope of -1/2
for comparison. Lower and further left is better: at equal error, the
horizontal distance between two lines is their ratio of cost.

Needs matplotlib (Debian's python3-matplotlib). Without it the script says so
and exits with status 0, writing nothing.
"""
import argparse
import csv
import os
import sys

from plot_sampling import slope  # the same least-squares fit as chapter 11's diagram

ESTIMATORS = [("uniform", "uniform bounces"), ("cosine", "cosine bounces"),
              ("nee", "next-event, uniform bounces"), ("both", "next-event, cosine bounces")]


def main():
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("csv", nargs="?", default=os.path.join(root, "tools", "study", "results", "ch12-path-study.csv"))
    parser.add_argument("--out", default=os.path.join(root, "chapters", "12-path-tracing", "figures"))
    args = parser.parse_args()
    try:
        import matplotlib
        matplotlib.use("svg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("plot_path_tracing.py: matplotlib is not installed (Debian: python3-matplotlib); no diagram drawn")
        return 0
    matplotlib.rcParams["svg.hashsalt"] = "ch12-path-tracing"  # the same file on every run
    matplotlib.rcParams["svg.fonttype"] = "none"

    with open(args.csv, newline="") as f:
        rows = list(csv.DictReader(f))
    fig, (by_time, by_paths) = plt.subplots(1, 2, figsize=(11, 4.6))
    for k, (name, label) in enumerate(ESTIMATORS):
        for prec, style in (("double", "-"), ("float", "--")):
            sel = [r for r in rows if r["estimator"] == name and r["precision"] == prec]
            if not sel:
                continue
            spp = [int(r["spp"]) for r in sel]
            err = [float(r["rms_error_less_reference_noise"]) for r in sel]
            ns = [float(r["cpu_ns_per_path"]) * int(r["spp"]) for r in sel]
            s = slope(list(zip(spp, err)))
            by_time.plot(ns, err, style, marker="o", color=f"C{k}", label=f"{label}, {prec}")
            by_paths.plot(spp, err, style, marker="o", color=f"C{k}", label=f"{label}, {prec}: slope {s:.2f}")
    first = [r for r in rows if r["estimator"] == "uniform" and r["precision"] == "double"]
    if first:
        e1 = float(first[0]["rms_error_less_reference_noise"])
        spp_max = max(int(r["spp"]) for r in first)
        by_paths.plot([1, spp_max], [e1, e1 * spp_max ** -0.5], ":", color="grey", label="n^(-1/2)")
    for ax, xlabel in ((by_time, "processor time per pixel (ns, both threads' CPU time)"),
                       (by_paths, "paths per pixel")):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(xlabel)
        ax.set_ylabel("RMS error (the reference's own noise taken out)")
        ax.set_title("the Cornell box")
        ax.grid(True, which="major", alpha=0.3)
    by_time.legend(fontsize=7, frameon=False)
    by_paths.legend(fontsize=7, frameon=False)
    fig.tight_layout()
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, "error_vs_time.svg")
    fig.savefig(path, metadata={"Date": None})
    plt.close(fig)
    print(f"plot_path_tracing.py: wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
