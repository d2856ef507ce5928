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
import sys

from plotting import begin, log_axes, plot_half_slope, plot_series, save

ESTIMATORS = [("uniform", "uniform bounces"), ("cosine", "cosine bounces"),
              ("nee", "next-event, uniform bounces"), ("both", "next-event, cosine bounces")]


def main():
    plt, args, rows = begin(__doc__, "plot_path_tracing.py", "ch12-path-tracing", ("tools", "study", "results", "ch12-path-study.csv"),
                                ("chapters", "12-path-tracing", "figures"))
    fig, (by_time, by_paths) = plt.subplots(1, 2, figsize=(11, 4.6))
    for k, (name, label) in enumerate(ESTIMATORS):
        sel = [r for r in rows if r["estimator"] == name]
        plot_series(by_paths, by_time, sel, f"C{k}", label, "rms_error_less_reference_noise",
                    lambda r: float(r["cpu_ns_per_path"]) * int(r["spp"]))
    plot_half_slope(by_paths, [r for r in rows if r["estimator"] == "uniform" and r["precision"] == "double"],
                    "rms_error_less_reference_noise")
    for ax, xlabel in ((by_time, "processor time per pixel (ns, both threads' CPU time)"),
                       (by_paths, "paths per pixel")):
        log_axes(ax, xlabel, "RMS error (the reference's own noise taken out)", "the Cornell box")
    by_time.legend(fontsize=7, frameon=False)
    by_paths.legend(fontsize=7, frameon=False)
    save(plt, fig, args.out, "error_vs_time.svg", "plot_path_tracing.py")
    return 0


if __name__ == "__main__":
    sys.exit(main())
