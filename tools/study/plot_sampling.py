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
import sys

from plotting import begin, log_axes, plot_half_slope, plot_series, save

SEQUENCES = ["random", "stratified", "halton"]


def main():
    plt, args, rows = begin(__doc__, "plot_sampling.py", "ch11-sampling", ("tools", "study", "results", "ch11-sampling.csv"),
                                ("chapters", "11-sampling", "figures"))
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, axes = plt.subplots(len(scenes), 2, figsize=(10, 4.2 * len(scenes)), squeeze=False)
    for (by_spp, by_time), scene in zip(axes, scenes):
        for k, seq in enumerate(SEQUENCES):
            sel = [r for r in rows if r["scene"] == scene and r["sequence"] == seq]
            plot_series(by_spp, by_time, sel, f"C{k}", seq, "rms_error", lambda r: float(r["ns_per_pixel"]))
        plot_half_slope(by_spp, [r for r in rows if r["scene"] == scene and r["sequence"] == "random"
                                 and r["precision"] == "double"], "rms_error")
        for ax, xlabel in ((by_spp, "samples per pixel"), (by_time, "render time per pixel (ns, both threads, under load)")):
            log_axes(ax, xlabel, "RMS error against the reference", f"{scene}")
        by_spp.legend(fontsize=8, frameon=False)
    save(plt, fig, args.out, "error_vs_samples.svg", "plot_sampling.py")
    return 0


if __name__ == "__main__":
    sys.exit(main())
