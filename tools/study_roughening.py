#!/usr/bin/env python3
"""The coat-roughening study (docs/STUDIES.md): reads a gonio sweep of sweeps/coat-roughening-*.toml and writes

  DATA.csv     per configuration: the coat's relative IOR eta, its roughness alpha_c, the base's alpha_b, the fitted
               effective roughness alpha_eff with its standard error, the fit's status and loss, and what each
               published rule gives (OpenPBR v1.1.1, adobe/openpbr-bsdf, OpenPBR PR #261) and the closed form below
  FIGURE.png   alpha_eff against each rule, and against the closed form
  stdout       the closed form's coefficients and every rule's residuals (RMS, largest, in units of alpha and of se)

usage: study_roughening.py SWEEP_DIR DATA.csv FIGURE.png

The closed form is PR #261's with its three numbers free:
    alpha_eff = c tanh(sqrt((a eta alpha_b)^2 + (b B(eta) alpha_c)^2) / c),   B(eta) = (eta - 1) sqrt(1 + eta^2) / eta
(PR #261: a = 1, b = 1.05, c = 0.85), fitted by least squares in alpha: for each c, (c atanh(alpha_eff / c))^2 is
linear in a^2 and b^2; the c whose fit has the smallest RMS residual in alpha (a grid, then golden-section search)
is kept. Unweighted: the fits' own
standard errors (1e-4 to 1e-3) are far below the form's misfit, and weighting by them would fit the narrowest lobes
alone.
The CSV's first line holds the gonio version, its commit, and the commands that regenerate the file (the sweep's file
from SWEEP_DIR/sweep.json).
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from study_common import provenance  # noqa: E402


def rules(eta, ac, ab):
    """alpha'_B of each published rule at coat weight 1 (the rules as gonio's models compute them)"""
    spec = np.sqrt(np.minimum(1.0, ab ** 2 + 2.0 * ac ** 2))   # OpenPBR v1.1.1: r'^4 = r_B^4 + 2 r_C^4, alpha = r^2
    adobe = np.sqrt(ab ** 2 + (1.0 - 1.0 / eta) * ac ** 2)   # adobe/openpbr-bsdf: X = 1 - 1/eta in place of 2
    B = 1.05 * (eta - 1.0) * np.sqrt(1.0 + eta ** 2) / eta   # OpenPBR PR #261
    pr261 = 0.85 * np.tanh(np.sqrt((eta * ab) ** 2 + (B * ac) ** 2) / 0.85)
    return {"openpbr_v1.1.1": spec, "adobe_openpbr_bsdf": adobe, "openpbr_pr261": pr261}


def main(sweep_dir, data_path, figure_path):
    with open(os.path.join(sweep_dir, "sweep.csv")) as fh:
        rows = list(csv.DictReader(fh))
    fit = next(h for h in rows[0] if h.startswith("fit.") and h.endswith(".layer.2.roughness"))
    model = fit.split(".")[1]
    configs = {}
    for r in rows:   # the fit columns are the same on every row of a configuration
        configs.setdefault(int(r["config"]), r)
    cfg = [configs[i] for i in sorted(configs)]
    eta = np.array([float(r["layer1.ior"]) for r in cfg])   # the exterior is air (the study's stack)
    ac = np.array([float(r["layer1.roughness"]) for r in cfg])
    ab = np.array([float(r["layer2.roughness"]) for r in cfg])
    status = [r[fit + ".status"] for r in cfg]
    ok = np.array([s == "fitted" for s in status])   # at-limit: written, not fitted by the closed form
    a_eff = np.array([float(r[fit]) if r[fit] else np.nan for r in cfg])
    given = np.isfinite(a_eff)
    se = np.array([float(r[fit + ".se"]) if r[fit + ".se"] else np.nan for r in cfg])
    loss = np.array([float(r[f"fit.{model}.loss"]) if r[f"fit.{model}.loss"] else np.nan for r in cfg])

    # the closed form: for each cap c, least squares of (c atanh(alpha_eff / c))^2 in a^2 and b^2
    B = (eta - 1.0) * np.sqrt(1.0 + eta ** 2) / eta
    X = np.stack([(eta * ab) ** 2, (B * ac) ** 2], axis=1)
    def form_at(c):   # (RMS in alpha, c, [a^2, b^2], the form at every configuration)
        y = (c * np.arctanh(a_eff[ok] / c)) ** 2
        coef, *_ = np.linalg.lstsq(X[ok], y, rcond=None)
        form = c * np.tanh(np.sqrt(np.maximum(X @ coef, 0.0)) / c)
        return np.sqrt(np.mean((form[ok] - a_eff[ok]) ** 2)), c, coef, form

    # a grid of c, then golden-section search around its best node
    lo_c = np.nanmax(a_eff[ok]) * (1 + 1e-9)
    grid = lo_c + np.geomspace(1e-4, 3.0, 200)
    k = int(np.argmin([form_at(c)[0] for c in grid]))
    lo, hi = (grid[k - 1] if k > 0 else lo_c), grid[min(k + 1, len(grid) - 1)]
    g = (np.sqrt(5.0) - 1.0) / 2.0
    for _ in range(80):
        c1, c2 = hi - g * (hi - lo), lo + g * (hi - lo)
        if form_at(c1)[0] < form_at(c2)[0]:
            hi = c2
        else:
            lo = c1
    _, c_coef, coef, closed = form_at(0.5 * (lo + hi))
    a_coef, b_coef = np.sqrt(np.maximum(coef, 0.0))
    predicted = rules(eta, ac, ab)
    predicted["closed_form"] = closed

    with open(data_path, "w", newline="") as fh:
        fh.write(provenance("study_roughening.py", sweep_dir, data_path, figure_path))
        fh.write(f"# effective roughness: {fit} (the fit's other free keys absorb the lobe's energy)\n")
        fh.write(f"# closed form: alpha_eff = {c_coef:.3f} tanh(sqrt(({a_coef:.4f} eta alpha_b)^2 + ({b_coef:.4f} B(eta) "
                 f"alpha_c)^2) / {c_coef:.3f}), B(eta) = (eta - 1) sqrt(1 + eta^2) / eta\n")
        out = csv.writer(fh)
        names = list(predicted)
        out.writerow(["eta", "alpha_c", "alpha_b", "alpha_eff", "alpha_eff_se", "status", "fit_loss"] + names)
        for i in range(len(cfg)):
            out.writerow([f"{eta[i]:g}", f"{ac[i]:g}", f"{ab[i]:g}",
                          f"{a_eff[i]:.6g}" if given[i] else "", f"{se[i]:.3g}" if given[i] else "", status[i],
                          f"{loss[i]:.6g}" if np.isfinite(loss[i]) else ""]
                         + [f"{predicted[n][i]:.6g}" for n in names])

    print(f"{ok.sum()} of {len(cfg)} configurations fitted ({model}); sweep {sweep_dir}")
    print(f"closed form: alpha_eff = {c_coef:.3f} tanh(sqrt(({a_coef:.4f} eta alpha_b)^2 + ({b_coef:.4f} B(eta) alpha_c)^2)"
          f" / {c_coef:.3f})")
    print(f"{'rule':20s} {'RMS':>8s} {'largest':>8s} {'RMS/se':>8s}  (alpha_rule - alpha_eff over the fitted)")
    for n, p in predicted.items():
        d = p[ok] - a_eff[ok]
        print(f"{n:20s} {np.sqrt(np.mean(d ** 2)):8.4f} {np.max(np.abs(d)):8.4f} "
              f"{np.sqrt(np.mean((d / se[ok]) ** 2)):8.1f}")
    smooth = ok & (ac == 0.0)
    if smooth.any():
        print("smooth coat: alpha_eff / alpha_b against eta")
        for e in sorted(set(eta[smooth])):
            sel = smooth & (eta == e)
            ratio = a_eff[sel] / ab[sel]
            print(f"  eta {e:g}: " + ", ".join(f"{x:.3f} (alpha_b {b:g})" for x, b in zip(ratio, ab[sel])))

    fig, axes = plt.subplots(1, len(predicted), figsize=(4.0 * len(predicted), 4.0), squeeze=False)
    lim = max(np.nanmax(a_eff), max(np.max(p) for p in predicted.values())) * 1.05
    for ax, (n, p) in zip(axes[0], predicted.items()):
        sc = ax.scatter(a_eff[ok], p[ok], c=eta[ok], s=10 + 60 * ac[ok], cmap="viridis")
        ax.plot([0, lim], [0, lim], "k--", lw=0.8)
        ax.set_xlim(0, lim)
        ax.set_ylim(0, lim)
        ax.set_xlabel("alpha_eff fitted to the reference")
        ax.set_ylabel(f"{n}")
        d = p[ok] - a_eff[ok]
        ax.set_title(f"{n}: RMS {np.sqrt(np.mean(d ** 2)):.3f}", fontsize=9)
    fig.colorbar(sc, ax=axes[0][-1], label="coat IOR eta (marker size: coat roughness)")
    fig.tight_layout()
    fig.savefig(figure_path, dpi=90)
    print(f"wrote {data_path} and {figure_path}")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
