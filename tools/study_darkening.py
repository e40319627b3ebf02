#!/usr/bin/env python3
"""The coat-darkening study (docs/STUDIES.md): reads a gonio sweep of sweeps/coat-darkening.toml and writes

  DATA.csv     per configuration and incident angle: the coat's relative IOR eta, roughness alpha_c and optical depth
               tau, the base's albedo E_b, theta_i, the reference's albedo E (red channel: the stack is grey) and the
               coat's own E_0 (the same coat over a black base), the reference's darkening factor
               Delta = (E - E_0) / (E_b (1 - E_0)) with its approximate standard error, the interfaced-Lambertian
               factor (1 - K) / (1 - E_b K) for the K of OpenPBR v1.1.1 (d'Eon's fit of E_F), of E_F integrated
               exactly, and of the MaterialX graph (F0 for E_F), the glTF KHR_materials_coat draft's darkening
               multiplier (as written, and with the hemispherical mean of F the PR #2534 review asks for), and each
               model's albedo
  FIGURE.png   Delta of the reference against each K's, and each model's albedo error against E_b
  stdout       the tables docs/STUDIES.md quotes

usage: study_darkening.py SWEEP_DIR DATA.csv FIGURE.png [ALPHA_C]

ALPHA_C: the coat roughness the figure's panels show (default 0, the smooth coats; sweeps/coat-darkening-rough*.toml's
figures show 1, the roughest).

The interfaced Lambertian (Elias 2001, d'Eon 2021): a Lambertian of albedo E_b under a smooth dielectric interface of
relative IOR eta has the directional albedo E(mu) = F(mu) + E_b (1 - F(mu)) (1 - K) / (1 - E_b K), K = 1 - (1 - E_F) /
eta^2 the interface's internal hemispherical reflectance, exactly. The albedos' standard errors are the binomial
sqrt(E (1 - E) / N) of N paths, an approximation (gonio's estimators weigh paths).
"""
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


def fresnel(mu, eta):
    """unpolarised dielectric Fresnel reflectance at cosine mu, relative IOR eta (light from the eta = 1 side)"""
    s2 = (1.0 - mu * mu) / (eta * eta)
    if s2 >= 1.0:
        return 1.0
    mt = math.sqrt(1.0 - s2)
    rs = (mu - eta * mt) / (mu + eta * mt)
    rp = (eta * mu - mt) / (eta * mu + mt)
    return 0.5 * (rs * rs + rp * rp)


def fresnel_albedo_exact(eta, n=20000):
    """E_F = 2 int_0^1 F(mu) mu dmu, midpoint rule"""
    mus = (np.arange(n) + 0.5) / n
    return float(2.0 * np.mean([fresnel(m, eta) * m for m in mus]))


def fresnel_albedo_fit(eta):
    """OpenPBR footnote avg_fresnel (d'Eon's fit), eta >= 1"""
    return math.log((10893.0 * eta - 1438.2) / (-774.4 * eta * eta + 10212.0 * eta + 1.0))


def delta(e_b, k):
    return (1.0 - k) / (1.0 - e_b * k)


def schlick(mu, f0):
    return f0 + (1.0 - f0) * (1.0 - mu) ** 5


def schlick_albedo(f0):
    """2 int_0^1 F_Schlick(mu) mu dmu = F0 + (1 - F0) / 21 (2 int (1 - mu)^5 mu dmu = 2 B(2, 6) = 1/21)"""
    return f0 + (1.0 - f0) / 21.0


