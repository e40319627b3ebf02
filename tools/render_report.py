#!/usr/bin/env python3
"""gonio render's report: HDR-FLIP of each model against the reference (and of the reference's two halves, its
floor), FLIP maps, and figure.png in the manner of Bati et al. 2019's Figure 6: a grid of spheres, at most six a
row (the reference, then each model, each with its relative L1), then their FLIP maps in a grid of the same shape, each
map in its sphere's place (the reference's place: its floor, its two halves against each other). Adds the numbers to
DIR/render.json; without the flip-evaluator package (pip install flip-evaluator) it says so there and draws the
spheres alone.

usage: render_report.py DIR
"""
import json
import math
import os
import sys
import textwrap

import numpy as np

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:  # FLIP's numbers without the figure
    plt = None

COLUMNS = 6   # spheres a row: 6 x 250 px and the colour bar stay under 1800 px at 110 dpi


def read_rgba(path):
    import OpenEXR

    with OpenEXR.File(path, separate_channels=True) as f:
        ch = f.parts[0].channels
        return np.stack([np.asarray(ch[c].pixels, dtype=np.float32) for c in "RGBA"], axis=-1)


def flip_stats(flip, ref, test, mask):
    """HDR-FLIP map of test against ref (H x W x 3 linear RGB, negatives clamped to 0) and its mean and 95th
    percentile over the sphere's pixels."""
    r = np.ascontiguousarray(np.clip(ref[..., :3], 0, None), dtype=np.float32)
    t = np.ascontiguousarray(np.clip(test[..., :3], 0, None), dtype=np.float32)
    err, _, _ = flip.evaluate(r, t, "HDR")
    err = np.asarray(err, dtype=np.float64)
    if err.ndim == 3:
        err = err[..., 0]
    vals = err[mask]
    return err, float(vals.mean()), float(np.percentile(vals, 95))


def compute_flip(d, j, ids):
    """HDR-FLIP of each model against the reference and of the reference's halves (its floor), into render.json's
    dict j and flip-MODEL.png; returns the maps {id or "reference" (the floor): H x W}, empty without the EXR reader
    or the flip-evaluator package (j says why)."""
    try:
        ref = read_rgba(os.path.join(d, "reference.exr"))
        halves = [read_rgba(os.path.join(d, "reference-half-%s.exr" % h)) for h in "ab"]
        imgs = {i: read_rgba(os.path.join(d, i + ".exr")) for i in ids}
    except ImportError as e:
        j["flip"] = "not computed: the EXR reader is missing (%s; pip install OpenEXR)" % e
        return {}
    try:
        import flip_evaluator as flip
    except ImportError as e:
        j["flip"] = "not computed: the flip-evaluator package is missing (%s; pip install flip-evaluator)" % e
        return {}
    try:
        from importlib.metadata import version

        ver = version("flip-evaluator")
    except Exception:  # noqa: BLE001
        ver = "unknown"
    j["flip"] = {"package": "flip-evaluator " + ver, "mode": "HDR (default parameters: 67 pixels per degree, "
                 "exposures chosen by FLIP)", "over": "the sphere's pixels"}
    mask = ref[..., 3] > 0
    maps = {}
    err, mean, p95 = flip_stats(flip, halves[0], halves[1], mask)
    maps["reference"] = err
    j["reference"]["floor"]["flip_mean_between_halves"] = mean
    j["reference"]["floor"]["flip_p95_between_halves"] = p95
    for m in j["models"]:
        if m["id"] in imgs:
            err, mean, p95 = flip_stats(flip, ref, imgs[m["id"]], mask)
            maps[m["id"]] = err
            m["flip_mean"] = mean
            m["flip_p95"] = p95
            if plt is not None:
                plt.imsave(os.path.join(d, "flip-%s.png" % m["id"]), err, cmap="magma", vmin=0, vmax=1)
    return maps


def wrap(text, width):
    """A title on lines of at most width characters (a user's model id may be 64 long)."""
    return textwrap.fill(text, width, break_on_hyphens=True)


def percent(x):
    """A render.json fraction as a percentage, or '-' where it is missing."""
    return "%.1f%%" % (100 * x) if isinstance(x, (int, float)) else "-"


