#!/usr/bin/env python3
"""The coat-darkening study over smooth and rough bases (docs/STUDIES.md, "The numerator"): reads a gonio sweep of
sweeps/coat-darkening-metal.toml (or of sweeps/coat-darkening-dielectric.toml: a glaze over a diffuse) and writes

  DATA.csv     per configuration and incident angle: the coat's relative IOR eta, the base's roughness alpha_b, the
               metal's extinction k (n 1.5: a grey metal) or the diffuse's albedo under the glaze, theta_i, the
               reference's albedo E (red channel) with its approximate standard error, the smooth limit E_smooth
               (below; metals only), and each model's albedo
  FIGURE.png   each model's albedo error against the metal's roughness
  stdout       the tables docs/STUDIES.md quotes

usage: study_darkening_metal.py SWEEP_DIR DATA.csv FIGURE.png

The smooth limit: a smooth coat over a smooth metal has the albedo E(mu) = F(mu) + (1 - F(mu))^2 R_b(mu_t) /
(1 - F(mu) R_b(mu_t)), F the coat's Fresnel, R_b the metal's against the coat (relative index (n + ik) / eta) at the
refracted cosine mu_t: the light enters with 1 - F, meets the metal at mu_t, and meets the coat from inside at mu_t
again, where it leaves with 1 - F (Fresnel's reciprocity) or returns with F. OpenPBR's darkening for a metal,
Delta = (1 - K) / (1 - E_b K) with K = lerp(K_s, K_r, r_b), K_s = F(mu_v), has this form where r_b = 0; #269's
numerator (1 - E_F) / eta^2 does not. The albedos' standard errors are the binomial sqrt(E (1 - E) / N).
"""
import cmath
import csv
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from study_common import provenance  # noqa: E402

METAL_N = 1.5   # stacks/coats/clear-over-grey-metal.toml


def fresnel_complex(mu, eta_i, n_t):
    """unpolarised Fresnel reflectance at cosine mu from a medium of real index eta_i into one of complex index n_t"""
    m = complex(n_t) / eta_i
    s2 = 1.0 - mu * mu
    ct = cmath.sqrt(1.0 - s2 / (m * m))
    rs = (mu - m * ct) / (mu + m * ct)
    rp = (m * mu - ct) / (m * mu + ct)
    return 0.5 * (abs(rs) ** 2 + abs(rp) ** 2)


def smooth_limit(eta, k, mu):
    """the albedo of a smooth coat of relative IOR eta over a smooth metal of index METAL_N + ik, light at cosine mu"""
    f = fresnel_complex(mu, 1.0, eta)
    mu_t = math.sqrt(1.0 - (1.0 - mu * mu) / (eta * eta))
    r_b = fresnel_complex(mu_t, eta, complex(METAL_N, k))
    return f + (1.0 - f) ** 2 * r_b / (1.0 - f * r_b)


def main(sweep_dir, data_path, figure_path):
    with open(os.path.join(sweep_dir, "sweep.csv")) as fh:
        rows = list(csv.DictReader(fh))
    metal = "layer2.k" in rows[0]   # else a glaze over a diffuse: its albedo
    third = "layer2.k" if metal else "layer3.albedo"
    E, N, models = {}, {}, defaultdict(dict)   # keys (eta, alpha_b, k or albedo, theta_i)
    for r in rows:
        if r["side"] != "R":
            continue
        key = (float(r["layer1.ior"]), float(r["layer2.roughness"]), float(r[third]), float(r["theta_i"]))
        if r["model"] == "reference":
            E[key] = float(r["albedo_reference_r"])
            N[key] = float(r["reference_paths"])
        elif r["albedo_model_r"] != "":
            models[r["model"]][key] = float(r["albedo_model_r"])
    names = sorted(models, key=lambda m: (m.split("+")[0], m))
    table = []
    for key in sorted(E):
        eta, ab, k, ti = key
        e = E[key]
        table.append([eta, ab, k, ti, e, math.sqrt(max(e * (1 - e), 0.0) / N[key]),
                      smooth_limit(eta, k, math.cos(math.radians(ti))) if metal else float("nan")]
                     + [models[m].get(key, float("nan")) for m in names])

    with open(data_path, "w", newline="") as fh:
        fh.write(provenance("study_darkening_metal.py", sweep_dir, data_path, figure_path))
        fh.write(f"# albedo: the red channel (a grey stack: metal n {METAL_N}, k as given; or a glaze over a diffuse of "
                 "the albedo given); E_smooth: a smooth coat over a smooth metal, exactly; model columns: albedos\n")
        out = csv.writer(fh)
        out.writerow(["eta", "alpha_b", "k" if metal else "albedo", "theta_i", "E_reference", "E_reference_se",
                      "E_smooth"]
                     + [f"E_{m}" for m in names])
        for t in table:
            out.writerow([f"{x:.6g}" if not math.isnan(x) else "" for x in t])

    a = np.array(table, dtype=float)
    eta, ab, k, ti, e, se = a[:, 0], a[:, 1], a[:, 2], a[:, 3], a[:, 4], a[:, 5]
    print(f"{len(a)} configuration-angles; sweep {sweep_dir}")
    roughest_smooth = ab == ab.min()
    z = (a[:, 6] - e) / se
    for t_i in sorted(set(ti)) if metal else []:
        s = roughest_smooth & (ti == t_i)
        print(f"the smooth limit against the reference at alpha_b {ab.min():g}, theta_i {t_i:g}: mean z "
              f"{np.mean(z[s]):+.1f}, mean (E_smooth - E) {np.mean((a[:, 6] - e)[s]):+.4f}, largest |E_smooth - E| "
              f"{np.max(np.abs(a[:, 6] - e)[s]):.4f}")
    over = "metals' k" if metal else "diffuse albedos"
    print(f"each model's albedo error, model - reference: RMS (mean) over the coats' IORs, the {over} and theta_i, "
          "per base roughness alpha_b " + " / ".join(f"{x:g}" for x in sorted(set(ab))))
    for j, m in enumerate(names):
        col = a[:, 7 + j]
        cells = []
        for x in sorted(set(ab)):
            s = (ab == x) & np.isfinite(col)
            d = col[s] - e[s]
            cells.append(f"{np.sqrt(np.mean(d ** 2)):.3f} ({np.mean(d):+.3f})" if s.any() else "-")
        print(f"  {m:20s} " + " / ".join(cells))

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for ax, t_i in zip(axes, (0.0, 70.0)):
        for j, m in enumerate(names):
            col = a[:, 7 + j]
            s = (ti == t_i) & np.isfinite(col)
            if s.any():
                xs = sorted(set(ab[s]))
                ax.plot(xs, [np.mean(col[s & (ab == x)] - e[s & (ab == x)]) for x in xs], "-o", ms=3, label=m)
        ax.axhline(0, color="k", lw=0.8)
        ax.set_xscale("log")
        ax.set_xlabel(f"{'metal' if metal else 'glaze'} roughness alpha_b")
        ax.set_ylabel(f"albedo error at theta_i = {t_i:g}, mean over eta and {'k' if metal else 'albedo'}")
        ax.set_title(f"a {'grey metal' if metal else 'glaze over a diffuse'} under a smooth clear coat, "
                     f"theta_i = {t_i:g}", fontsize=9)
        ax.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    fig.savefig(figure_path, dpi=90)
    print(f"wrote {data_path} and {figure_path}")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