def gltf_draft_darkening(eta, alpha_c, mu, hemispherical=False):
    """KHR_materials_coat draft (KhronosGroup/glTF PR #2534, extensions/2.0/Khronos/KHR_materials_coat/README.md at
    ac989f7, "Real-time Implementation"), image-based lighting seen from mu: T = (1 - R)^2,
    R = (F_Schlick(mu) + F0 + 0.5 F90) / 2 with F90 = 1, scaled by 1 - 0.5 r_c for the coat's roughness r_c = sqrt(alpha_c);
    T multiplies the base beside fresnel_coat's 1 - F (the draft's `base = material * coatColor * coatDarkening`), so
    it is the draft's Delta. hemispherical: F0 + 0.5 F90 replaced by Schlick's hemispherical albedo."""
    f0 = ((eta - 1.0) / (eta + 1.0)) ** 2
    mean = schlick_albedo(f0) if hemispherical else f0 + 0.5
    r = 0.5 * (schlick(mu, f0) + mean) * (1.0 - 0.5 * math.sqrt(alpha_c))
    return (1.0 - r) ** 2


def read_sweep(sweep_dir):
    """The reference's albedo E and paths N, and each model's albedo, keyed (eta, alpha_c, tau, E_b, theta_i); the
    models' names; K per eta: (v1.1.1's, exact E_F's, MaterialX's)."""
    with open(os.path.join(sweep_dir, "sweep.csv")) as fh:
        rows = list(csv.DictReader(fh))
    E, N, models = {}, {}, defaultdict(dict)   # keys (eta, alpha_c, tau, E_b, theta_i)
    for r in rows:
        if r["side"] != "R":
            continue
        key = (float(r["layer1.ior"]), float(r["layer1.roughness"]), float(r["layer1.optical_depth"]),
               float(r["layer2.albedo"]), float(r["theta_i"]))
        if r["model"] == "reference":
            E[key] = float(r["albedo_reference_r"])
            N[key] = float(r["reference_paths"])
        else:
            models[r["model"]][key] = float(r["albedo_model_r"])
    names = sorted(models, key=lambda m: (m.split("+")[0], m))
    K = {}   # per eta: (v1.1.1's, exact E_F's, MaterialX's)
    for eta in sorted({k[0] for k in E}):
        f0 = ((eta - 1.0) / (eta + 1.0)) ** 2
        K[eta] = (1.0 - (1.0 - fresnel_albedo_fit(eta)) / eta ** 2, 1.0 - (1.0 - fresnel_albedo_exact(eta)) / eta ** 2,
                  1.0 - (1.0 - f0) / eta ** 2)

    return E, N, models, names, K


def darkening_table(E, N, models, names, K):
    """Per configuration and angle: the keys, the reference's albedo and Delta with its se, the formulas' Delta, the
    glTF draft's, and each model's albedo."""
    table = []
    for key in sorted(E):
        eta, ac, tau, e_b, ti = key
        e, e0 = E[key], E[(eta, ac, tau, 0.0, ti)]
        se = math.sqrt(max(e * (1 - e), 0.0) / N[key])
        se0 = math.sqrt(max(e0 * (1 - e0), 0.0) / N[(eta, ac, tau, 0.0, ti)])
        d_true = d_se = float("nan")
        if e_b > 0:
            d_true = (e - e0) / (e_b * (1 - e0))
            d_se = math.hypot(se, (1 - e) / (1 - e0) * se0) / (e_b * (1 - e0))
        mu = math.cos(math.radians(ti))
        table.append([eta, ac, tau, e_b, ti, e, e0, d_true, d_se] + [delta(e_b, k) for k in K[eta]]
                     + [gltf_draft_darkening(eta, ac, mu), gltf_draft_darkening(eta, ac, mu, True)]
                     + [models[m].get(key, float("nan")) for m in names])

    return table


def write_data(table, names, sweep_dir, data_path, figure_path):
    with open(data_path, "w", newline="") as fh:
        fh.write(provenance("study_darkening.py", sweep_dir, data_path, figure_path))
        fh.write("# albedo: the red channel (a grey stack); delta_* = (1 - K) / (1 - E_b K) with K of OpenPBR v1.1.1 "
                 "(d'Eon's E_F fit), of E_F integrated exactly, of the MaterialX graph (F0); delta_gltf_draft*: the glTF "
                 "KHR_materials_coat draft's (1 - R)^2, R with F0 + 0.5 F90 as written or Schlick's hemispherical albedo; "
                 "model columns: albedos\n")
        out = csv.writer(fh)
        out.writerow(["eta", "alpha_c", "tau", "E_b", "theta_i", "E_reference", "E_0", "delta_reference",
                      "delta_reference_se", "delta_openpbr_v1.1.1", "delta_exact_E_F", "delta_materialx_F0",
                      "delta_gltf_draft", "delta_gltf_draft_hemispherical"]
                     + [f"E_{m}" for m in names])
        for t in table:
            out.writerow([f"{x:.6g}" if isinstance(x, float) and not math.isnan(x) else ("" if isinstance(x, float)
                          else x) for x in t])



