#!/usr/bin/env python3
"""The base-F0 study (docs/STUDIES.md): reads a gonio sweep of sweeps/coat-base-f0.toml (a smooth coat of IOR 1.5 in
air over a rough conductor of complex IOR n + ik, theta_i = 0) and writes

  DATA.csv     per conductor: n, k, the reference's albedo E at normal incidence, the base's effective reflectance
               under the coat F0_eff = (E - F_c) / ((1 - F_c) E_lobe) (F_c = 0.04 the coat's, E_lobe the GGX lobe's
               own albedo at normal incidence with F = 1), and the F0 an engine puts under the coat: the metal's F0
               in air as it is, Filament's conversion of it, the metal's Fresnel against the coat (|(n + ik - 1.5) /
               (n + ik + 1.5)|^2, one crossing), that with the coat's inter-reflections (T^2 R / (1 - F_c R)); and
               each model's albedo
  FIGURE.png   each F0 against the reference's
  stdout       the table docs/STUDIES.md quotes

usage: study_base_f0.py SWEEP_DIR DATA.csv FIGURE.png

Filament (and Unity HDRP's ConvertF0ForClearCoat15): f0' = (1 - 5 sqrt(f0))^2 / (5 - sqrt(f0))^2, exact for a
dielectric base (its real IOR from f0, against 1.5 instead of 1).
"""
import csv
import json
import math
import os
import sys
import tomllib
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from study_common import provenance  # noqa: E402

ETA_COAT = 1.5


def f0_against(n, k, outside):
    """the normal-incidence reflectance of a conductor n + ik under a medium of real index `outside`"""
    z = complex(n, k)
    return abs((z - outside) / (z + outside)) ** 2


def filament(f0):
    s = math.sqrt(f0)
    return (1 - 5 * s) ** 2 / (5 - s) ** 2


def ggx_lobe_albedo(alpha, n=400):
    """the directional albedo at normal incidence of a GGX reflection lobe with F = 1 and the height-correlated
    Smith G2 (the reference's): int D(h) G2(l, v) / (4 mu_l) over l, by the midpoint rule in the half vector"""
    # v = z; l = reflect(v, h); dl = 4 (v.h) dh; f cos = D G2 / (4 mu_v); mu_v = 1
    th = (np.arange(n) + 0.5) / n * (math.pi / 4)   # half-vector angles up to 45 degrees (l to the horizon)
    a2 = alpha * alpha
    c = np.cos(th)
    D = a2 / (math.pi * (c * c * (a2 - 1) + 1) ** 2)
    lam_l = 0.5 * (np.sqrt(1 + a2 * np.tan(2 * th) ** 2) - 1)
    G2 = 1 / (1 + lam_l)   # Lambda(v) = 0 at normal incidence
    # dl = 4 (v.h) dh, dh = sin th dth dphi
    integrand = D * G2 / 4 * 4 * c * np.sin(th)
    return float(np.sum(integrand) * (math.pi / 4) / n * 2 * math.pi)


def base_walks(sweep_dir):
    """whether the sweep's stack walks on its base's microsurface (`microfacets = "multiple"` on layer 2): its lobe then
    returns all the light at F = 1, E_lobe = 1"""
    with open(os.path.join(sweep_dir, "sweep.json")) as fh:
        sweep_file = json.load(fh)["sweep_file"]
    with open(sweep_file, "rb") as fh:
        stack_file = os.path.join(os.path.dirname(sweep_file), tomllib.load(fh)["stack"])
    with open(stack_file, "rb") as fh:
        return tomllib.load(fh)["layer"][1].get("microfacets") == "multiple"


