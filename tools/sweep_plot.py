#!/usr/bin/env python3
"""Figures of a gonio sweep (gonio sweep / gonio merge run it): usage: sweep_plot.py SWEEP_OUTPUT_DIR

  error-vs-<parameter>.png  each model's RMSE of log(1 + sqrt f) (reflection side) against each varied
                            parameter, averaged over the other parameters and the incident angles; in a [spectral]
                            sweep the albedo's CIEDE2000 against the spectral reference, the RGB run's too (rgb-run)
  atlas.png                 which model is closest to the reference where: the best model per cell of the first
                            two varied parameters (or the parameter and the incident angle), one panel per angle
  fit-<model>-<key>.png     a [[fit]]'s fitted value of a key, with its standard error, against the first varied
                            parameter, a line per combination of the others (unconstrained and not-fitted left out)
  sweep.html                the figures
"""
import csv
import html
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

COLOURS = ["tab:red", "tab:orange", "tab:pink", "tab:cyan", "tab:blue", "tab:green", "tab:purple", "tab:brown"]
# the convention variants (ids with a '+', docs/MODELS.md) get the light shades of matplotlib's tab20
VARIANT_COLOURS = [matplotlib.colormaps["tab20"](i) for i in range(1, 20, 2)] + [matplotlib.colormaps["tab20b"](i) for i in range(0, 20, 4)]


def fit_figures(out, header, rows, params):
    """[[fit]] columns (fit.MODEL.KEY, .se, .status): the fitted value against the first varied parameter"""
    col = {h: i for i, h in enumerate(header)}
    per_config = {}   # the fit columns are the same on every row of a configuration
    for r in rows:
        per_config.setdefault(r[col["config"]], r)
    names = []
    for f in sorted({h for h in header if h.startswith("fit.") and h + ".status" in col}):
        lines = defaultdict(list)
        for r in per_config.values():
            if r[col[f + ".status"]] not in ("fitted", "at-limit"):
                continue
            others = tuple(f"{p} {float(r[col[p]]):.3g}" for p in params[1:])
            lines[others].append((float(r[col[params[0]]]), float(r[col[f]]), float(r[col[f + ".se"]])))
        fig, ax = plt.subplots(figsize=(5.5 + (2.5 if len(lines) > 1 else 0.0), 3.8), layout="constrained")
        palette = COLOURS if len(lines) <= len(COLOURS) else [matplotlib.colormaps["turbo"](x)
                                                               for x in np.linspace(0.05, 0.95, len(lines))]
        for i, (others, pts) in enumerate(sorted(lines.items())):
            pts.sort()
            ax.errorbar([p[0] for p in pts], [p[1] for p in pts], yerr=[p[2] for p in pts], fmt="-o", ms=3,
                        capsize=2, color=palette[i % len(palette)], label=", ".join(others) or None)
        ax.set_xlabel(params[0])
        ax.set_ylabel(f[len("fit."):])
        ax.set_title(f"fitted {f[len('fit.'):]} (error bars: its standard error)", fontsize=9)
        if len(lines) > 1:
            ax.legend(fontsize=6, loc="center left", bbox_to_anchor=(1.02, 0.5), frameon=False)
        name = "fit-" + f[len("fit."):].replace("/", "_") + ".png"
        fig.savefig(os.path.join(out, name), dpi=100)
        plt.close(fig)
        names.append(name)
    return names


