#!/usr/bin/env python3
"""Figures and an HTML report for a `gonio compare` (or `gonio simulate`) output directory.

usage: report.py OUT_DIR

Reads OUT_DIR/summary.json and OUT_DIR/slices.csv (through python/gonio) and writes, in OUT_DIR:
  slices.png      the seed's BRDF slice diagrams: in-plane values remapped as log(1 + sqrt f) of the luminance,
                  one panel per incident angle (at most four a row), reference dashed black, one colour (and past
                  nine models, a marker) per model, the legend below the panels
  albedo.png      directional albedo (luminance) against incident angle, reference and models (and the
                  directional transmittance for transmissive stacks), one legend at the right; gonio's convention
                  variants (ids with a '+') in their model's colour, dashed or dotted (only here and in report.html)
  topview-<i>.png top orthographic view of the reflection hemisphere for incident angle i, as a grid of at most six
                  panels a row: the reference, then each model (remapped luminance, one colour bar), then the
                  signed differences model - reference (a symmetric scale, its own colour bar), each difference
                  in the same place of its block as its model;
                  topview-<i>-T.png the same for the transmission hemisphere of a transmissive stack
  slices-T.png    the slice diagrams of the transmission side (transmissive stacks)
  report.html     the figures and the metric tables: one row per model grouped by family (summary.json's "family";
                  without it the id before the first '+', and "your models" for models from the user's files), the
                  best model of each incident angle and side and its tie marked, then per family the detailed
                  per-angle metrics
Luminance is Y = 0.2126 R + 0.7152 G + 0.0722 B (linear sRGB primaries).
"""
import glob
import html
import json
import math
import os
import sys
import textwrap
from dataclasses import dataclass

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

TOOLS = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(TOOLS, "..", "python"))
import gonio  # noqa: E402  (python/gonio: gonio's files as arrays)

LUMA = np.array([0.2126, 0.7152, 0.0722])
# tab10 without its grey (the reference's band is grey); past nine models the colours repeat with a marker
COLOURS = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown", "tab:pink", "tab:olive",
           "tab:cyan"]
MARKERS = ["o", "s", "^", "D", "v", "P"]
VARIANT_DASHES = {"+g2": "--", "+tir": ":", "+g2+tir": "-."}
TOPVIEW_COLUMNS = 6      # panels a row of a top view: 6 x 260 px and the colour bar stay under 1800 px
PANEL_W, PANEL_H = 2.6, 3.0   # inches (100 px each at the top views' dpi): a top-view panel's cell
TITLE_H = 0.5            # inches of a cell above its panel: a title of two lines
BAR_W = 1.3              # inches right of the panels: a block's colour bar and its label
SLICE_COLUMNS = 4        # slice panels a row
LEGEND_FONT = 8          # points: legible at 100% zoom at the figures' dpi
YOUR_MODELS = "your models"


@dataclass
class Data:
    """What the figures draw: the summary, the slices' luminance inputs and the models drawn in them."""
    out: str
    summary: dict
    images: dict           # (source, theta_i, side) -> (n_theta, n_phi, 3) f
    errors: dict           # the same keys -> their standard errors
    n_theta: int
    n_phi: int
    angles: list
    sides: list
    scored: list           # the scored models, in summary order
    defaults: list         # of them, the models as published (no '+'): the slices and top views draw these


def remap(f):
    """The seed's remapping, log(1 + sqrt f): lobes and tails on one scale."""
    return np.log1p(np.sqrt(np.maximum(f, 0.0)))


def is_scored(m):
    """A model with metrics: applicable, and its values usable (an invalid model is listed, not drawn)."""
    return bool(m.get("applicable")) and m.get("scored", True) and "angles" in m


def load(out):
    """OUT's summary and slices (through python/gonio), the sides it has, and the models to draw."""
    run = gonio.read_run(out)
    images = {k: v[..., :3] for k, v in run.values.items()}
    errors = {k: v[..., 3:] for k, v in run.values.items()}
    summary = run.summary
    scored = [m for m in summary.get("models", []) if is_scored(m)]
    transmissive = any(k[0] == "reference" and k[2] == "T" and float(v.max()) > 0 for k, v in images.items())
    return Data(out, summary, images, errors, run.bins.n_theta, run.bins.n_phi,
                [a["theta_i"] for a in summary["angles"]], ["R", "T"] if transmissive else ["R"],
                scored, [m for m in scored if "+" not in m["id"]])


