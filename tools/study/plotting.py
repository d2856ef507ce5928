"""plotting.py — what the studies' diagrams share: the command line, matplotlib's set-up, the fitted
slope, the error-against-count-and-time lines of one series and the saved file.

Imported by plot_sampling.py (chapter 11) and plot_path_tracing.py (chapter 12), whose diagrams are
drawn the same way; plot.py uses the matplotlib set-up only.
"""
import argparse
import csv
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PRECISIONS = (("double", "-"), ("float", "--"))  # solid lines for double, dashed for float


def begin(doc, script, salt, csv_default, out_default):
    """A study diagram's start: its command line (the CSV, optional, and --out, both relative to the
    repository), matplotlib and the CSV's rows, as (plt, args, rows). Without matplotlib it exits with
    status 0, having said so: the diagrams are optional."""
    parser = argparse.ArgumentParser(description=doc.split("\n")[0])
    parser.add_argument("csv", nargs="?", default=os.path.join(ROOT, *csv_default))
    parser.add_argument("--out", default=os.path.join(ROOT, *out_default))
    args = parser.parse_args()
    plt = pyplot(script, salt)
    if plt is None:
        sys.exit(0)
    return plt, args, read_rows(args.csv)


def pyplot(script, salt, nothing="no diagram drawn"):
    """matplotlib.pyplot drawing SVG files that are the same on every run; None, said, without matplotlib."""
    try:
        import matplotlib
        matplotlib.use("svg")
        import matplotlib.pyplot as plt
    except ImportError:
        print(f"{script}: matplotlib is not installed (Debian: python3-matplotlib); {nothing}")
        return None
    matplotlib.rcParams["svg.hashsalt"] = salt  # the same file on every run
    matplotlib.rcParams["svg.fonttype"] = "none"
    return plt


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def slope(points):
    """The least-squares slope of log(y) against log(x)."""
    xs = [math.log(x) for x, _ in points]
    ys = [math.log(y) for _, y in points]
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)


def plot_series(by_spp, by_time, rows, colour, label, error, ns):
    """One series' rows, a line for each precision: error against spp on by_spp (its fitted slope in the
    legend) and against time on by_time. error is the CSV's column, ns(row) the row's time."""
    for prec, style in PRECISIONS:
        sel = [r for r in rows if r["precision"] == prec]
        if not sel:
            continue
        spp = [int(r["spp"]) for r in sel]
        err = [float(r[error]) for r in sel]
        s = slope(list(zip(spp, err)))
        by_spp.plot(spp, err, style, marker="o", color=colour, label=f"{label}, {prec}: slope {s:.2f}")
        by_time.plot([ns(r) for r in sel], err, style, marker="o", color=colour, label=f"{label}, {prec}")


def plot_half_slope(ax, rows, error):
    """The n^(-1/2) line for comparison, from the first of rows (one series, one precision)."""
    if rows:
        e1 = float(rows[0][error])
        spp_max = max(int(r["spp"]) for r in rows)
        ax.plot([1, spp_max], [e1, e1 * spp_max ** -0.5], ":", color="grey", label="n^(-1/2)")


def log_axes(ax, xlabel, ylabel, title):
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, which="major", alpha=0.3)


def save(plt, fig, out, name, script):
    """The diagram as OUT/NAME, without a date so that the file is the same on every run."""
    fig.tight_layout()
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, name)
    fig.savefig(path, metadata={"Date": None})
    plt.close(fig)
    print(f"{script}: wrote {path}")
