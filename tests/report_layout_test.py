#!/usr/bin/env python3
"""The report's layout with many models: tools/report.py and tools/render_report.py on synthetic outputs of 30 models
(no Vulkan device, no gonio binary): every figure at most 1800 pixels wide and its panels no smaller than at a few
models, report.html's models grouped by family with the best and its tie marked.

usage: report_layout_test.py    (Python 3 with numpy and matplotlib: /usr/bin/python3 on Debian)
"""
import csv
import json
import os
import re
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
sys.path.insert(0, os.path.join(ROOT, "python"))
sys.path.insert(0, os.path.join(ROOT, "tools"))
from gonio.outputs import SLICES_HEADER  # noqa: E402

MAX_WIDTH = 1800
DTHETA, DPHI = 5.0, 10.0
N_THETA, N_PHI = 18, 36
ANGLES = [0.0, 60.0]
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def lobe(theta_i, scale):
    """A synthetic f on the bins: a constant and a lobe around the specular direction, per channel."""
    th = np.radians((np.arange(N_THETA) + 0.5) * DTHETA)[:, None]
    ph = np.radians(np.arange(N_PHI) * DPHI)[None, :]
    ti = np.radians(theta_i)
    cos_spec = np.cos(th) * np.cos(ti) - np.sin(th) * np.sin(ti) * np.cos(ph)
    f = 0.1 + scale * np.exp(20 * (cos_spec - 1))
    return np.stack([f, 0.9 * f, 0.8 * f], axis=-1)


def angle_metrics(theta_i, rmse, within):
    """One incident angle's metrics as compare writes them (the fields report.py reads)."""
    return {"theta_i": theta_i, "rmse_remapped": rmse, "reference_noise_remapped": 0.01, "chi2_per_dof": 2.0,
            "mean_z": 0.5, "chi2_p_value": 0.02, "bias_p_value": 0.3, "smallest_detectable_relative_bias": 0.01,
            "within_reference_noise": within, "verdict": "" if within else "the chi-square test rejects agreement",
            "albedo_error": [0.01, 0.01, 0.01], "albedo_model": [0.3, 0.3, 0.3], "albedo_model_total": [0.3, 0.3, 0.3],
            "reflects_more_than_it_receives": False,
            "max_error_remapped": {"value": 0.2, "theta": 2.5, "phi": 0, "channel": "R"}}


def model_ids():
    """30 drawn models (built-in families, variants, the user's files with long ids), one not applicable, one not
    scored."""
    families = {"ww09": "Weidlich-Wilkie", "ww-corrected": "Weidlich-Wilkie", "belcour18-forward": "Belcour 2018",
                "tm21": "transfer matrices", "openpbr": "production", "standard-surface": "production"}
    models = [(i, {"family": f}) for i, f in families.items()]
    models += [("belcour18-forward+g2", {"family": "Belcour 2018"}), ("openpbr+pr261", {"family": "production"})]
    models += [(f"user-model-{k}", {"file": f"/home/me/user-model-{k}.glsl"}) for k in range(20)]
    models += [(f"a-rather-long-user-model-identifier-with-parts-{k}", {"file": "/home/me/long.glsl"})
               for k in range(4)]
    return models