def print_findings(a, K, names, sweep_dir):
    eta, ac, tau, e_b, ti = a[:, 0], a[:, 1], a[:, 2], a[:, 3], a[:, 4]
    d_true, d_se = a[:, 7], a[:, 8]
    print(f"{len(a)} configuration-angles; sweep {sweep_dir}")
    print("K per eta: v1.1.1 (fit) / exact E_F / MaterialX (F0):")
    for e in sorted(K):
        print(f"  eta {e:g}: " + " / ".join(f"{k:.4f}" for k in K[e]))
    print("the reference's Delta against the formula (clear coats, E_b > 0): mean of (formula - reference) / se and "
          "of (formula / reference - 1)")
    for rough in sorted(set(ac)):
        for t_i in sorted(set(ti)):
            sel = (ac == rough) & (tau == 0) & (e_b > 0) & (ti == t_i)
            parts = []
            for j, n in enumerate(["v1.1.1", "exact E_F", "MaterialX F0"]):
                d = a[sel, 9 + j]
                parts.append(f"{n}: z {np.mean((d - d_true[sel]) / d_se[sel]):+7.1f}, "
                             f"{100 * np.mean(d / d_true[sel] - 1):+6.2f}% (max {100 * np.max(np.abs(d / d_true[sel] - 1)):.2f}%)")
            print(f"  alpha_c {rough:g}, theta_i {t_i:g}: " + "; ".join(parts))
    print("glTF PR #2534: F0 + 0.5 F90 against Schlick's hemispherical albedo F0 + (1 - F0)/21 and the exact E_F:")
    for e in sorted(K):
        f0 = ((e - 1.0) / (e + 1.0)) ** 2
        print(f"  eta {e:g}: F0 + 0.5 = {f0 + 0.5:.4f}, Schlick {schlick_albedo(f0):.4f} "
              f"({(f0 + 0.5) / schlick_albedo(f0):.2f}x), exact E_F {fresnel_albedo_exact(e):.4f} "
              f"({(f0 + 0.5) / fresnel_albedo_exact(e):.2f}x), the coat's internal K_r {K[e][1]:.4f}")
    print("the glTF draft's T against the reference's Delta (clear coats, E_b > 0): mean, smallest and largest T / Delta - 1")
    for rough in sorted(set(ac)):
        for t_i in sorted(set(ti)):
            sel = (ac == rough) & (tau == 0) & (e_b > 0) & (ti == t_i)
            parts = []
            for j, n in enumerate(["as written", "hemispherical"]):
                r = a[sel, 12 + j] / d_true[sel] - 1
                parts.append(f"{n}: {100 * np.mean(r):+6.1f}% ({100 * np.min(r):+.1f} to {100 * np.max(r):+.1f}%)")
            print(f"  alpha_c {rough:g}, theta_i {t_i:g}: " + "; ".join(parts))
    print("  the albedo error the draft's T makes alone, E_b (1 - E_0) (T - Delta), RMS over the smooth clear coats, "
          "as written / hemispherical, at theta_i " + " / ".join(f"{x:g}" for x in sorted(set(ti))) + ": " + ", ".join(
              " / ".join(f"{np.sqrt(np.mean((e_b[s] * (1 - a[s, 6]) * (a[s, 12 + j] - d_true[s])) ** 2)):.3f}"
                         for j in (0, 1))
              for s in [(ac == 0) & (tau == 0) & (e_b > 0) & (ti == x) for x in sorted(set(ti))]))
    sel = (ac == 0) & (tau == 0) & (e_b > 0) & (ti == 0) & (eta == 1.5)
    print("  eta 1.5, smooth, theta_i 0, per E_b: Delta reference / as written / hemispherical: " + "; ".join(
        f"{x:g}: {d_true[sel & (e_b == x)][0]:.3f} / {a[sel & (e_b == x), 12][0]:.3f} / {a[sel & (e_b == x), 13][0]:.3f}"
        for x in sorted(set(e_b[sel]))))
    for rough in sorted(set(ac)):
        print(f"each model's albedo error, model - reference, coat roughness {rough:g} (RMS over the configurations "
              "with E_b > 0 it takes; clear | absorbing coats), at theta_i " + " / ".join(f"{x:g}" for x in sorted(set(ti))))
        for j, m in enumerate(names):
            col = a[:, 14 + j]
            cells = []
            for absorbing in (False, True):
                vals = []
                for t_i in sorted(set(ti)):
                    sel = (e_b > 0) & (ti == t_i) & (ac == rough) & ((tau > 0) == absorbing) & np.isfinite(col)
                    vals.append(f"{np.sqrt(np.mean((col[sel] - a[sel, 5]) ** 2)):.3f}" if sel.any() else "-")
                cells.append(" / ".join(vals))
            print(f"  {m:24s} {cells[0]:22s} | {cells[1]}")


