#!/usr/bin/env python3
"""Figures and an HTML report for a `gonio compare` (or `gonio simulate`) output directory.

usage: report.py OUT_DIR

Reads OUT_DIR/summary.json and OUT_DIR/slices.csv (through python/gonio) and writes, in OUT_DIR:
  slices.png      the seed's BRDF slice diagrams: in-plane values remapped as log(1 + sqrt f) of the luminance,
                  one panel per incident angle, reference dashed black, one colour per model
  albedo.png      directional albedo (luminance) against incident angle, reference and models (and the
                  directional transmittance for transmissive stacks); gonio's convention variants (ids with a
                  '+') in their model's colour, dashed or dotted (only here and in report.html's table)
  topview-<i>.png top orthographic view of the reflection hemisphere for incident angle i: reference, each
                  model, and the signed difference model - reference (remapped luminance);
                  topview-<i>-T.png the same for the transmission hemisphere of a transmissive stack
  slices-T.png    the slice diagrams of the transmission side (transmissive stacks)
  report.html     the figures and the metric tables
Luminance is Y = 0.2126 R + 0.7152 G + 0.0722 B (linear sRGB primaries).
"""
import html
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import gonio  # noqa: E402  (python/gonio: gonio's files as arrays)

LUMA = np.array([0.2126, 0.7152, 0.0722])
COLOURS = ["tab:red", "tab:orange", "tab:pink", "tab:cyan", "tab:blue", "tab:green", "tab:purple", "tab:brown"]


def remap(f):
    return np.log1p(np.sqrt(np.maximum(f, 0.0)))


def load(out):
    run = gonio.read_run(out)
    images = {k: v[..., :3] for k, v in run.values.items()}
    errors = {k: v[..., 3:] for k, v in run.values.items()}
    return run.summary, images, errors, run.bins.n_theta, run.bins.n_phi


