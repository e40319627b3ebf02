#!/usr/bin/env python3
"""How much light a rough metal's microsurface sends back after more than one bounce, and which production model's
compensation restores it (docs/STUDIES.md, "A rough metal's multiple scattering"): for gold and silver (measured n, k
in RGB) at GGX alpha 0.3, 0.6 and 1.0, under an index-matched smooth coat (no coat at all, as every model reads it:
coat IOR 1, roughness 0), it runs `gonio compare` on the stack with `microfacets = "single"` and with
`microfacets = "multiple"` (the walk on the microsurface, Heitz et al. 2016) and writes

  DATA.csv   per metal, alpha, incident angle and applicable model: the model's directional albedo, the single- and
             the multiple-scattering reference's (each the mean of R, G, B), the model's relative error against each,
             and its remapped RMSE against the multiple-scattering reference (its first line: the gonio version, the
             commit and the command that writes it again)
  stdout     the tables docs/STUDIES.md quotes

usage: study_microfacets_metal.py WORK_DIR DATA.csv [--paths N] [--gonio build/gonio] [--metals Au,Ag]
                                  [--alphas 0.3,0.6,1.0]

Every run: incident angles 0, 45, 75 degrees, the default 1 x 2 degree bins, seed 1, every model and its variants
(--models all). A run whose summary.json is in WORK_DIR already is read, not run again.
"""
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from study_common import ROOT, runs_arguments, write_runs_data  # noqa: E402

METALS = ["Au", "Ag"]
ALPHAS = ["0.3", "0.6", "1.0"]
SCATTERING = ["single", "multiple"]
ANGLES = "0,45,75"
# the production models the tables show (every applicable model goes into DATA.csv)
PRODUCTION = ["openpbr", "openpbr+single", "standard-surface", "materialx-layer", "cycles-principled", "openpbr-adobe"]


def run_name(metal, alpha, scattering):
    return f"bare-{metal.lower()}-{alpha}-{scattering}"


def stack_text(metal, alpha, scattering):
    return (f'name = "{run_name(metal, alpha, scattering)}"\n'
            f'description = "{metal}, GGX alpha {alpha}, {scattering} scattering on the microsurface, under an '
            'index-matched smooth coat (no coat)"\nexterior_ior = 1.0\n\n'
            '[[layer]]\ninterface = "dielectric"\nior = 1.0\nroughness = 0\n\n'
            f'[[layer]]\ninterface = "conductor"\nmaterial = "{metal}"\nroughness = {alpha}\n'
            f'microfacets = "{scattering}"\n')


def summary(work, metal, alpha, scattering, gonio, paths):
    """the compare run's summary.json, run now where WORK_DIR lacks it"""
    name = run_name(metal, alpha, scattering)
    out = os.path.join(work, name)
    path = os.path.join(out, "summary.json")
    if not os.path.exists(path):
        os.makedirs(work, exist_ok=True)
        stack = os.path.join(work, name + ".toml")
        with open(stack, "w") as fh:
            fh.write(stack_text(metal, alpha, scattering))
        subprocess.run([gonio, "compare", stack, "--theta-i", ANGLES, "--paths", str(paths), "--seed", "1",
                        "--models", "all", "--no-report", "--quiet", "--out", out], check=True,
                       stdout=subprocess.DEVNULL)
    with open(path) as fh:
        return json.load(fh)


def mean3(v):
    return sum(v) / len(v)


def rows_of(metal, alpha, single, multiple):
    """one row per incident angle and model applicable to the multiple-scattering run"""
    refs = {}
    for name, run in (("single", single), ("multiple", multiple)):
        scored = [m for m in run["models"] if m["applicable"]]
        refs[name] = [mean3(a["albedo_reference"]) for a in scored[0]["angles"]]
    rows = []
    for m in multiple["models"]:
        if not m["applicable"]:
            continue
        for i, a in enumerate(m["angles"]):
            model = mean3(a["albedo_model"])
            rows.append({"metal": metal, "alpha": alpha, "theta_i": a["theta_i"], "model": m["id"],
                         "albedo_model": f"{model:.5f}", "albedo_single": f"{refs['single'][i]:.5f}",
                         "albedo_multiple": f"{refs['multiple'][i]:.5f}",
                         "error_vs_single": f"{model / refs['single'][i] - 1:.5f}",
                         "error_vs_multiple": f"{model / refs['multiple'][i] - 1:.5f}",
                         "rmse_remapped_vs_multiple": f"{a['rmse_remapped']:.5f}"})
    return rows


def print_tables(rows):
    """the single-scattering reference's loss, and each production model's albedo error against the
    multiple-scattering reference, in percent"""
    keys = sorted({(r["metal"], r["alpha"], r["theta_i"]) for r in rows}, key=lambda k: (k[0], float(k[1]), k[2]))
    by = {(r["metal"], r["alpha"], r["theta_i"], r["model"]): r for r in rows}
    shown = [m for m in PRODUCTION if any(k[3] == m for k in by)]
    print("| metal | alpha | theta_i | albedo, multiple | single's loss | " + " | ".join(shown) + " |")
    print("|---|---|---|---|---|" + "---|" * len(shown))
    for metal, alpha, th in keys:
        any_row = next(r for (m, a, t, _), r in by.items() if (m, a, t) == (metal, alpha, th))
        ms, ss = float(any_row["albedo_multiple"]), float(any_row["albedo_single"])
        cells = [f"{100 * float(by[(metal, alpha, th, m)]['error_vs_multiple']):+.1f}%"
                 if (metal, alpha, th, m) in by else "-" for m in shown]
        print(f"| {metal} | {alpha} | {th:g} | {ms:.4f} | {100 * (ss / ms - 1):+.1f}% | " + " | ".join(cells) + " |")


def main():
    p = runs_arguments(__doc__)
    p.add_argument("--metals", default=",".join(METALS))
    p.add_argument("--alphas", default=",".join(ALPHAS))
    a = p.parse_args()
    rows = []
    for metal in a.metals.split(","):
        for alpha in a.alphas.split(","):
            runs = [summary(a.work, metal, alpha, s, a.gonio, a.paths) for s in SCATTERING]
            rows += rows_of(metal, alpha, *runs)
    write_runs_data(a.gonio, a.data, rows,
                    f"python3 tools/study_microfacets_metal.py {a.work} {a.data} --paths {a.paths}")
    print_tables(rows)


if __name__ == "__main__":
    main()
