#!/usr/bin/env python3
"""convergence.png from a `gonio bench --out DIR` run: usage bench_plot.py DIR.

Per stack: relative RMS error against a 2^25-path run and the median relative standard error of the bins
above 1% of their slice's peak, against paths and against seconds (log-log), with the 1/sqrt(N) line; and
the seconds each stack needs for a median relative standard error of 1% and 0.1%, extrapolated along 1/sqrt(N).
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(out):
    with open(os.path.join(out, "bench.json")) as fh:
        bench = json.load(fh)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for k, st in enumerate(bench["stacks"]):
        conv = st.get("convergence") or []
        if not conv:
            continue
        colour = f"C{k}"
        paths = [c["paths"] for c in conv]
        secs = [c["seconds"] for c in conv]
        for ax, x in ((axes[0], paths), (axes[1], secs)):
            ax.loglog(x, [c["relative_rmse"] for c in conv], "-o", color=colour, ms=3, label=f"{st['stack']} RMSE vs long run")
            ax.loglog(x, [c["median_rse"] for c in conv], "--", color=colour, label=f"{st['stack']} median rse")
        last = conv[-1]
        n1 = last["paths"] * (last["median_rse"] / 0.01) ** 2
        rate = st["paths_per_second"]
        st["seconds_to_rse_1pct"] = n1 / rate
        st["seconds_to_rse_0_1pct"] = 100 * n1 / rate
    ref = bench["stacks"][0].get("convergence") or []
    if ref:
        n0, e0 = ref[0]["paths"], ref[0]["median_rse"]
        xs = [c["paths"] for c in ref]
        axes[0].loglog(xs, [e0 * (n0 / x) ** 0.5 for x in xs], "k:", label="1/sqrt(N)")
    axes[0].set_xlabel("paths per incident angle")
    axes[1].set_xlabel("seconds (wall clock)")
    for ax in axes:
        ax.set_ylabel("relative error")
        ax.grid(True, which="both", alpha=0.3)
    axes[1].legend(fontsize=7)
    fig.suptitle(f"reference convergence on {bench['device']}, theta_i = {bench['theta_i']:g}")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "convergence.png"), dpi=110)
    with open(os.path.join(out, "bench.json"), "w") as fh:
        json.dump(bench, fh, indent=2)
    for st in bench["stacks"]:
        if "seconds_to_rse_1pct" in st:
            print(f"{st['stack']}: median relative standard error 1% in {st['seconds_to_rse_1pct']:.3g} s, "
                  f"0.1% in {st['seconds_to_rse_0_1pct']:.3g} s (extrapolated along 1/sqrt(N))")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
