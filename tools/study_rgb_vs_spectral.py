#!/usr/bin/env python3
"""The colour error of rendering coated metals in RGB (docs/SPECTRAL.md, "RGB against spectral"): for each measured
metal (Au, Cu, Al) under an IOR-1.5 coat, clear or tinted yellow at three thicknesses, smooth and rough, it runs
`gonio compare STACK --rgb-vs-spectral --reduction R` for both reductions (dominant, f0) and writes

  DATA.csv   per configuration, reduction and incident angle: the directional albedo's CIEDE2000 and Delta E_ITP
             between the RGB and the spectral run, the lit bins' median and 95th-percentile CIEDE2000 and Delta
             E_ITP, and the bins' noise floor (the median CIEDE2000 the two runs' noise alone makes)
  stdout     the tables docs/SPECTRAL.md quotes

  FIGURE.png per-bin CIEDE2000 maps (top views of the reflected hemisphere, lit bins) of the rough finish under the
             tinted coat (thickness 1) at 45 degrees, each metal, both reductions

usage: study_rgb_vs_spectral.py WORK_DIR DATA.csv FIGURE.png [--paths N] [--gonio build/gonio]
                                [--metals Au,Cu] [--finishes rough] [--coats clear]   (a subset: the test's)

The tinted coat's optical depth is TINT's spectrum (a yellow dye: tau = 0.05 + 0.6 exp(-(lambda - 380 nm) / 60 nm),
absorbing the blue) times the thickness 0.5, 1 or 2. Every run uses 5 x 10 degree bins (the bins' colour is then
above the noise at 2e6 paths; the default 1 x 2 degree bins need about 50 times the paths) and seed 1. A run whose
rgb-vs-spectral.json is in WORK_DIR already is read, not run again.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from study_common import ROOT  # noqa: E402

METALS = ["Au", "Cu", "Al"]
TINT = [(nm, 0.05 + 0.6 * math.exp(-(nm - 380) / 60)) for nm in (380, 400, 420, 450, 500, 550, 600, 700, 780)]
COATS = {"clear": 0.0, "tinted-0.5": 0.5, "tinted-1": 1.0, "tinted-2": 2.0}   # the tint's thickness factor
FINISHES = {"smooth": (0.02, 0.02), "rough": (0.1, 0.3)}   # (coat alpha, metal alpha)
REDUCTIONS = ["dominant", "f0"]
ANGLES = "0,45,75"


def stack_text(metal, coat_name, finish):
    coat, base = FINISHES[finish]
    f = COATS[coat_name]
    tau = "0" if f == 0 else "[" + ", ".join(f"[{nm}, {f * v:.4f}]" for nm, v in TINT) + "]"
    return (f'name = "{coat_name}-coat-{metal.lower()}-{finish}"\n'
            f'description = "{coat_name} coat (ior 1.5, alpha {coat}) over {metal} (alpha {base})"\n'
            'exterior_ior = 1.0\n\n[[layer]]\ninterface = "dielectric"\n'
            f'roughness = {coat}\nior = 1.5\noptical_depth = {tau}\n\n'
            f'[[layer]]\ninterface = "conductor"\nmaterial = "{metal}"\nroughness = {base}\n')


def draw_maps(work, metals, path, finish="rough", coat="tinted-1", theta_i=45.0):
    """per-bin CIEDE2000 of the lit bins, top views (theta radial, phi around), a column per metal, a row per
    reduction; where the configuration was not run, the panel says so"""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    fig, axes = plt.subplots(len(REDUCTIONS), len(metals), subplot_kw={"projection": "polar"},
                             figsize=(3.2 * len(metals), 3.2 * len(REDUCTIONS)), squeeze=False)
    mesh = None
    for i, red in enumerate(REDUCTIONS):
        for j, metal in enumerate(metals):
            ax = axes[i][j]
            ax.set_xticks([])
            ax.set_yticks([])
            f = os.path.join(work, f"{metal}-{finish}-{coat}-{red}", "rgb-vs-spectral.csv")
            if not os.path.exists(f):
                ax.set_title(f"{metal}, {red}: not run", fontsize=9)
                continue
            with open(f) as fh:
                rows = [r for r in csv.DictReader(fh) if float(r["theta_i"]) == theta_i and r["side"] == "R"]
            th = sorted({float(r["theta_lo"]) for r in rows} | {float(r["theta_hi"]) for r in rows})
            ph = sorted({float(r["phi_lo"]) for r in rows} | {float(r["phi_hi"]) for r in rows})
            grid = np.full((len(th) - 1, len(ph) - 1), np.nan)
            for r in rows:
                if r["lit"] == "1":
                    grid[th.index(float(r["theta_lo"])), ph.index(float(r["phi_lo"]))] = float(r["de2000"])
            mesh = ax.pcolormesh(np.radians(ph), th, grid, vmin=0, vmax=15, cmap="magma", shading="flat")
            lit = grid[~np.isnan(grid)]
            med = float(np.median(lit)) if lit.size else float("nan")
            ax.set_title(f"{metal}, {red}: median {med:.1f}", fontsize=9)
    if mesh is not None:
        fig.colorbar(mesh, ax=axes, shrink=0.6, label="CIEDE2000, RGB run against spectral")
    fig.suptitle(f"{finish} {coat} coat, theta_i {theta_i:g}: lit bins (light from phi = 0)", fontsize=10)
    fig.savefig(path, dpi=90)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("work")
    ap.add_argument("data")
    ap.add_argument("figure")
    ap.add_argument("--metals", default=",".join(METALS))
    ap.add_argument("--finishes", default=",".join(FINISHES))
    ap.add_argument("--coats", default=",".join(COATS))
    ap.add_argument("--paths", default="2e6")
    ap.add_argument("--gonio", default=os.path.join(ROOT, "build", "gonio"))
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    metals, finishes, coats = a.metals.split(","), a.finishes.split(","), a.coats.split(",")
    for x, known in ((metals, METALS), (finishes, FINISHES), (coats, COATS)):
        for v in x:
            if v not in known:
                sys.exit(f"study_rgb_vs_spectral.py: unknown '{v}'; known: {', '.join(known)}")
    rows = []
    for metal in metals:
        for finish in finishes:
            for coat in coats:
                stack = os.path.join(a.work, f"{metal}-{finish}-{coat}.toml")
                with open(stack, "w") as fh:
                    fh.write(stack_text(metal, coat, finish))
                for red in REDUCTIONS:
                    out = os.path.join(a.work, f"{metal}-{finish}-{coat}-{red}")
                    cmd = [a.gonio, "compare", stack, "--rgb-vs-spectral", "--reduction", red, "--theta-i", ANGLES,
                           "--paths", a.paths, "--dtheta", "5", "--dphi", "10", "--seed", "1", "--quiet",
                           "--out", out]
                    if not os.path.exists(os.path.join(out, "rgb-vs-spectral.json")):
                        print(" ".join(cmd), file=sys.stderr, flush=True)
                        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
                    with open(os.path.join(out, "rgb-vs-spectral.json")) as fh:
                        j = json.load(fh)
                    for s in j["angles"]:
                        rows.append({"metal": metal, "finish": finish, "coat": coat, "reduction": red,
                                     "theta_i": s["theta_i"], "albedo_de2000": s["albedo"]["de2000"],
                                     "albedo_de_itp": s["albedo"]["de_itp"],
                                     "median_de2000": s["de2000"]["median"], "p95_de2000": s["de2000"]["p95"],
                                     "median_de_itp": s["de_itp"]["median"], "p95_de_itp": s["de_itp"]["p95"],
                                     "noise_de2000": s["median_de2000_noise"], "lit_bins": s["lit_bins"],
                                     "clipped": j["reduction_clipped"]})
    version = subprocess.run([a.gonio, "--version"], capture_output=True, text=True).stdout.strip()
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    with open(a.data, "w", newline="") as fh:
        fh.write(f"# {version} at commit {commit}; regenerate: python3 tools/study_rgb_vs_spectral.py {a.work} "
                 f"{a.data} {a.figure} --paths {a.paths}\n")
        w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.3f}" if isinstance(v, float) and k != "theta_i" else v)
                        for k, v in r.items()})
    # the tables: per metal, finish and coat, both reductions: the albedo's and the bins' median CIEDE2000 per angle
    draw_maps(a.work, metals, a.figure)
    print(f"| metal | finish | coat | dominant: albedo dE00 ({ANGLES.replace(',', '/')}) | bins median | "
          "f0: albedo dE00 | bins median | noise |")
    print("|---|---|---|---|---|---|---|---|")
    for metal in metals:
        for finish in finishes:
            for coat in coats:
                sel = {red: [r for r in rows if r["metal"] == metal and r["finish"] == finish and r["coat"] == coat
                             and r["reduction"] == red] for red in REDUCTIONS}
                cells = []
                for red in REDUCTIONS:
                    cells.append("/".join(f"{r['albedo_de2000']:.1f}" for r in sel[red]))
                    cells.append("/".join(f"{r['median_de2000']:.1f}" for r in sel[red]))
                noise = max(r["noise_de2000"] for red in REDUCTIONS for r in sel[red])
                print(f"| {metal} | {finish} | {coat} | " + " | ".join(cells) + f" | {noise:.2f} |")
    # which reduction is least wrong: the mean over configurations and angles of each statistic
    print()
    for red in REDUCTIONS:
        sel = [r for r in rows if r["reduction"] == red]
        mean = {k: sum(r[k] for r in sel) / len(sel) for k in ("albedo_de2000", "median_de2000", "p95_de2000",
                                                               "albedo_de_itp", "median_de_itp")}
        print(f"{red}: mean albedo dE00 {mean['albedo_de2000']:.2f}, bins median {mean['median_de2000']:.2f}, "
              f"p95 {mean['p95_de2000']:.2f}; albedo dE_ITP {mean['albedo_de_itp']:.1f}, bins median "
              f"{mean['median_de_itp']:.1f}")

if __name__ == "__main__":
    main()