def style_of(k):
    """The colour and marker of the k-th model drawn: nine colours, then the same colours with another marker."""
    return COLOURS[k % len(COLOURS)], MARKERS[(k // len(COLOURS)) % len(MARKERS)]


def legend_width(labels, ncol, fontsize=LEGEND_FONT):
    """Inches a legend of ncol columns takes, its entries dealt as matplotlib deals them (the first columns one entry
    longer): per column an entry's handle and spacing (about 5 em) and its longest label (about 0.6 em a
    character)."""
    rows, long_cols = divmod(len(labels), ncol)
    sizes = [rows + 1] * long_cols + [rows] * (ncol - long_cols)
    starts = np.cumsum([0] + sizes)
    return sum(5.0 + 0.6 * max(len(s) for s in labels[a:b]) for a, b in zip(starts[:-1], starts[1:]) if b > a) \
        * fontsize / 72


def legend_columns(labels, width_in, fontsize=LEGEND_FONT):
    """The most legend columns that fit across width_in inches (at least one)."""
    return next((n for n in range(len(labels), 1, -1) if legend_width(labels, n, fontsize) <= width_in), 1)


def legend_height(rows, fontsize=LEGEND_FONT):
    """Inches that rows of legend entries take (1.5 line heights a row, and a margin)."""
    return rows * 1.5 * fontsize / 72 + 0.15


def wrap_label(label, width=30):
    """A panel title on lines of at most width characters (a user's model id may be 64 long)."""
    return textwrap.fill(label, width, break_on_hyphens=True)


def wrap_to(text, width_in, fontsize):
    """A title on as many lines as it needs to fit width_in inches (about 0.55 em a character)."""
    return textwrap.fill(text, max(20, int(width_in * 72 / (0.55 * fontsize))))


# ---- slices.png, slices-T.png ------------------------------------------------------------------------------------

def in_plane(a, p0, p180):
    """The plane of incidence of an (n_theta, n_phi, ...) array: phi = 0 (the light's side, theta reversed) then
    phi = 180 (the specular / straight-through side)."""
    return np.concatenate([a[::-1, p0], a[:, p180]])


def draw_slice_panel(ax, d, ti, side, x, p0, p180):
    """One incident angle's in-plane slice: the reference's +- 2 se band and its values, then each model."""
    key = ("reference", ti, side)
    if key in d.images:
        lum = in_plane(d.images[key], p0, p180) @ LUMA
        # se of a sum of channels bounded by the sum of their se: the channels share their paths
        se = in_plane(d.errors[key], p0, p180) @ LUMA
        ax.fill_between(x, remap(lum - 2 * se), remap(lum + 2 * se), color="0.75", lw=0, label="reference +- 2 se")
        ax.plot(x, remap(lum), "k--", lw=1.4, label="reference")
    for k, m in enumerate(d.defaults):
        img = d.images.get((m["id"], ti, side))
        if img is None:
            continue
        colour, marker = style_of(k)
        ax.plot(x, remap(in_plane(img, p0, p180) @ LUMA), color=colour, lw=1.2, label=m["id"],
                marker=marker if k >= len(COLOURS) else None, markevery=max(1, len(x) // 12), ms=4)
    ax.axvline(ti, color="gold", lw=0.8)
    ax.set_title(f"theta_i = {ti:g} deg")
    ax.set_xlabel("theta_o (deg; + specular side)" if side == "R" else "theta_t from -z (deg; + straight-through side)")
    ax.set_xlim(-90, 90)


def unique_legend(axes):
    """Every labelled line of the axes, once, in order of appearance."""
    handles, labels = [], []
    for ax in axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    return handles, labels


def draw_slices(d, side):
    """slices.png (or slices-T.png): a panel per incident angle, at most SLICE_COLUMNS a row, the legend below them
    in as many rows as it needs (a legend inside would cover data)."""
    dtheta, dphi = d.summary["bins"]["dtheta_deg"], d.summary["bins"]["dphi_deg"]
    theta_c = (np.arange(d.n_theta) + 0.5) * dtheta
    x = np.concatenate([-theta_c[::-1], theta_c])
    # the plane of incidence: the bins' columns at the light's azimuth phi_i and opposite it (the columns nearest, for
    # a phi_i between bin centres)
    angles = d.summary.get("angles") or [{}]
    phi_i = float(angles[0].get("phi_i", 0.0))
    n_phi = int(round(360 / dphi))
    p0, p180 = int(round(phi_i / dphi)) % n_phi, int(round((phi_i + 180) / dphi)) % n_phi
    cols = min(len(d.angles), SLICE_COLUMNS)
    rows = math.ceil(len(d.angles) / cols)
    width = max(4.0 * cols, 5.0)
    labels = ["reference +- 2 se", "reference"] + [m["id"] for m in d.defaults]
    ncol = legend_columns(labels, width - 0.3)
    leg_h = legend_height(math.ceil(len(labels) / ncol))
    fig, axes = plt.subplots(rows, cols, figsize=(width, 3.6 * rows + leg_h), squeeze=False)
    flat = list(axes.flat)
    for ax, ti in zip(flat, d.angles):
        draw_slice_panel(ax, d, ti, side, x, p0, p180)
    for ax in flat[len(d.angles):]:
        ax.axis("off")
    for r in range(rows):
        axes[r][0].set_ylabel("log(1 + sqrt(f))  (luminance)")
    handles, labels = unique_legend(flat)
    fig.legend(handles, labels, loc="lower center", ncol=ncol, fontsize=LEGEND_FONT, frameon=False)
    what = "BRDF" if side == "R" else "BTDF"
    plane = "the plane of incidence" + (f" (phi_i {phi_i:g} deg)" if phi_i else "")
    fig.suptitle(wrap_to(f"{d.summary['stack']}: {what} in {plane}", width, 12))
    fig.tight_layout(rect=(0, leg_h / fig.get_figheight(), 1, 1))
    fig.savefig(os.path.join(d.out, "slices.png" if side == "R" else "slices-T.png"), dpi=110)
    plt.close(fig)


# ---- albedo.png --------------------------------------------------------------------------------------------------

def draw_albedo_panel(ax, d, side, colour_of, marker_of):
    """One side's directional albedo (or transmittance) against theta_i: the reference, each model, the variants in
    their model's colour and marker, dashed or dotted."""
    key = "reflected" if side == "R" else "transmitted"
    ref = [float(np.dot([a["energy"][c][key] for c in "RGB"], LUMA)) for a in d.summary["angles"]]
    ax.plot(d.angles, ref, "k--o", label="reference")
    for m in d.scored:
        per_angle = m["angles"] if side == "R" else m.get("transmission_angles", [])
        if not per_angle:
            continue
        base, _, suffix = m["id"].partition("+")
        ax.plot([a["theta_i"] for a in per_angle], [float(np.dot(a["albedo_model"], LUMA)) for a in per_angle],
                VARIANT_DASHES.get("+" + suffix, "--") if suffix else "-", marker=marker_of.get(base, "."),
                ms=3 if suffix else 5, color=colour_of.get(base, "grey"), label=m["id"])
    ax.set_xlabel("theta_i (deg)")
    ax.set_ylabel(f"directional {'albedo' if side == 'R' else 'transmittance'} (luminance)")
    ax.set_title(f"{d.summary['stack']}: {key} energy")


def draw_albedo(d):
    """albedo.png: a panel per side, one legend at the right in columns of at most 24 entries, the figure as tall as
    the legend needs."""
    styles = {m["id"]: style_of(k) for k, m in enumerate(d.defaults)}
    colour_of = {i: s[0] for i, s in styles.items()}
    marker_of = {i: s[1] for i, s in styles.items()}
    labels = ["reference"] + [m["id"] for m in d.scored]
    ncol = math.ceil(len(labels) / 24)
    rows = math.ceil(len(labels) / ncol)
    leg_w = legend_width(labels, ncol) + 0.2
    panels_w = 4.6 * len(d.sides)
    height = max(3.6, legend_height(rows) + 0.4)
    fig, axs = plt.subplots(1, len(d.sides), figsize=(panels_w + leg_w, height), squeeze=False)
    for ax, side in zip(axs[0], d.sides):
        draw_albedo_panel(ax, d, side, colour_of, marker_of)
    handles, labels = unique_legend(axs[0])
    split = panels_w / (panels_w + leg_w)
    fig.legend(handles, labels, loc="center left", bbox_to_anchor=(split, 0.5), ncol=ncol, fontsize=LEGEND_FONT,
               frameon=False)
    fig.tight_layout(rect=(0, 0, split, 1))
    fig.savefig(os.path.join(d.out, "albedo.png"), dpi=110)
    plt.close(fig)


# ---- topview-<i>.png ---------------------------------------------------------------------------------------------

def hemisphere_mesh(d):
    """The bins' corners in the orthographic top view: x = sin theta cos phi, y = sin theta sin phi."""
    dtheta, dphi = d.summary["bins"]["dtheta_deg"], d.summary["bins"]["dphi_deg"]
    th_edges = np.radians(np.arange(d.n_theta + 1) * dtheta)
    ph_edges = np.radians((np.arange(d.n_phi + 1) - 0.5) * dphi)
    PH, TH = np.meshgrid(ph_edges, th_edges)
    return np.sin(TH) * np.cos(PH), np.sin(TH) * np.sin(PH)


def place_axes(fig, left, top, width, height):
    """An axes left and top inches from the figure's top-left corner, width x height inches (the top views are laid
    out by hand: a layout engine takes seconds over 60 panels)."""
    fw, fh = fig.get_size_inches()
    return fig.add_axes([left / fw, (fh - top - height) / fh, width / fw, height / fh])


def text_height(text, fontsize):
    """Inches that text's lines take at fontsize."""
    return (text.count("\n") + 1) * 1.3 * fontsize / 72


def block_title(fig, text, cols, top, fontsize=10):
    """A block's title, centred over its panels, its top at top inches."""
    fw, fh = fig.get_size_inches()
    fig.text(cols * PANEL_W / 2 / fw, 1 - top / fh, text, ha="center", va="top", fontsize=fontsize)


def block_axes(fig, n, cols, top):
    """n square, frameless panels in rows of cols from top inches down, each in a PANEL_W x PANEL_H cell with its
    title's room above it."""
    size = min(PANEL_W, PANEL_H - TITLE_H) - 0.15
    axes = [place_axes(fig, c * PANEL_W + (PANEL_W - size) / 2, top + r * PANEL_H + TITLE_H, size, size)
            for r, c in (divmod(k, cols) for k in range(n))]
    for ax in axes:
        ax.axis("off")
    return axes


def block_colour_bar(fig, mappable, cols, rows, top, label):
    """A block's colour bar right of its panels, at most two panels high, centred on the block."""
    height = min(rows, 2) * PANEL_H - 0.8
    cax = place_axes(fig, cols * PANEL_W + 0.25, top + (rows * PANEL_H - height) / 2, 0.18, height)
    fig.colorbar(mappable, cax=cax, label=label)


def hemisphere_panel(ax, X, Y, values, title, ti, **mesh):
    """A top-view panel: the hemisphere's bins, square, the light's direction (phi = 0 at theta_i) as a gold dot."""
    drawn = ax.pcolormesh(X, Y, values, shading="flat", **mesh)
    ax.set_title(title, fontsize=9)
    ax.set_aspect("equal")
    ax.set_xlim(-1.02, 1.02)
    ax.set_ylim(-1.02, 1.02)
    ax.plot([math.sin(math.radians(ti))], [0], marker="o", color="gold", ms=4)
    return drawn


def difference_scale(panels):
    """The difference's symmetric scale: the 99th percentile of |difference| over the models' bins, so that one delta
    spike cannot flatten the rest (bins beyond it saturate)."""
    ref = panels[0][1]
    diffs = [np.abs(v - ref).ravel() for _, v in panels[1:]]
    return max(float(np.percentile(np.concatenate(diffs), 99)) if diffs else 0.0, 1e-6)


def draw_topview(d, ti, side, fname, mesh_xy):
    """One top view: the reference and the models in one block on one scale, their differences to the reference in a
    second block, model k's difference in the place model k has in the first (the reference's place left blank)."""
    X, Y = mesh_xy
    panels = [("reference", remap(d.images[("reference", ti, side)] @ LUMA))]
    panels += [(m["id"], remap(d.images[(m["id"], ti, side)] @ LUMA)) for m in d.defaults
               if (m["id"], ti, side) in d.images]
    n = len(panels)
    cols = min(n, TOPVIEW_COLUMNS)
    rows = math.ceil(n / cols)
    width = cols * PANEL_W + BAR_W
    what = "reflection" if side == "R" else "transmission (seen from below, theta from -z)"
    title = wrap_to(f"{d.summary['stack']}, theta_i = {ti:g} deg, {what}: top view, log(1 + sqrt f) of luminance",
                    width, 11)
    dmax = difference_scale(panels)
    titles = ["the reference, then each model" if n > 1 else "the reference"]
    if n > 1:
        titles.append(wrap_to(f"model - reference, each in its model's place above (a symmetric scale, +-{dmax:.3g}: "
                              f"the 99th percentile of |difference|)", cols * PANEL_W, 10))
    head = text_height(title, 11) + 0.25
    height = head + sum(text_height(t, 10) + 0.1 + rows * PANEL_H for t in titles) + 0.1
    fig = plt.figure(figsize=(width, height))
    fig.text(0.5, 1 - 0.1 / height, title, ha="center", va="top", fontsize=11)
    top = head
    block_title(fig, titles[0], cols, top)
    top += text_height(titles[0], 10) + 0.1
    vmax = max(float(v.max()) for _, v in panels) or 1.0
    for ax, (label, v) in zip(block_axes(fig, n, cols, top), panels):
        mesh = hemisphere_panel(ax, X, Y, v, wrap_label(label), ti, cmap="viridis", vmin=0, vmax=vmax)
    block_colour_bar(fig, mesh, cols, rows, top, "log(1 + sqrt f)")
    top += rows * PANEL_H
    if n > 1:
        block_title(fig, titles[1], cols, top)
        top += text_height(titles[1], 10) + 0.1
        for ax, (label, v) in zip(block_axes(fig, n, cols, top)[1:], panels[1:]):
            mesh = hemisphere_panel(ax, X, Y, v - panels[0][1], wrap_label(label) + " - ref", ti, cmap="RdBu_r",
                                    vmin=-dmax, vmax=dmax)
        block_colour_bar(fig, mesh, cols, rows, top, "model - reference")
    fig.savefig(os.path.join(d.out, fname), dpi=100)
    plt.close(fig)


def draw_topviews(d):
    """Every incident angle's top views (and the transmission side's); returns [(caption, file name)]."""
    mesh_xy = hemisphere_mesh(d)
    done = []
    for i, ti in enumerate(d.angles):
        for side in d.sides:
            fname = f"topview-{i}.png" if side == "R" else f"topview-{i}-T.png"
            draw_topview(d, ti, side, fname, mesh_xy)
            done.append((f"{ti:g} {side}", fname))
    return done


# ---- report.html: families -----------------------------------------------------------------------------------------

def builtin_ids():
    """The ids of gonio's built-in models (each file's '// gonio-model: ID' line), or None where the shaders are not
    beside tools/."""
    files = glob.glob(os.path.join(TOOLS, "..", "shaders", "lib", "models", "builtin", "*.glsl"))
    if not files:
        return None
    ids = set()
    for path in files:
        with open(path) as fh:
            for line in fh:
                if line.startswith("// gonio-model:"):
                    ids.add(line.split(":", 1)[1].strip())
                    break
    return ids


def family_of(m, builtins):
    """A model's family: summary.json's "family"; a model from the user's files (a "file", or an id gonio does not
    build in) is one of "your models"; otherwise the id before the first '+' (a variant with its model)."""
    base = m["id"].split("+", 1)[0]
    if "file" in m or (builtins is not None and base not in builtins and not m.get("family")):
        return YOUR_MODELS
    return m.get("family") or base


def group_by_family(models):
    """[(family, [model])]: the families in order of their first model in summary.json, "your models" last; in a
    family each variant right after its model."""
    builtins = builtin_ids()
    order = {m["id"]: k for k, m in enumerate(models)}
    groups = {}
    for m in models:
        groups.setdefault(family_of(m, builtins), []).append(m)

    def place(m):
        base = m["id"].split("+", 1)[0]
        return order.get(base, order[m["id"]]), order[m["id"]]
    names = sorted(groups, key=lambda f: (f == YOUR_MODELS, min(order[m["id"]] for m in groups[f])))
    return [(f, sorted(groups[f], key=place)) for f in names]


# ---- report.html: tables -----------------------------------------------------------------------------------------

def metric_columns(summary, models):
    """The (theta_i, side) pairs the models were scored at, in the summary's angle order, R before T."""
    present = {(a["theta_i"], s) for m in models for s, a in side_angles(m)}
    return [(a["theta_i"], s) for s in ("R", "T") for a in summary["angles"] if (a["theta_i"], s) in present]


def side_angles(m):
    """[(side, per-angle metrics)] of a scored model: reflection, then transmission."""
    return [("R", a) for a in m.get("angles", [])] + [("T", a) for a in m.get("transmission_angles", [])]


def best_mark(mid, b):
    """The mark of model mid in a best_model entry: ("best" | "tie" | "", who it ties with)."""
    if b.get("best") == mid:
        return "best", b.get("runner_up", "") if b.get("tie") else ""
    if b.get("tie") and b.get("runner_up") == mid:
        return "tie", b.get("best", "")
    return "", ""


def rmse_cell(m, a, side, best):
    """A summary-table cell: the remapped rmse, bold with a mark for the best of its angle and for its tie."""
    if a is None:
        return "<td>-</td>"
    mark, other = best_mark(m["id"], best.get((a["theta_i"], side), {}))
    value = f"{a['rmse_remapped']:.4f}"
    if not mark:
        return f"<td>{value}</td>"
    if mark == "best":
        note = "best, tie" if other else "best"
        tip = f"best at this angle; tie with {other}" if other else "best at this angle"
    else:
        note, tip = "tie", f"tie with the best, {other}"
    return f"<td class=best title='{html.escape(tip, quote=True)}'><b>{value}</b> <small>{note}</small></td>"


def verdict_count(m):
    """How many of a model's angles and sides are within the reference's noise, and its white-furnace flag."""
    pairs = side_angles(m)
    within = sum(1 for _, a in pairs if a["within_reference_noise"])
    flag = " <b>reflects &gt; 1</b>" if any(a.get("reflects_more_than_it_receives") for _, a in pairs) else ""
    return f"{within} / {len(pairs)}{flag}"


def summary_row(m, columns, best):
    """One model's row of the summary table (a not-applicable model has none; a model not scored says why)."""
    mid = html.escape(m["id"])
    if not is_scored(m):
        return (f"<tr><td>{mid}</td><td colspan={len(columns) + 2} class=na>not scored: "
                f"{html.escape(m.get('reason', ''))}</td></tr>")
    by_key = {(a["theta_i"], s): a for s, a in side_angles(m)}
    cells = "".join(rmse_cell(m, by_key.get(c), c[1], best) for c in columns)
    return f"<tr><td>{mid}</td>{cells}<td>{verdict_count(m)}</td><td>{m.get('seconds', 0):.3f}</td></tr>"


def summary_table(groups, columns, best):
    """One row per applicable model, grouped by family (a family row first): the rmse per angle and side, the best
    and its tie marked, the verdicts within noise."""
    head = "".join(f"<th>{ti:g} {s}</th>" for ti, s in columns)
    body = []
    for family, models in groups:
        rows = [summary_row(m, columns, best) for m in models if m.get("applicable")]
        if rows:
            body.append(f"<tbody><tr class=fam><th colspan={len(columns) + 3}>{html.escape(family)}</th></tr>"
                        + "".join(rows) + "</tbody>")
    return (f"<table class=summary><thead><tr><th rowspan=2>model</th><th colspan={max(len(columns), 1)}>rmse remapped "
            f"at theta_i (deg), side</th><th rowspan=2>within noise</th><th rowspan=2>model seconds</th></tr>"
            f"<tr>{head}</tr></thead>{''.join(body)}</table>")


def best_list(summary):
    """The best model of each incident angle and side, and its tie, as one list."""
    items = []
    for b in summary.get("best_model", []):
        tie = f" (tie with {html.escape(b['runner_up'])})" if b.get("tie") else ""
        items.append(f"<li>{b['theta_i']:g} {b['side']}: <b>{html.escape(b['best'])}</b>{tie}</li>")
    return f"<ul class=best>{''.join(items)}</ul>" if items else ""


def not_applicable_line(models):
    """The models that cannot represent the stack, in one line (their reasons are in the details below)."""
    ids = [html.escape(m["id"]) for m in models if not m.get("applicable")]
    return f"<p>Not applicable to this stack ({len(ids)}): {', '.join(ids)}.</p>" if ids else ""


def detail_row(m, side, a, best):
    """One model's detailed metrics at one incident angle and side."""
    mx = a["max_error_remapped"]
    mark, other = best_mark(m["id"], best.get((a["theta_i"], side), {}))
    note = ""
    if mark == "best":
        note = " <b>best</b>" + (f" (tie with {html.escape(other)})" if other else "")
    elif mark == "tie":
        note = f" <b>tie</b> (with {html.escape(other)})"
    verdict = ("<span style='color:#070'>within noise</span>" if a["within_reference_noise"]
               else "<span style='color:#a00'>differs</span>: " + html.escape(a.get("verdict", "")))
    albedo = " ".join(f"{v:+.4f}" for v in a["albedo_error"])
    if a.get("reflects_more_than_it_receives"):
        albedo += " <b>reflects " + " ".join(f"{v:.3f}" for v in a["albedo_model_total"]) + " &gt; 1</b>"
    cells = [html.escape(m["id"]) + note, f"{a['theta_i']:g} {side}", f"{a['rmse_remapped']:.4f}",
             f"{a['reference_noise_remapped']:.4f}", f"{a['chi2_per_dof']:.3g}", f"{a['mean_z']:+.3g}",
             f"{a['chi2_p_value']:.2g} / {a['bias_p_value']:.2g}",
             f"{100 * a['smallest_detectable_relative_bias']:.2g}%", verdict, albedo,
             f"{mx['value']:.3f} at theta {mx['theta']:g}, phi {mx['phi']:g} deg, channel {mx['channel']}",
             f"{m['seconds']:.3f}"]
    return "<tr>" + "".join(f"<td>{v}</td>" for v in cells) + "</tr>"


def model_detail_rows(m, best):
    """An applicable model's detailed rows: one per angle and side, or one saying why it was not scored."""
    if not is_scored(m):
        return [f"<tr><td>{html.escape(m['id'])}</td><td colspan=11>not scored: {html.escape(m.get('reason', ''))}"
                f"</td></tr>"]
    return [detail_row(m, side, a, best) for side, a in side_angles(m)]


DETAIL_HEAD = """<tr><th>model</th><th>theta_i, side</th><th>rmse remapped</th><th>reference noise</th><th>chi2/dof</th>
<th>mean z</th><th>p (chi2 / bias)</th><th>detectable bias</th><th>verdict</th><th>albedo error (R G B)</th>
<th>largest remapped error</th><th>model seconds</th></tr>"""


def family_details(groups, best, open_all):
    """Per family with an applicable model, a <details> with its models' detailed per-angle table; its summary line
    counts the models and names the family's best marks."""
    parts = []
    for family, models in groups:
        applicable = [m for m in models if m.get("applicable")]
        if not applicable:
            continue
        scored = sum(1 for m in applicable if is_scored(m))
        wins = sorted({(k[1], k[0]) for m in applicable for k, b in best.items() if best_mark(m["id"], b)[0] == "best"})
        marks = [f"best at {ti:g} {side}" for side, ti in wins]
        line = (f"{html.escape(family)}: {len(applicable)} model{'s' if len(applicable) != 1 else ''}, {scored} scored"
                + (f"; {', '.join(marks)}" if marks else ""))
        rows = [r for m in applicable for r in model_detail_rows(m, best)]
        parts.append(f"<details{' open' if open_all else ''}><summary>{line}</summary><table>{DETAIL_HEAD}"
                     f"{''.join(rows)}</table></details>")
    return "".join(parts)


def not_applicable_details(groups):
    """The models that cannot represent the stack and why, by family, in one <details>."""
    rows = []
    for family, models in groups:
        na = [m for m in models if not m.get("applicable")]
        if na:
            rows.append(f"<tr class=fam><th colspan=2>{html.escape(family)}</th></tr>")
            rows += [f"<tr><td>{html.escape(m['id'])}</td><td>{html.escape(m.get('reason', ''))}</td></tr>" for m in na]
    if not rows:
        return ""
    count = sum(1 for _, models in groups for m in models if not m.get("applicable"))
    return (f"<details><summary>not applicable to this stack: {count} model{'s' if count != 1 else ''}, and why"
            f"</summary><table><tr><th>model</th><th>why not</th></tr>{''.join(rows)}</table></details>")


def energy_table(summary):
    """Where the reference's light went, per incident angle and channel."""
    rows = []
    for a in summary["angles"]:
        e = a["energy"]
        cells = [f"{a['theta_i']:g}", f"{a['paths']:,}"] + [
            " ".join(f"{e[c][k]:.4f}" for c in "RGB")
            for k in ("reflected", "transmitted", "absorbed", "microfacet_loss", "truncated")]
        cells.append(" ".join(f"{e[c]['sum']:.6f}" for c in "RGB"))
        rse = a.get("relative_se", {})
        cells.append(f"{rse.get('median', float('nan')):.3g} / {rse.get('p90', float('nan')):.3g} / "
                     f"{a['worst_relative_se']:.3g}")
        rows.append("<tr>" + "".join(f"<td>{v}</td>" for v in cells) + "</tr>")
    return ("<table><tr><th>theta_i</th><th>paths</th><th>reflected</th><th>transmitted</th><th>absorbed</th>"
            "<th>microfacet loss</th><th>truncated</th><th>sum</th><th>relative se: median / 90th pct / worst</th></tr>"
            + "".join(rows) + "</table>")


HOW_TO_READ = """<h2>How to read the metrics</h2>
<p>Errors are over every bin and channel of one side (R: reflection, T: transmission). <b>rmse remapped</b> is the RMS of
log(1+sqrt f_model) - log(1+sqrt f_reference), the seed's remapping, which weighs lobes and tails alike; the lowest per angle
is marked <b>best</b>, and <b>tie</b> when the reference's noise cannot tell the best two apart (paired test at 1%).
<b>reference noise</b> is the RMS of the reference's own standard error in that space. The verdict is a statistic
(docs/MODELS.md, "Verdicts"): bins are grouped into cells with a trustworthy standard error (relative se below 5%; sparse
bins pooled with their neighbours), each cell gives z = (model - reference) / se; <b>chi2/dof</b> is the mean of
z<sup>2</sup> (about 1 when the model is the reference), <b>mean z</b> the bias (its sign: above or below), <b>p</b> the
p-values of the chi-square test and of the bias test, and <b>within noise</b> means neither rejects agreement at 1%
(the summary counts the angles and sides where it holds).
<b>detectable bias</b>: a model off by this relative factor everywhere would be seen at these paths.
<b>albedo error</b> is the model's directional albedo minus the reference's, per channel.
Ids with a <b>+</b> are gonio's convention variants of a model (+g2: height-correlated Smith G2 in the lobes and tables;
+tir: the TIR term kept below absorbing media); they are in these tables and the albedo figure, the slices and top views
show the models as their official codes compute them. Models are grouped by family; the summary has one row per model,
the details of a family open with a click.</p>"""

STYLE = """<style>body{font-family:sans-serif;max-width:1800px;margin:auto} p{max-width:75em}
td,th{padding:2px 8px;border-bottom:1px solid #ddd} img{max-width:100%}
table.summary thead th{position:sticky;top:0;background:#fff} tr.fam th{text-align:left;background:#eef}
td.best{background:#efe} td.na{color:#777} details{margin:4px 0} summary{cursor:pointer;font-weight:bold}</style>"""


def metrics_section(summary):
    """The models' part of report.html: the best per angle, the summary table by family, the not-applicable ones,
    the per-family details."""
    models = summary.get("models", [])
    if not models:
        return ""
    groups = group_by_family(models)
    best = {(b["theta_i"], b["side"]): b for b in summary.get("best_model", [])}
    columns = metric_columns(summary, [m for m in models if is_scored(m)])
    open_all = sum(1 for m in models if is_scored(m)) <= 6
    return (f"{HOW_TO_READ}<h2>Models by family</h2><p>Best per incident angle and side:</p>{best_list(summary)}"
            f"{summary_table(groups, columns, best)}{not_applicable_line(models)}"
            f"<h2>Per-angle metrics, by family</h2>{family_details(groups, best, open_all)}"
            f"{not_applicable_details(groups)}")


def write_html(d, topviews):
    """report.html: the run, where the light went, the models' metrics, the figures, the renderings."""
    s = d.summary
    name = s["stack"]
    dtheta, dphi = s["bins"]["dtheta_deg"], s["bins"]["dphi_deg"]
    transmissive = "T" in d.sides
    families = {m["id"]: f for f, ms in group_by_family(s.get("models", [])) for m in ms}
    page = f"""<!doctype html><html><head><meta charset="utf-8"><title>gonio: {html.escape(name)}</title>
{STYLE}</head><body>
<h1>gonio compare: {html.escape(name)}</h1>
<p>{html.escape(s.get('stack_file', ''))}; device {html.escape(s['device'])}; {s['paths_per_angle']} paths per
incident angle, seed {s['seed']}; bins {dtheta:g} x {dphi:g} deg.</p>
<pre>{html.escape(s.get('stack_description', ''))}</pre>
<h2>Where the light went (reference; per channel R G B)</h2>
{energy_table(s)}
{metrics_section(s)}
<h2>Slices</h2><img src="slices.png">{'<img src="slices-T.png">' if transmissive else ''}<h2>Directional albedo</h2><img src="albedo.png">
<h2>Top views</h2>{''.join(f'<h3>theta_i = {ti}</h3><img src="{f}">' for ti, f in topviews)}
{render_section(d.out, families)}</body></html>"""
    with open(os.path.join(d.out, "report.html"), "w") as fh:
        fh.write(page)


def main(out):
    d = load(out)
    for side in d.sides:
        draw_slices(d, side)
    draw_albedo(d)
    topviews = draw_topviews(d)
    write_html(d, topviews)
    print(f"wrote {out}/{{slices.png{',slices-T.png' if 'T' in d.sides else ''},albedo.png,topview-*.png,report.html}}")


def num(x, fmt):
    """A render.json number in fmt, or '-' where it is missing."""
    return fmt % x if isinstance(x, (int, float)) else "-"


def render_rows(j, families):
    """render.json's models as table rows, grouped by their family in summary.json (a family row first)."""
    groups = {}
    for m in j["models"]:
        groups.setdefault(families.get(m["id"], m["id"].split("+", 1)[0]), []).append(m)
    rows = []
    for family, models in groups.items():
        rows.append(f"<tr class=fam><th colspan=4>{html.escape(family)}</th></tr>")
        for m in models:
            if "not_rendered" in m:
                rows.append(f"<tr><td>{html.escape(m['id'])}</td><td colspan=3>not rendered: "
                            f"{html.escape(m['not_rendered'])}</td></tr>")
                continue
            rows.append(f"<tr><td>{html.escape(m['id'])}</td><td>{num(m.get('relative_l1'), '%.4f')}</td>"
                        f"<td>{num(m.get('flip_mean'), '%.4f')}</td><td>{num(m.get('flip_p95'), '%.4f')}</td></tr>")
    return rows


def render_section(out, families=None):
    """report.html's renderings (compare --render ENV): OUT/render's figure and, per model, relative L1 and HDR-FLIP
    beside the reference's floor (render.json, written by gonio render and tools/render_report.py)."""
    path = os.path.join(out, "render", "render.json")
    if not os.path.exists(path):
        return ""
    with open(path) as fh:
        j = json.load(fh)
    floor = j["reference"]["floor"]
    rows = [f"<tr><td>reference (floor: between its halves)</td><td>{num(floor.get('relative_l1_between_halves'), '%.4f')}"
            f"</td><td>{num(floor.get('flip_mean_between_halves'), '%.4f')}</td>"
            f"<td>{num(floor.get('flip_p95_between_halves'), '%.4f')}</td></tr>"]
    rows += render_rows(j, families or {})
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
