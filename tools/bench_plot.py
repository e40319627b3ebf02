#!/usr/bin/env python3
"""Figures and bench.html of a `gonio bench --out DIR` run: usage bench_plot.py DIR.

Reads DIR/bench.json and writes, in DIR:
  convergence.png  per stack: relative RMS error against a 2^25-path run and the median relative standard
                   error of the bins above 1% of their slice's peak, against paths and seconds (log-log), with
                   the fitted c / sqrt(N) line of the median rse
  pareto.png       per stack and model: device cost (per evaluation of f, and per full bin-integrated grid of
                   one incident angle) against RMSE in log(1 + sqrt f) from the 2^25-path reference; the
                   reference's own runs (2^16 .. 2^23 paths) on the same axes, with their device seconds
  atlas.png        over random two-layer stacks (coat over a conductor): the best model per stack and incident
                   angle against coat and base roughness, and against coat roughness and incident angle
  bench.html       the tables and the figures
"""
import html
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MARKERS = "osD^vP*Xh<>"


def model_colours(ids):
    return {m: f"C{i % 10}" for i, m in enumerate(ids)}


def all_model_ids(bench):
    ids = []
    for st in bench["stacks"]:
        for m in st.get("models") or []:
            if m["id"] not in ids:
                ids.append(m["id"])
    for st in (bench.get("atlas") or {}).get("stacks", []):
        for a in st["angles"]:
            for m in a["rmse_remapped"]:
                if m not in ids:
                    ids.append(m)
    return ids


def convergence_png(bench, out):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    drawn = False
    for k, st in enumerate(bench["stacks"]):
        conv = st.get("convergence") or []
        if not conv:
            continue
        drawn = True
        colour = f"C{k}"
        paths = [c["paths"] for c in conv]
        secs = [c["seconds"] for c in conv]
        for ax, x in ((axes[0], paths), (axes[1], secs)):
            ax.loglog(x, [c["relative_rmse"] for c in conv], "-o", color=colour, ms=3, label=f"{st['stack']} RMSE vs long run")
            ax.loglog(x, [c["median_rse"] for c in conv], "--", color=colour, label=f"{st['stack']} median rse")
        fit = st.get("rse_fit")
        if fit:
            axes[0].loglog(paths, [fit["c"] / math.sqrt(n) for n in paths], ":", color=colour, lw=1)
    axes[0].set_xlabel("paths per incident angle (dotted: fit c / sqrt(N) of the median rse)")
    axes[1].set_xlabel("seconds (wall clock)")
    for ax in axes:
        ax.set_ylabel("relative error")
        ax.grid(True, which="both", alpha=0.3)
    if drawn:
        axes[1].legend(fontsize=7)
    fig.suptitle(f"reference convergence on {bench['device']}, theta_i = {bench['theta_i']:g}")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "convergence.png"), dpi=110)
    plt.close(fig)