def main(sweep_dir, data_path, figure_path):
    with open(os.path.join(sweep_dir, "sweep.csv")) as fh:
        rows = list(csv.DictReader(fh))
    E, models, alpha = {}, defaultdict(dict), None
    for r in rows:
        if r["side"] != "R" or float(r["theta_i"]) != 0:
            continue
        key = (float(r["layer2.ior"]), float(r["layer2.k"]))
        alpha = float(r["layer2.roughness"])
        if r["model"] == "reference":
            E[key] = float(r["albedo_reference_r"])
        else:
            models[r["model"]][key] = float(r["albedo_model_r"])
    names = sorted(models)
    f_c = ((ETA_COAT - 1) / (ETA_COAT + 1)) ** 2
    e_lobe = 1.0 if base_walks(sweep_dir) else ggx_lobe_albedo(alpha)
    table = []
    for (n, k), e in sorted(E.items()):
        f0_air = f0_against(n, k, 1.0)
        r_rel = f0_against(n, k, ETA_COAT)
        bounces = (1 - f_c) ** 2 * r_rel / (1 - f_c * r_rel) / (1 - f_c)   # per unit (1 - F_c), as F0_eff
        table.append([n, k, e, (e - f_c) / ((1 - f_c) * e_lobe), f0_air, filament(f0_air), r_rel, bounces]
                     + [models[m].get((n, k), float("nan")) for m in names])
    cols = ["n", "k", "E_reference", "F0_effective", "F0_in_air", "F0_filament", "F0_against_coat",
            "F0_against_coat_with_interreflections"] + [f"E_{m}" for m in names]
    with open(data_path, "w", newline="") as fh:
        fh.write(provenance("study_base_f0.py", sweep_dir, data_path, figure_path))
        lobe = "multiple scattering" if e_lobe == 1.0 else "G2"
        fh.write(f"# theta_i 0; F_c {f_c:.4f} (the smooth coat of IOR {ETA_COAT}); E_lobe {e_lobe:.5f} (GGX alpha "
                 f"{alpha:g}, F = 1, {lobe}); F0_effective = (E_reference - F_c) / ((1 - F_c) E_lobe)\n")
        out = csv.writer(fh)
        out.writerow(cols)
        for t in table:
            out.writerow([f"{x:.6g}" for x in t])
    a = np.array(table, dtype=float)
    print(f"{len(a)} conductors; F_c {f_c:.4f}, E_lobe {e_lobe:.5f} (alpha {alpha:g})")
    # metals (k >= 1); k = 0 is a dielectric, and below the coat's index it reflects totally inside the coat beyond
    # asin(n / 1.5), which no normal-incidence F0 describes
    for label, sel in [("metals (k >= 1)", a[:, 1] >= 1), ("k = 0", a[:, 1] == 0)]:
        print(f"{label}: F0 under the coat against the reference's effective F0 (RMS, largest, of the difference):")
        for j, name in [(4, "the metal's F0 in air, as it is"), (5, "Filament / HDRP's conversion"),
                        (6, "the metal's Fresnel against the coat"), (7, "the same with the coat's inter-reflections")]:
            d = a[sel, j] - a[sel, 3]
            w = np.argmax(np.abs(d))
            print(f"  {name:45s} RMS {np.sqrt(np.mean(d * d)):.4f}, largest {d[w]:+.4f} "
                  f"(n {a[sel][w, 0]:g}, k {a[sel][w, 1]:g})")
        print(f"{label}: each model's albedo error at normal incidence (RMS, largest):")
        for j, m in enumerate(names):
            d = a[sel, 8 + j] - a[sel, 2]
            d = d[np.isfinite(d)]
            if d.size:
                print(f"  {m:24s} RMS {np.sqrt(np.mean(d * d)):.4f}, largest {d[np.argmax(np.abs(d))]:+.4f}")
    fig, ax = plt.subplots(figsize=(5.5, 4.6))
    for j, (name, mk) in enumerate([("in air, as it is", "s"), ("Filament / HDRP", "o"), ("against the coat", "x"),
                                    ("against the coat, inter-reflections", "+")]):
        ax.scatter(a[a[:, 1] >= 1, 3], a[a[:, 1] >= 1, 4 + j], marker=mk, s=22, label=name)
    ax.plot([0, 1], [0, 1], "k--", lw=0.8)
    ax.set_xlabel("the base's effective F0 under the coat (reference)")
    ax.set_ylabel("F0 an engine puts under the coat")
    ax.legend(fontsize=7)
    ax.set_title("a metal's F0 under a clear coat of IOR 1.5 (k >= 1)", fontsize=9)
    fig.tight_layout()
    fig.savefig(figure_path, dpi=90)
    print(f"wrote {data_path} and {figure_path}")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
