#!/usr/bin/env python3
"""gonio render's report: HDR-FLIP of each model against the reference (and of the reference's two halves, its
floor), FLIP maps, and figure.png in the manner of Bati et al. 2019's Figure 6: a row of spheres (reference, then
each model), their FLIP maps below. Adds the numbers to DIR/render.json; without the flip-evaluator package
(pip install flip-evaluator) it says so there and draws the spheres alone.

usage: render_report.py DIR
"""
import json
import os
import sys

import numpy as np

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:  # FLIP's numbers without the figure
    plt = None


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


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    d = sys.argv[1]
    jpath = os.path.join(d, "render.json")
    with open(jpath) as f:
        j = json.load(f)
    ids = [m["id"] for m in j["models"] if "not_rendered" not in m]
    try:
        ref = read_rgba(os.path.join(d, "reference.exr"))
        halves = [read_rgba(os.path.join(d, "reference-half-%s.exr" % h)) for h in "ab"]
        imgs = {i: read_rgba(os.path.join(d, i + ".exr")) for i in ids}
    except ImportError as e:
        j["flip"] = "not computed: the EXR reader is missing (%s; pip install OpenEXR)" % e
        imgs = None
    maps = {}
    if imgs is not None:
        mask = ref[..., 3] > 0
        try:
            import flip_evaluator as flip
        except ImportError as e:
            flip = None
            j["flip"] = "not computed: the flip-evaluator package is missing (%s; pip install flip-evaluator)" % e
        if flip is not None:
            try:
                from importlib.metadata import version

                ver = version("flip-evaluator")
            except Exception:  # noqa: BLE001
                ver = "unknown"
            j["flip"] = {"package": "flip-evaluator " + ver, "mode": "HDR (default parameters: 67 pixels per degree, "
                         "exposures chosen by FLIP)", "over": "the sphere's pixels"}
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
    j["figure"] = "figure.png" if plt is not None else "not drawn: matplotlib is missing (Debian: python3-matplotlib)"
    with open(jpath, "w") as f:
        json.dump(j, f, indent=2)
        f.write("\n")
    if plt is None:
        return

    # the figure: spheres (the PNGs render wrote, one exposure), FLIP maps below
    cols = ["reference"] + ids
    rows = 2 if maps else 1
    fig, ax = plt.subplots(rows, len(cols), figsize=(2.2 * len(cols), 2.4 * rows + 0.3), squeeze=False)
    for c, name in enumerate(cols):
        a = ax[0][c]
        a.imshow(plt.imread(os.path.join(d, name + ".png")))
        a.set_title(name, fontsize=8)
        a.axis("off")
        if rows == 2:
            b = ax[1][c]
            b.imshow(maps[name], cmap="magma", vmin=0, vmax=1)
            b.axis("off")
            if name == "reference":
                fl = j["reference"]["floor"]
                b.set_title("floor (halves)\nFLIP %.3f" % fl["flip_mean_between_halves"], fontsize=7)
            else:
                m = next(x for x in j["models"] if x["id"] == name)
                b.set_title("FLIP %.3f  L1 %.1f%%" % (m["flip_mean"], 100 * m["relative_l1"]), fontsize=7)
    fig.suptitle("%s under %s" % (j["stack"], j["environment"]["name"]), fontsize=9)
    fig.tight_layout()
    fig.savefig(os.path.join(d, "figure.png"), dpi=110)


if __name__ == "__main__":
    main()