def main(out):
    with open(os.path.join(out, "sweep.csv")) as fh:
        reader = csv.reader(fh)
        header = next(reader)
        all_rows = list(reader)
        rows = [r for r in all_rows if r[header.index("model")] != "reference"]   # the models' rows only
    ti_col = header.index("theta_i")
    params = header[1:ti_col]
    col = {h: i for i, h in enumerate(header)}
    models = sorted({r[col["model"]] for r in rows}, key=lambda m: [r[col["model"]] for r in rows].index(m))
    defaults = [m for m in models if "+" not in m]
    variants = [m for m in models if "+" in m]
    colour = {m: COLOURS[i % len(COLOURS)] for i, m in enumerate(defaults)}
    colour.update({m: VARIANT_COLOURS[i % len(VARIANT_COLOURS)] for i, m in enumerate(variants)})
    refl = [r for r in rows if r[col["side"]] == "R"]
    figures = []
    # the error plotted: a [spectral] sweep's albedo CIEDE2000 (docs/SWEEPS.md), else the remapped RMSE
    spectral = "albedo_de2000" in col
    metric = "albedo_de2000" if spectral else "rmse_remapped"
    metric_label = "albedo CIEDE2000 against the spectral run" if spectral else "RMSE of log(1 + sqrt f)"

    # 1. error against each parameter
    for p in params:
        fig, ax = plt.subplots(figsize=(5.5, 3.8))
        for m in models:
            acc = defaultdict(list)
            for r in refl:
                if r[col["model"]] == m:
                    acc[float(r[col[p]])].append(float(r[col[metric]]))
            if not acc:
                continue
            xs = sorted(acc)
            ax.plot(xs, [np.mean(acc[x]) for x in xs], "-o", ms=3, color=colour[m], label=m)
        xs_all = sorted({float(r[col[p]]) for r in refl})
        if len(xs_all) > 2 and min(xs_all) > 0 and max(xs_all) / min(xs_all) > 20:
            ax.set_xscale("log")
        ax.set_xlabel(p)
        ax.set_ylabel(metric_label + ", mean")
        ax.set_title(f"error against {p}", fontsize=10)
        ax.legend(fontsize=7)
        fig.tight_layout()
        name = f"error-vs-{p}.png"
        fig.savefig(os.path.join(out, name), dpi=100)
        plt.close(fig)
        figures.append(name)

    # 2. atlas: the best model per cell
    angles = sorted({float(r[ti_col]) for r in refl})
    xname = params[0]
    yname = params[1] if len(params) > 1 else "theta_i"
    best = {}
    tied = defaultdict(set)   # models the reference's noise cannot tell from the best (sweep.csv: tied_with_best)
    for r in refl:
        if r[col["model"]] == "rgb-run":   # not a model: the stack's own RGB run
            continue
        key = (float(r[col[xname]]), float(r[col[yname]]) if yname != "theta_i" else float(r[ti_col]),
               float(r[ti_col]) if yname != "theta_i" else 0.0)
        e = float(r[col[metric]])
        if key not in best or e < best[key][1]:
            best[key] = (r[col["model"]], e)
        if "tied_with_best" in col and r[col["tied_with_best"]] == "1":
            tied[key].add(r[col["model"]])
    panels = angles if yname != "theta_i" else [0.0]
    xs = sorted({k[0] for k in best})
    ys = sorted({k[1] for k in best})
    fig, axes = plt.subplots(1, len(panels), figsize=(3.6 * len(panels) + 3.2, 4.0), squeeze=False, layout="constrained")
    for ax, a in zip(axes[0], panels):
        for (x, y, aa), (m, e) in best.items():
            if aa != a:
                continue
            ax.scatter(xs.index(x), ys.index(y), s=260, marker="s", color=colour[m])
            others = sorted(tied[(x, y, aa)] - {m})
            if others:   # a tie: the runner-up's colour inside, "tie" written
                ax.scatter(xs.index(x), ys.index(y), s=90, marker="s", color=colour[others[0]], edgecolors="white")
                ax.text(xs.index(x), ys.index(y) - 0.32, "tie", ha="center", va="center", fontsize=5, color="black")
            ax.text(xs.index(x), ys.index(y), f"{e:.2f}", ha="center", va="center", fontsize=6, color="white")
        ax.set_xticks(range(len(xs)), [f"{x:.3g}" for x in xs], fontsize=7, rotation=45)
        ax.set_yticks(range(len(ys)), [f"{y:.3g}" for y in ys], fontsize=7)
        ax.set_xlabel(xname)
        ax.set_ylabel(yname)
        ax.set_title(f"theta_i = {a:g}" if yname != "theta_i" else "all angles", fontsize=9)
    handles = [plt.Line2D([], [], marker="s", ls="", color=colour[m], label=m) for m in models]
    axes[0][-1].legend(handles=handles, loc="center left", bbox_to_anchor=(1.02, 0.5), fontsize=7, frameon=False)
    fig.suptitle(f"best model (lowest {metric_label}) per configuration; numbers: its value" +
                 ("" if spectral else ";\ninner square: a runner-up the reference's noise cannot tell from it (tie)"),
                 fontsize=8)
    fig.savefig(os.path.join(out, "atlas.png"), dpi=100)
    plt.close(fig)
    figures.append("atlas.png")

    figures += fit_figures(out, header, all_rows, params)

    with open(os.path.join(out, "sweep.html"), "w") as fh:
        fh.write("<!doctype html><html><head><meta charset='utf-8'><title>gonio sweep</title></head><body>"
                 f"<h1>gonio sweep: {html.escape(os.path.basename(os.path.abspath(out)))}</h1>"
                 f"<p>{len(rows)} rows in sweep.csv; parameters: {html.escape(', '.join(params))}.</p>"
                 + "".join(f"<h2>{html.escape(f)}</h2><img src='{html.escape(f)}'>" for f in figures) + "</body></html>")
    print(f"wrote {out}/{{{','.join(figures)},sweep.html}}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