def pareto_front(points):
    """Indices of the points not dominated in (cost, error), both smaller-is-better, sorted by cost."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], math.inf
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def pareto_png(bench, out, colours):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for k, st in enumerate(bench["stacks"]):
        mk = MARKERS[k % len(MARKERS)]
        models = [m for m in st.get("models") or [] if m.get("applicable") and m.get("rmse_remapped") is not None]
        pts = []
        for m in models:
            axes[0].scatter(m["ns_per_evaluation"], m["rmse_remapped"], marker=mk, color=colours[m["id"]], s=36)
            axes[1].scatter(m["device_seconds_per_grid"], m["rmse_remapped"], marker=mk, color=colours[m["id"]], s=36)
            pts.append((m["device_seconds_per_grid"], m["rmse_remapped"]))
        conv = [c for c in st.get("convergence") or [] if c.get("rmse_remapped") is not None]
        if conv:
            xs = [c["device_seconds"] for c in conv]
            ys = [c["rmse_remapped"] for c in conv]
            axes[1].plot(xs, ys, "-", color="0.5", lw=1, marker=mk, mfc="white", ms=5)
            pts += list(zip(xs, ys))
        if pts:
            front = pareto_front(pts)
            axes[1].plot([pts[i][0] for i in front], [pts[i][1] for i in front], ":", color=f"C{k}", lw=1.2)
        axes[1].scatter([], [], marker=mk, color="k", label=st["stack"])
    for mid, c in colours.items():
        axes[0].scatter([], [], marker="s", color=c, label=mid)
    axes[1].plot([], [], "-", color="0.5", marker="o", mfc="white", label="reference, 2^16..2^23 paths")
    axes[1].plot([], [], ":", color="k", label="Pareto front per stack")
    axes[0].set_xlabel("device ns per evaluation of f")
    axes[1].set_xlabel("device seconds per grid (one incident angle, every bin)")
    axes[1].set_xscale("log")
    for ax in axes:
        ax.set_yscale("log")
        ax.set_ylabel("RMSE of log(1 + sqrt f) against the 2^25-path reference")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(f"cost against error on {bench['device']}, theta_i = {bench['theta_i']:g}")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "pareto.png"), dpi=110)
    plt.close(fig)


def atlas_png(atlas, out, colours):
    angles = atlas["theta_i"]
    n = len(angles)
    fig, axes = plt.subplots(1, n + 2, figsize=(3.6 * (n + 2), 4.0))

    def pos(a):   # roughness on a log axis, 0 drawn at 3e-5
        return max(a, 3e-5)

    for st in atlas["stacks"]:
        for j, a in enumerate(st["angles"]):
            if not a["best"]:
                continue
            c = colours[a["best"]]
            clear = a["margin"] is not None and a["margin"] > a["reference_noise_remapped"]
            kw = dict(color=c, s=40) if clear else dict(facecolors="none", edgecolors=c, s=40)
            axes[j].scatter(pos(st["coat_roughness"]), pos(st["base_roughness"]), **kw)
            axes[n].scatter(pos(st["coat_roughness"]), a["theta_i"], **kw)
    for j, t in enumerate(angles):
        ax = axes[j]
        ax.set_title(f"theta_i = {t:g}", fontsize=9)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("coat roughness (0 drawn at 3e-5)")
        ax.set_ylabel("base roughness")
        ax.grid(True, which="both", alpha=0.3)
    axes[n].set_xscale("log")
    axes[n].set_xlabel("coat roughness")
    axes[n].set_ylabel("incident angle (degrees)")
    axes[n].set_title("best model against coat roughness and angle", fontsize=9)
    axes[n].grid(True, alpha=0.3)
    legend = axes[n + 1]
    legend.axis("off")
    for mid, c in colours.items():
        legend.scatter([], [], color=c, label=mid)
    legend.scatter([], [], facecolors="none", edgecolors="k", label="hollow: margin over the runner-up\nbelow the reference's noise")
    legend.legend(fontsize=8, loc="center left")
    fig.suptitle(f"error atlas: the model closest to the reference (lowest RMSE of log(1 + sqrt f)), "
                 f"{len(atlas['stacks'])} random coat-over-conductor stacks, seed {atlas['seed']}, "
                 f"{atlas['paths']:.3g} paths per angle", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "atlas.png"), dpi=100)
    plt.close(fig)


def fmt(v, spec=".3g"):
    return "—" if v is None else format(v, spec)


def table(head, rows):
    h = "<tr>" + "".join(f"<th>{html.escape(x)}</th>" for x in head) + "</tr>"
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(x))}</td>" for x in r) + "</tr>" for r in rows)
    return f"<table>{h}{body}</table>"


def bench_html(bench, out, figures):
    s = [f"<!doctype html><meta charset='utf-8'><title>gonio bench</title>"
         "<style>body{font-family:sans-serif;max-width:1200px;margin:auto}table{border-collapse:collapse;margin:1em 0}"
         "td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}th{background:#eee}img{max-width:100%}</style>",
         f"<h1>gonio bench</h1><p>Device: {html.escape(bench['device'])} ({html.escape(bench['driver'])}); CPU twin on "
         f"{bench['cpu_threads']} threads; incident angle {bench['theta_i']:g} degrees; {bench.get('paths', 0):.3g} device paths "
         f"and {bench.get('cpu_paths', 0):.3g} CPU-twin paths per throughput run. Ratios are measured in the same run.</p>",
         "<h2>Reference throughput</h2>"]
    rows = []
    for st in bench["stacks"]:
        rows.append([st["stack"], st.get("layers", ""), fmt(st["paths_per_second"] * 1e-6), fmt(st["cpu_seconds_per_mpath"]),
                     fmt(st["general_walk_paths_per_second"] * 1e-6), fmt(st.get("specialised_over_general"), ".2f"),
                     fmt(st["cpu_twin_paths_per_second"] * 1e-6), fmt(st.get("device_over_cpu_twin"), ".2f")])
    s.append(table(["stack", "layers", "device Mpaths/s", "cpu-s/Mpath", "general walk Mpaths/s", "specialised / general",
                    "CPU twin Mpaths/s", "device / twin"], rows))
    rows = []
    for st in bench["stacks"]:
        f = st.get("rse_fit")
        if f:
            rows.append([st["stack"], fmt(f["c"]), fmt(f["free_slope"]), fmt(f["paths_to_rse_1pct"]), fmt(f["seconds_to_rse_1pct"]),
                         fmt(f["paths_to_rse_0_1pct"]), fmt(f["seconds_to_rse_0_1pct"])])
    if rows:
        s.append("<h2>Time to a median relative standard error of 1% and 0.1%</h2><p>Extrapolated: median rse = c / sqrt(N) "
                 "fitted to the runs of 2<sup>18</sup> to 2<sup>23</sup> paths (the free slope of the same fit is shown as a "
                 "check), divided by the device paths per second above. Bins above 1% of their slice's peak, default bins.</p>")
        s.append(table(["stack", "c", "free slope", "paths to 1%", "seconds to 1%", "paths to 0.1%", "seconds to 0.1%"], rows))
    if "convergence.png" in figures:
        s.append("<img src='convergence.png'>")
    rows = []
    for st in bench["stacks"]:
        for m in st.get("models") or []:
            if m.get("applicable"):
                rows.append([st["stack"], m["id"], fmt(m["rmse_remapped"], ".4f"), fmt(m.get("rmse_remapped_transmission"), ".4f"),
                             fmt(m["reference_noise_remapped"], ".4f"), fmt(m["ns_per_evaluation"], ".1f"),
                             fmt(m["device_seconds_per_grid"], ".4f"), f"{m['evaluations']:.3g}"])
    if rows:
        s.append("<h2>Models: cost against error</h2><p>Each model on the bins of the 2<sup>25</sup>-path reference run (one "
                 "incident angle); RMSE of log(1 + sqrt f) over every bin and channel (transmission side separately); device "
                 "seconds from timestamps, after a first evaluation that compiled the pipelines and computed Belcour's tables "
                 f"({fmt(bench.get('belcour_table_device_seconds'))} device-s in all).</p>")
        s.append(table(["stack", "model", "RMSE", "RMSE (T)", "reference noise", "ns / evaluation", "device-s / grid",
                        "evaluations"], rows))
    if "pareto.png" in figures:
        s.append("<img src='pareto.png'>")
    atlas = bench.get("atlas")
    if atlas and atlas["stacks"]:
        counts = {}
        for st in atlas["stacks"]:
            for a in st["angles"]:
                counts.setdefault(a["theta_i"], {}).setdefault(a["best"], 0)
                counts[a["theta_i"]][a["best"]] += 1
        ids = sorted({m for c in counts.values() for m in c})
        rows = [[f"{t:g}"] + [counts[t].get(m, 0) for m in ids] for t in sorted(counts)]
        s.append(f"<h2>Error atlas</h2><p>{len(atlas['stacks'])} random two-layer stacks (a dielectric coat over a "
                 f"conductor: every model applies), seed {atlas['seed']}, reference {atlas['paths']:.3g} paths per angle on "
                 f"{atlas['dtheta']:g} x {atlas['dphi']:g} degree bins ({fmt(atlas.get('seconds'))} s in all). How often each "
                 "model is the closest to the reference:</p>")
        s.append(table(["theta_i"] + ids, rows))
        if "atlas.png" in figures:
            s.append("<img src='atlas.png'>")
        rows = []
        for st in atlas["stacks"]:
            for a in st["angles"]:
                rows.append([st["name"], fmt(st["coat_roughness"]), fmt(st["coat_ior"]), fmt(st["coat_optical_depth"]),
                             fmt(st["base_roughness"]), fmt(st["base_k"]), f"{a['theta_i']:g}", a["best"], fmt(a["best_rmse"], ".4f"),
                             fmt(a["margin"], ".4f"), fmt(a["reference_noise_remapped"], ".4f")])
        s.append(table(["stack", "coat alpha", "coat IOR", "coat tau", "base alpha", "base k", "theta_i", "best", "RMSE",
                        "margin", "reference noise"], rows))
    with open(os.path.join(out, "bench.html"), "w") as fh:
        fh.write("\n".join(s))


def main(out):
    with open(os.path.join(out, "bench.json")) as fh:
        bench = json.load(fh)
    colours = model_colours(all_model_ids(bench))
    figures = []
    if any(st.get("convergence") for st in bench["stacks"]):
        convergence_png(bench, out)
        figures.append("convergence.png")
    if any(st.get("models") for st in bench["stacks"]):
        pareto_png(bench, out, colours)
        figures.append("pareto.png")
    if bench.get("atlas") and bench["atlas"]["stacks"]:
        atlas_png(bench["atlas"], out, colours)
        figures.append("atlas.png")
    bench_html(bench, out, figures)
    for st in bench["stacks"]:
        f = st.get("rse_fit")
        if f:
            print(f"{st['stack']}: median relative standard error 1% in {f['seconds_to_rse_1pct']:.3g} s, 0.1% in "
                  f"{f['seconds_to_rse_0_1pct']:.3g} s (extrapolated along the fit c / sqrt(N))")
    print(f"wrote {', '.join(figures + ['bench.html'])} in {out}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
