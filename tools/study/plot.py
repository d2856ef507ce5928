#!/usr/bin/python3
"""plot.py — one work-precision diagram per case family, from the study's CSV.

    tools/study/plot.py [tools/study/results/study.csv] [--out tools/study/results]

Writes OUT/work-precision-FAMILY.svg for every family of sphere formulations
in the CSV, spheres' and triangles' (the plane families, with one formulation
each, are left out; a space in a family's name becomes "-" in the file name). Each diagram is page width: the median time per query
across, the 99th percentile of t's relative error up, both logarithmic; one
marker shape per formulation, filled for double and hollow for float. Errors
of 0 cannot be drawn on a log axis and errors of 1 and more mean a wrong root,
so errors are clipped to [1e-17, 1] and the axis says so.

An optional part of the study: it needs matplotlib (Debian's
python3-matplotlib). Without it the script says so and exits with status 0,
writing nothing.
"""
import argparse
import csv
import os
import sys

from plotting import pyplot

FLOOR, CEILING = 1e-17, 1.0
MARKERS = "osD^v<>ph*X"


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("csv", nargs="?", default=os.path.join(here, "results", "study.csv"))
    parser.add_argument("--out", default=os.path.join(here, "results"))
    args = parser.parse_args()
    plt = pyplot("plot.py", "work-precision", "no diagrams drawn")
    if plt is None:
        return 0

    with open(args.csv, newline="") as f:
        rows = [r for r in csv.DictReader(f) if not r["family"].startswith("plane")]
    families = list(dict.fromkeys(r["family"] for r in rows))
    formulations = list(dict.fromkeys(r["formulation"] for r in rows))
    marker = {name: MARKERS[k % len(MARKERS)] for k, name in enumerate(formulations)}
    colour = {name: f"C{k % 10}" for k, name in enumerate(formulations)}

    for family in families:
        fig, ax = plt.subplots(figsize=(7.5, 4.2))
        clipped = False
        for r in (r for r in rows if r["family"] == family):
            err = float(r["rel_p99"])
            shown = min(max(err, FLOOR), CEILING)
            clipped = clipped or shown != err
            double = r["precision"] == "double"
            ax.plot(float(r["ns_median"]), shown, marker[r["formulation"]], markersize=8,
                    markeredgecolor=colour[r["formulation"]], markeredgewidth=1.5,
                    markerfacecolor=colour[r["formulation"]] if double else "none")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylim(FLOOR / 3, CEILING * 3)
        ax.set_xlabel("median time per query (ns, this thread's CPU time)")
        ax.set_ylabel("t's relative error, 99th percentile\n(clipped to [1e-17, 1]: 0 drawn at 1e-17)")
        ax.set_title(f"family '{family}': filled = double, hollow = float"
                     + ("" if clipped else " (no point clipped)"))
        ax.grid(True, which="major", alpha=0.3)
        present = [n for n in formulations if any(r["family"] == family and r["formulation"] == n for r in rows)]
        handles = [plt.Line2D([], [], linestyle="none", marker=marker[n], color=colour[n], markersize=8,
                              markerfacecolor="none", markeredgewidth=1.5, label=n) for n in present]
        ax.legend(handles=handles, loc="center left", bbox_to_anchor=(1.01, 0.5), fontsize=9, frameon=False)
        fig.tight_layout()
        path = os.path.join(args.out, f"work-precision-{family.replace(' ', '-')}.svg")
        fig.savefig(path, metadata={"Date": None})
        plt.close(fig)
        print(f"plot.py: wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