def draw_figure(a, names, figure_path, panel_ac=0.0):
    ac, tau, e_b, ti = a[:, 1], a[:, 2], a[:, 3], a[:, 4]
    d_true = a[:, 7]
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    ax = axes[0]
    coats = "smooth" if panel_ac == 0 else f"alpha_c {panel_ac:g}"
    sel = (tau == 0) & (e_b > 0) & (ti == 0) & (ac == panel_ac)
    for j, (n, mk) in enumerate([("OpenPBR v1.1.1", "o"), ("exact E_F", "x"), ("MaterialX F0", "^"),
                                 ("glTF draft (1 - R)^2", "s"), ("glTF draft, hemispherical F", "v")]):
        ax.scatter(d_true[sel], a[sel, 9 + j], marker=mk, s=18, label=n)
    lim = [np.nanmin(d_true[sel]) * 0.95, 1.0]
    ax.plot(lim, lim, "k--", lw=0.8)
    ax.set_xlabel(f"Delta of the reference, theta_i = 0 ({coats} clear coats)")
    ax.set_ylabel("the model's darkening factor")
    ax.legend(fontsize=8)
    ax.set_title("the darkening factor: formula against the reference", fontsize=9)
    ax = axes[1]
    sel = (e_b > 0) & (ti == 0) & (ac == panel_ac)
    for j, m in enumerate(names):
        col = a[:, 14 + j]
        s = sel & np.isfinite(col)
        if s.any():
            xs = sorted(set(e_b[s]))
            ax.plot(xs, [np.mean(col[s & (e_b == x)] - a[s & (e_b == x), 5]) for x in xs], "-o", ms=3, label=m)
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xlabel("base albedo E_b")
    ax.set_ylabel(f"albedo error at theta_i = 0, mean over the {coats} coats")
    ax.legend(fontsize=6, ncol=2)
    ax.set_title("each model's albedo against the reference", fontsize=9)
    fig.tight_layout()
    fig.savefig(figure_path, dpi=90)


def main(sweep_dir, data_path, figure_path, panel_ac="0"):
    E, N, models, names, K = read_sweep(sweep_dir)
    table = darkening_table(E, N, models, names, K)
    write_data(table, names, sweep_dir, data_path, figure_path)
    a = np.array(table, dtype=float)
    print_findings(a, K, names, sweep_dir)
    draw_figure(a, names, figure_path, float(panel_ac))
    print(f"wrote {data_path} and {figure_path}")


if __name__ == "__main__":
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    main(*sys.argv[1:])