def main(out):
    summary, images, errors, n_theta, n_phi = load(out)
    dtheta, dphi = summary["bins"]["dtheta_deg"], summary["bins"]["dphi_deg"]
    angles = [a["theta_i"] for a in summary["angles"]]
    models = [m for m in summary.get("models", []) if m.get("applicable")]
    # convention variants (ids base+g2, +tir: docs/MODELS.md, Conventions) are drawn in the albedo figure only, in
    # their base model's colour; the slices and top views show the models as their official codes compute them
    defaults = [m for m in models if "+" not in m["id"]]
    colour_of = {m["id"]: COLOURS[k % len(COLOURS)] for k, m in enumerate(defaults)}
    dashes = {"+g2": "--", "+tir": ":", "+g2+tir": "-."}
    sources = ["reference"] + [m["id"] for m in defaults]
    theta_c = (np.arange(n_theta) + 0.5) * dtheta
    name = summary["stack"]

    transmissive = any(k[2] == "T" for k in images if k[0] == "reference") and any(
        float(images[k].max()) > 0 for k in images if k[0] == "reference" and k[2] == "T")
    sides = ["R", "T"] if transmissive else ["R"]

    # 1. slice diagrams (plane of incidence: phi = 180 on the specular / straight-through side, phi = 0 on the
    #    light's side), one figure per side
    for side in sides:
        fig, axes = plt.subplots(1, len(angles), figsize=(4.2 * len(angles), 3.6), squeeze=False)
        p180, p0 = int(round(180 / dphi)), 0
        for ax, ti in zip(axes[0], angles):
            x = np.concatenate([-theta_c[::-1], theta_c])
            for k, src in enumerate(sources):
                img = images.get((src, ti, side))
                if img is None:
                    continue
                lum = np.concatenate([img[::-1, p0, :], img[:, p180, :]]) @ LUMA
                y = remap(lum)
                if src == "reference":
                    # the reference's band: +- 2 standard errors of the luminance (se of a sum of channels bounded
                    # by the sum of their se: the channels share their paths)
                    se = np.concatenate([errors[(src, ti, side)][::-1, p0, :], errors[(src, ti, side)][:, p180, :]]) @ LUMA
                    ax.fill_between(x, remap(lum - 2 * se), remap(lum + 2 * se), color="0.75", lw=0, label="reference +- 2 se")
                    ax.plot(x, y, "k--", lw=1.4, label="reference")
                else:
                    ax.plot(x, y, color=COLOURS[(k - 1) % len(COLOURS)], lw=1.2, label=src)
            ax.axvline(ti, color="gold", lw=0.8)
            ax.set_title(f"theta_i = {ti:g} deg")
            ax.set_xlabel("theta_o (deg; + specular side)" if side == "R" else "theta_t from -z (deg; + straight-through side)")
            ax.set_xlim(-90, 90)
        axes[0][0].set_ylabel("log(1 + sqrt(f))  (luminance)")
        handles, labels = axes[0][0].get_legend_handles_labels()
        for ax in axes[0][1:]:   # every source, once, below the panels (a legend inside would cover data)
            for h, l in zip(*ax.get_legend_handles_labels()):
                if l not in labels:
                    handles.append(h)
                    labels.append(l)
        fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 6), fontsize=8, frameon=False)
        fig.suptitle(f"{name}: {'BRDF' if side == 'R' else 'BTDF'} in the plane of incidence")
        fig.tight_layout(rect=(0, 0.06 + 0.04 * ((len(labels) - 1) // 6), 1, 1))
        fig.savefig(os.path.join(out, "slices.png" if side == "R" else "slices-T.png"), dpi=110)
        plt.close(fig)

    # 2. directional albedo (and transmittance) against incident angle
    fig, axs = plt.subplots(1, len(sides), figsize=(5 * len(sides), 3.6), squeeze=False)
    for ax, side in zip(axs[0], sides):
        key = "reflected" if side == "R" else "transmitted"
        ref_alb = [float(np.dot([a["energy"][c][key] for c in "RGB"], LUMA)) for a in summary["angles"]]
        ax.plot(angles, ref_alb, "k--o", label="reference")
        for m in models:
            per_angle = m["angles"] if side == "R" else m.get("transmission_angles", [])
            if not per_angle:
                continue
            base, _, suffix = m["id"].partition("+")
            ax.plot(angles, [float(np.dot(a["albedo_model"], LUMA)) for a in per_angle],
                    dashes.get("+" + suffix, "-") if suffix else "-", marker="o" if not suffix else ".",
                    color=colour_of.get(base, "grey"), label=m["id"])
        ax.set_xlabel("theta_i (deg)")
        ax.set_ylabel(f"directional {'albedo' if side == 'R' else 'transmittance'} (luminance)")
        ax.set_title(f"{name}: {key} energy")
        ax.legend(fontsize=6 if len(models) > len(defaults) else 7, loc="upper left", bbox_to_anchor=(1.01, 1.0), frameon=False)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "albedo.png"), dpi=110)
    plt.close(fig)

    # 3. top views: orthographic projection of the reflection hemisphere
    th_edges = np.radians(np.arange(n_theta + 1) * dtheta)
    ph_edges = np.radians((np.arange(n_phi + 1) - 0.5) * dphi)
    PH, TH = np.meshgrid(ph_edges, th_edges)
    X, Y = np.sin(TH) * np.cos(PH), np.sin(TH) * np.sin(PH)
    topviews = []
    for i, (ti, side) in enumerate([(ti, side) for ti in angles for side in sides]):
        panels = [("reference", images[("reference", ti, side)] @ LUMA, "viridis")]
        for m in defaults:
            if (m["id"], ti, side) in images:
                panels.append((m["id"], images[(m["id"], ti, side)] @ LUMA, "viridis"))
        ref = remap(panels[0][1])
        vmax = max(float(remap(p[1]).max()) for p in panels) or 1.0
        ncol = 2 * len(panels) - 1
        fig, axes = plt.subplots(1, ncol, figsize=(2.6 * ncol + 1.2, 3.1), squeeze=False, layout="constrained")
        for ax, (label, lum, cmap) in zip(axes[0], panels):
            mesh = ax.pcolormesh(X, Y, remap(lum), cmap=cmap, vmin=0, vmax=vmax, shading="flat")
            ax.set_title(label, fontsize=9)
        fig.colorbar(mesh, ax=list(axes[0][:len(panels)]), shrink=0.7, pad=0.01, label="log(1 + sqrt f)")
        # the difference scale: the 99th percentile of |difference| over the models' bins, so that one delta spike
        # cannot flatten the rest (bins beyond it saturate)
        diffs = [np.abs(remap(p[1]) - ref).ravel() for p in panels[1:]]
        dmax = max(float(np.percentile(np.concatenate(diffs), 99)) if diffs else 0.0, 1e-6)
        dmesh = None
        for ax, (label, lum, _) in zip(axes[0][len(panels):], panels[1:]):
            dmesh = ax.pcolormesh(X, Y, remap(lum) - ref, cmap="RdBu_r", vmin=-dmax, vmax=dmax, shading="flat")
            ax.set_title(f"{label} - ref", fontsize=9)
        if dmesh is not None:
            fig.colorbar(dmesh, ax=list(axes[0][len(panels):]), shrink=0.7, pad=0.01, label="model - reference")
        for ax in axes[0]:
            ax.set_aspect("equal")
            ax.axis("off")
            ax.plot([math.sin(math.radians(ti))], [0], marker="o", color="gold", ms=4)
        what = "reflection" if side == "R" else "transmission (seen from below, theta from -z)"
        fig.suptitle(f"{name}, theta_i = {ti:g} deg, {what}: top view, log(1 + sqrt f) of luminance; differences on a "
                     f"symmetric scale (+-{dmax:.3g}, the 99th percentile of |difference|)", fontsize=9)
        fname = f"topview-{angles.index(ti)}.png" if side == "R" else f"topview-{angles.index(ti)}-T.png"
        fig.savefig(os.path.join(out, fname), dpi=100)
        plt.close(fig)
        topviews.append((f"{ti:g} {side}", fname))

    # 4. report.html
    best = {(b["theta_i"], b["side"]): b for b in summary.get("best_model", [])}
    rows = []
    for m in summary.get("models", []):
        if not m.get("applicable"):
            rows.append(f"<tr><td>{html.escape(m['id'])}</td><td colspan=11>not applicable: {html.escape(m['reason'])}</td></tr>")
            continue
        for side, a in [("R", a) for a in m["angles"]] + [("T", a) for a in m.get("transmission_angles", [])]:
            mx = a["max_error_remapped"]
            b = best.get((a["theta_i"], side), {})
            mark = ""
            if b.get("best") == m["id"]:
                mark = " <b>best</b>" + (f" (tie with {html.escape(b['runner_up'])})" if b.get("tie") else "")
            elif b.get("tie") and b.get("runner_up") == m["id"]:
                mark = f" <b>tie</b> (with {html.escape(b['best'])})"
            verdict = ("<span style='color:#070'>within noise</span>" if a["within_reference_noise"]
                       else "<span style='color:#a00'>differs</span>: " + html.escape(a.get("verdict", "")))
            rows.append(
                "<tr>" + "".join(f"<td>{v}</td>" for v in [
                    html.escape(m["id"]) + mark, f"{a['theta_i']:g} {side}", f"{a['rmse_remapped']:.4f}",
                    f"{a['reference_noise_remapped']:.4f}",
                    f"{a['chi2_per_dof']:.3g}", f"{a['mean_z']:+.3g}",
                    f"{a['chi2_p_value']:.2g} / {a['bias_p_value']:.2g}",
                    f"{100 * a['smallest_detectable_relative_bias']:.2g}%", verdict,
                    " ".join(f"{v:+.4f}" for v in a["albedo_error"]) + (
                        " <b>reflects " + " ".join(f"{v:.3f}" for v in a["albedo_model_total"]) + " &gt; 1</b>"
                        if a.get("reflects_more_than_it_receives") else ""),
                    f"{mx['value']:.3f} at theta {mx['theta']:g}, phi {mx['phi']:g} deg, channel {mx['channel']}",
                    f"{m['seconds']:.3f}"]) + "</tr>")
    # the stack and the energy book, first
    energy_rows = []
    for a in summary["angles"]:
        e = a["energy"]
        cells = [f"{a['theta_i']:g}", f"{a['paths']:,}"] + [
            " ".join(f"{e[c][k]:.4f}" for c in "RGB") for k in ("reflected", "transmitted", "absorbed", "microfacet_loss", "truncated")]
        cells.append(" ".join(f"{e[c]['sum']:.6f}" for c in "RGB"))
        rse = a.get("relative_se", {})
        cells.append(f"{rse.get('median', float('nan')):.3g} / {rse.get('p90', float('nan')):.3g} / {a['worst_relative_se']:.3g}")
        energy_rows.append("<tr>" + "".join(f"<td>{v}</td>" for v in cells) + "</tr>")
    stack_text = html.escape(summary.get("stack_description", ""))
    rendering = render_section(out)
    page = f"""<!doctype html><html><head><meta charset="utf-8"><title>gonio: {html.escape(name)}</title>
<style>body{{font-family:sans-serif;max-width:1400px;margin:auto}} td,th{{padding:2px 8px;border-bottom:1px solid #ddd}}
img{{max-width:100%}}</style></head><body>
<h1>gonio compare: {html.escape(name)}</h1>
<p>{html.escape(summary.get('stack_file', ''))}; device {html.escape(summary['device'])}; {summary['paths_per_angle']} paths per
incident angle, seed {summary['seed']}; bins {dtheta:g} x {dphi:g} deg.</p>
<pre>{stack_text}</pre>
<h2>Where the light went (reference; per channel R G B)</h2>
<table><tr><th>theta_i</th><th>paths</th><th>reflected</th><th>transmitted</th><th>absorbed</th><th>microfacet loss</th>
<th>truncated</th><th>sum</th><th>relative se: median / 90th pct / worst</th></tr>{''.join(energy_rows)}</table>
<h2>How to read the metrics</h2>
<p>Errors are over every bin and channel of one side (R: reflection, T: transmission). <b>rmse remapped</b> is the RMS of
log(1+sqrt f_model) - log(1+sqrt f_reference), the seed's remapping, which weighs lobes and tails alike; the lowest per angle
is marked <b>best</b>, and <b>tie</b> when the reference's noise cannot tell the best two apart (paired test at 1%).
<b>reference noise</b> is the RMS of the reference's own standard error in that space. The verdict is a statistic
(docs/MODELS.md, "Verdicts"): bins are grouped into cells with a trustworthy standard error (relative se below 5%; sparse
bins pooled with their neighbours), each cell gives z = (model - reference) / se; <b>chi2/dof</b> is the mean of
z<sup>2</sup> (about 1 when the model is the reference), <b>mean z</b> the bias (its sign: above or below), <b>p</b> the
p-values of the chi-square test and of the bias test, and <b>within noise</b> means neither rejects agreement at 1%.
<b>detectable bias</b>: a model off by this relative factor everywhere would be seen at these paths.
<b>albedo error</b> is the model's directional albedo minus the reference's, per channel.
Ids with a <b>+</b> are gonio's convention variants of a model (+g2: height-correlated Smith G2 in the lobes and tables;
+tir: the TIR term kept below absorbing media); they are in this table and the albedo figure, the slices and top views
show the models as their official codes compute them.</p>
<table><tr><th>model</th><th>theta_i, side</th><th>rmse remapped</th><th>reference noise</th><th>chi2/dof</th><th>mean z</th>
<th>p (chi2 / bias)</th><th>detectable bias</th><th>verdict</th>
<th>albedo error (R G B)</th><th>largest remapped error</th><th>model seconds</th></tr>
{''.join(rows)}</table>
<h2>Slices</h2><img src="slices.png">{'<img src="slices-T.png">' if transmissive else ''}<h2>Directional albedo</h2><img src="albedo.png">
<h2>Top views</h2>{''.join(f'<h3>theta_i = {ti}</h3><img src="{f}">' for ti, f in topviews)}
{rendering}</body></html>"""
    with open(os.path.join(out, "report.html"), "w") as fh:
        fh.write(page)
    print(f"wrote {out}/{{slices.png{',slices-T.png' if transmissive else ''},albedo.png,topview-*.png,report.html}}")


def render_section(out):
    """report.html's renderings (compare --render ENV): OUT/render's figure and, per model, relative L1 and HDR-FLIP
    beside the reference's floor (render.json, written by gonio render and tools/render_report.py)."""
    path = os.path.join(out, "render", "render.json")
    if not os.path.exists(path):
        return ""
    with open(path) as fh:
        j = json.load(fh)
    floor = j["reference"]["floor"]

    def num(x, fmt):
        return fmt % x if isinstance(x, (int, float)) else "-"
    rows = [f"<tr><td>reference (floor: between its halves)</td><td>{num(floor.get('relative_l1_between_halves'), '%.4f')}"
            f"</td><td>{num(floor.get('flip_mean_between_halves'), '%.4f')}</td>"
            f"<td>{num(floor.get('flip_p95_between_halves'), '%.4f')}</td></tr>"]
    for m in j["models"]:
        if "not_rendered" in m:
            rows.append(f"<tr><td>{html.escape(m['id'])}</td><td colspan=3>not rendered: "
                        f"{html.escape(m['not_rendered'])}</td></tr>")
            continue
        rows.append(f"<tr><td>{html.escape(m['id'])}</td><td>{num(m.get('relative_l1'), '%.4f')}</td>"
                    f"<td>{num(m.get('flip_mean'), '%.4f')}</td><td>{num(m.get('flip_p95'), '%.4f')}</td></tr>")
    flip = j.get("flip")
    flip_note = "" if isinstance(flip, dict) else f"<p>HDR-FLIP {html.escape(str(flip))}</p>"
    figure = '<img src="render/figure.png">' if os.path.exists(os.path.join(out, "render", "figure.png")) else ""
    env = j["environment"]
    return f"""<h2>Renderings (under {html.escape(env['name'])})</h2>
<p>The reference and each model on a sphere, {j['size']} x {j['size']} pixels, lit by {html.escape(env['source'])}
(gonio render, docs/RENDER.md; the reference from a table of {html.escape(str(j['reference']['paths_per_angle']))} paths per
angle over theta_i 0 to 88 degrees in two halves). A model within the reference's floor (its two halves against each other)
cannot be told from it with these paths. Files: render/.</p>{flip_note}
<table><tr><th>image</th><th>relative L1 against the reference</th><th>HDR-FLIP mean</th><th>HDR-FLIP 95th percentile</th></tr>
{''.join(rows)}</table>{figure}
"""


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