def number(x):
    """A render.json number to three decimals, or '-' where it is missing."""
    return "%.3f" % x if isinstance(x, (int, float)) else "-"


def grid_block(sub, n, cols):
    """A block of n panels in rows of cols, every panel frameless, those past n blank; returns the n axes in reading
    order."""
    rows = math.ceil(n / cols)
    axes = list(sub.subplots(rows, cols, squeeze=False).flat)
    for ax in axes:
        ax.axis("off")
    return axes[:n]


def sphere_titles(j, names):
    """Each sphere's title: its name and its relative L1 against the reference (the reference: its floor)."""
    by_id = {m["id"]: m for m in j["models"]}
    floor = j["reference"]["floor"]
    titles = {"reference": "reference\nfloor: L1 %s" % percent(floor.get("relative_l1_between_halves"))}
    for i in names[1:]:
        titles[i] = "%s\nL1 %s" % (wrap(i, 30), percent(by_id[i].get("relative_l1")))
    return titles


def flip_titles(j, names):
    """Each FLIP map's title: its mean and 95th percentile (the reference's place: its floor between its halves)."""
    by_id = {m["id"]: m for m in j["models"]}
    floor = j["reference"]["floor"]
    titles = {"reference": "floor (its halves)\nFLIP %s, p95 %s" % (
        number(floor.get("flip_mean_between_halves")), number(floor.get("flip_p95_between_halves")))}
    for i in names[1:]:
        titles[i] = "%s\nFLIP %s, p95 %s" % (wrap(i, 30), number(by_id[i].get("flip_mean")),
                                             number(by_id[i].get("flip_p95")))
    return titles


def draw_figure(d, j, ids, maps):
    """figure.png: the spheres (the PNGs render wrote, one exposure) in a grid of at most COLUMNS a row, the
    reference first, then each model; with FLIP, the maps in a second block, each in its sphere's place (the
    reference's: its floor), on one colour bar."""
    names = ["reference"] + ids
    n = len(names)
    ncol = min(n, COLUMNS)
    rows = math.ceil(n / ncol)
    blocks = 2 if maps else 1
    width = 2.3 * ncol + 1.0
    chars = int(width * 72 / (0.55 * 9))   # a 9-point title's characters across the figure
    fig = plt.figure(figsize=(width, 2.7 * rows * blocks + 0.4), layout="constrained")
    subs = np.atleast_1d(fig.subfigures(blocks, 1))
    titles = sphere_titles(j, names)
    for ax, name in zip(grid_block(subs[0], n, ncol), names):
        ax.imshow(plt.imread(os.path.join(d, name + ".png")))
        ax.set_title(titles[name], fontsize=8)
    subs[0].suptitle(wrap("the reference, then each model (one exposure: x / (1 + x), sRGB); L1: relative L1 against "
                          "the reference", chars), fontsize=9)
    if maps:
        titles = flip_titles(j, names)
        image = None
        for ax, name in zip(grid_block(subs[1], n, ncol), names):
            if name in maps:
                image = ax.imshow(maps[name], cmap="magma", vmin=0, vmax=1)
                ax.set_title(titles[name], fontsize=8)
        subs[1].colorbar(image, ax=subs[1].axes, shrink=min(0.8, 2.0 / rows), label="HDR-FLIP error")
        subs[1].suptitle(wrap("HDR-FLIP against the reference, each in its sphere's place above", chars), fontsize=9)
    fig.suptitle("%s under %s" % (j["stack"], j["environment"]["name"]), fontsize=10)
    fig.savefig(os.path.join(d, "figure.png"), dpi=110)
    plt.close(fig)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    d = sys.argv[1]
    jpath = os.path.join(d, "render.json")
    with open(jpath) as f:
        j = json.load(f)
    ids = [m["id"] for m in j["models"] if "not_rendered" not in m]
    maps = compute_flip(d, j, ids)
    j["figure"] = "figure.png" if plt is not None else "not drawn: matplotlib is missing (Debian: python3-matplotlib)"
    with open(jpath, "w") as f:
        json.dump(j, f, indent=2)
        f.write("\n")
    if plt is not None:
        draw_figure(d, j, ids, maps)


if __name__ == "__main__":
    main()