def write_compare(out):
    """A compare output: summary.json and slices.csv, 30 models drawn (28 as published, 2 variants) plus one not
    applicable and one not scored."""
    models, rows = [], []
    for k, (mid, extra) in enumerate(model_ids()):
        rmse = [0.05 + 0.001 * k, 0.06 + 0.001 * k]
        models.append(dict(extra, id=mid, applicable=True, scored=True, seconds=0.1,
                           angles=[angle_metrics(t, r, k % 5 == 0) for t, r in zip(ANGLES, rmse)]))
        rows += [(mid, t, lobe(t, 1.0 + 0.05 * k)) for t in ANGLES]
    models.append({"id": "gltf-clearcoat", "family": "production", "applicable": False, "reason": "colourless coat"})
    models.append({"id": "nan-test", "file": "/home/me/nan.glsl", "applicable": True, "scored": False,
                   "reason": "NaN in 3 bins"})
    rows += [("reference", t, lobe(t, 1.0)) for t in ANGLES]
    energy = {c: {"reflected": 0.3, "transmitted": 0.0, "absorbed": 0.7, "microfacet_loss": 0.0, "truncated": 0.0,
                  "sum": 1.0} for c in "RGB"}
    summary = {
        "stack": "synthetic", "stack_file": "synthetic.toml", "device": "none", "seed": 1, "paths_per_angle": 1000,
        "stack_description": "synthetic", "bins": {"dtheta_deg": DTHETA, "dphi_deg": DPHI, "n_theta": N_THETA,
                                                   "n_phi": N_PHI},
        "angles": [{"theta_i": t, "paths": 1000, "energy": energy, "relative_se": {"median": 0.1, "p90": 0.2},
                    "worst_relative_se": 0.5} for t in ANGLES],
        "best_model": [{"theta_i": 0.0, "side": "R", "best": "ww09", "runner_up": "ww-corrected", "tie": True},
                       {"theta_i": 60.0, "side": "R", "best": "ww09", "runner_up": "ww-corrected", "tie": False}],
        "models": models}
    with open(os.path.join(out, "summary.json"), "w") as fh:
        json.dump(summary, fh)
    with open(os.path.join(out, "slices.csv"), "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(SLICES_HEADER)
        for source, t, f in rows:
            for i in range(N_THETA):
                for j in range(N_PHI):
                    w.writerow([source, t, "R", i * DTHETA, (i + 1) * DTHETA, (j - 0.5) * DPHI, (j + 0.5) * DPHI,
                                *f[i, j], 0.01, 0.01, 0.01])


def width(path):
    return mpimg.imread(path).shape[1]


def check_compare_figures(out):
    """Every figure exists, at most MAX_WIDTH wide; the top views wrap into rows of six."""
    for name in ("slices.png", "albedo.png", "topview-0.png", "topview-1.png", "report.html"):
        check(os.path.exists(os.path.join(out, name)), f"report.py wrote {name}")
    for name in ("slices.png", "albedo.png", "topview-0.png", "topview-1.png"):
        w = width(os.path.join(out, name))
        check(w <= MAX_WIDTH, f"{name} is {w} <= {MAX_WIDTH} pixels wide with 30 models")
    img = mpimg.imread(os.path.join(out, "topview-0.png"))
    # 31 panels (the reference and 30 models as published) in rows of six: 6 rows a block, 2 blocks, >= 200 px each
    check(img.shape[0] >= 12 * 200, f"topview-0.png is tall enough for two blocks of 6 rows ({img.shape[0]} px)")


def check_report_html(out):
    """The models by family, the best and its tie marked, the details per family."""
    page = open(os.path.join(out, "report.html")).read()
    check("rmse remapped" in page, "report.html has the metric tables")
    families = re.findall(r"<tr class=fam><th colspan=\d+>([^<]*)</th>", page)
    summary_families = families[:5]
    check(summary_families == ["Weidlich-Wilkie", "Belcour 2018", "transfer matrices", "production", "your models"],
          f"the summary table's families, in order: {summary_families}")
    check("<small>best, tie</small>" in page and "<small>tie</small>" in page, "the best and its tie are marked")
    check(page.count("<details") == 6, f"a <details> per family with an applicable model and one for the not "
          f"applicable ({page.count('<details')})")
    fam = page.split(">Belcour 2018<", 1)[1]
    check(fam.index("belcour18-forward<") < fam.index("belcour18-forward+g2"), "a variant follows its model")
    check("not scored: NaN in 3 bins" in page, "a model not scored says why")
    check("gltf-clearcoat" in page.split("Not applicable to this stack", 1)[1], "the not-applicable models listed")


def check_render_figure(tmp):
    """render_report.py's figure.png with 30 models, with FLIP maps and without."""
    import render_report

    d = os.path.join(tmp, "render")
    os.makedirs(d)
    ids = [mid for mid, _ in model_ids()]
    sphere = np.zeros((64, 64, 4))
    sphere[..., :3], sphere[..., 3] = 0.5, 1.0
    for name in ["reference"] + ids:
        plt.imsave(os.path.join(d, name + ".png"), sphere)
    j = {"stack": "synthetic", "environment": {"name": "studio"},
         "reference": {"floor": {"relative_l1_between_halves": 0.03, "flip_mean_between_halves": 0.02,
                                 "flip_p95_between_halves": 0.05}},
         "models": [{"id": i, "relative_l1": 0.1, "flip_mean": 0.2, "flip_p95": 0.4} for i in ids]}
    for maps in ({}, {i: np.random.default_rng(1).random((64, 64)) for i in ["reference"] + ids}):
        render_report.draw_figure(d, j, ids, maps)
        img = mpimg.imread(os.path.join(d, "figure.png"))
        what = "with FLIP maps" if maps else "spheres alone"
        check(img.shape[1] <= MAX_WIDTH, f"figure.png ({what}) is {img.shape[1]} <= {MAX_WIDTH} pixels wide")
        blocks = 2 if maps else 1
        check(img.shape[0] >= blocks * 6 * 200, f"figure.png ({what}): 6 rows of spheres a block ({img.shape[0]} px)")


def main():
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "cmp")
        os.makedirs(out)
        write_compare(out)
        r = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "report.py"), out], capture_output=True,
                           text=True)
        check(r.returncode == 0, "report.py runs on 30 models" + (": " + r.stderr[-2000:] if r.returncode else ""))
        if r.returncode == 0:
            check_compare_figures(out)
            check_report_html(out)
        check_render_figure(tmp)
    print(f"{len(failures)} failures" if failures else "all passed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
