#!/usr/bin/env python3
"""tools/study_base_f0.py on a synthetic sweep (no Vulkan device, no gonio binary): where the reference's albedo at
normal incidence is F_c + (1 - F_c) E_lobe F0 for a chosen F0, the script's effective F0 is that F0; Filament's
conversion equals the Fresnel against the coat for a real index n >= 1 (the case it was derived for: its f0 is
((n - 1) / (n + 1))^2), and differs from it for a metal; the GGX lobe's own albedo is within 1e-4 of an independent
quadrature (over l, not the half vector); where the sweep's stack walks on the metal's microsurface the lobe is
read as returning all the light (E_lobe 1).

usage: study_base_f0_test.py    (Python 3 with numpy and matplotlib: /usr/bin/python3 on Debian)
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
sys.path.insert(0, os.path.join(ROOT, "tools"))
import study_base_f0  # noqa: E402


def lobe_albedo_over_l(alpha, n=2000):
    """int D(h) G2(l, z) / (4 mu_l) mu_l dl over the hemisphere of l, v = z, by the midpoint rule in theta_l"""
    th = (np.arange(n) + 0.5) / n * (math.pi / 2)
    a2 = alpha * alpha
    h = th / 2   # the half vector of l and z (in the plane of l)
    D = a2 / (math.pi * (np.cos(h) ** 2 * (a2 - 1) + 1) ** 2)
    G2 = 1 / (1 + 0.5 * (np.sqrt(1 + a2 * np.tan(th) ** 2) - 1))
    return float(np.sum(D * G2 / 4 * np.sin(th)) * (math.pi / 2) / n * 2 * math.pi)


def check(sweep_file, e_lobe):
    """a synthetic sweep of sweeps/SWEEP_FILE whose reference is F_c + (1 - F_c) E_lobe F0: F0 read back"""
    f_c = 0.04
    with tempfile.TemporaryDirectory() as d:
        sweep = os.path.join(d, "sweep")
        os.makedirs(sweep)
        header = ["config", "layer2.roughness", "layer2.ior", "layer2.k", "theta_i", "side", "model",
                  "albedo_model_r", "albedo_reference_r"]
        rows, chosen = [], {}
        for i, (n, k) in enumerate([(1.2, 0.0), (2.5, 0.0), (0.5, 3.0), (1.5, 6.0)]):
            f0 = 0.05 + 0.2 * i   # the effective F0 the synthetic reference has
            chosen[(n, k)] = f0
            e = f_c + (1 - f_c) * e_lobe * f0
            rows.append([i, 0.1, n, k, 0, "R", "reference", "", f"{e:.12g}"])
            rows.append([i, 0.1, n, k, 0, "R", "a-model", f"{e - 0.02:.12g}", f"{e:.12g}"])
        with open(os.path.join(sweep, "sweep.csv"), "w", newline="") as fh:
            csv.writer(fh).writerows([header] + rows)
        with open(os.path.join(sweep, "sweep.json"), "w") as fh:
            json.dump({"sweep_file": os.path.join(ROOT, "sweeps", sweep_file)}, fh)
        data, figure = os.path.join(d, "data.csv"), os.path.join(d, "figure.png")
        run = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "study_base_f0.py"), sweep, data, figure],
                             capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
        with open(data) as fh:
            table = list(csv.DictReader(x for x in fh if not x.startswith("#")))
        assert len(table) == 4
        for r in table:
            n, k = float(r["n"]), float(r["k"])
            assert abs(float(r["F0_effective"]) - chosen[(n, k)]) < 1e-5, r
            assert abs(float(r["E_a-model"]) - float(r["E_reference"]) + 0.02) < 1e-6, r
            assert abs(float(r["F0_in_air"]) - ((n - 1) ** 2 + k * k) / ((n + 1) ** 2 + k * k)) < 1e-5, r
            against = ((n - 1.5) ** 2 + k * k) / ((n + 1.5) ** 2 + k * k)
            assert abs(float(r["F0_against_coat"]) - against) < 1e-5, r
            if k == 0 and n >= 1:
                assert abs(float(r["F0_filament"]) - against) < 1e-5, r
            else:
                assert abs(float(r["F0_filament"]) - against) > 1e-3, r
        assert os.path.getsize(figure) > 0


def main():
    for alpha in (0.1, 0.3):
        a, b = study_base_f0.ggx_lobe_albedo(alpha, 4000), lobe_albedo_over_l(alpha, 40000)
        assert abs(a - b) < 1e-4, (alpha, a, b)
    # the single-scattering lobe's own albedo; 1 where the sweep's stack walks on the metal's microsurface
    check("coat-base-f0.toml", study_base_f0.ggx_lobe_albedo(0.1))
    check("coat-base-f0-multiple.toml", 1.0)
    print("study_base_f0: the effective F0 read back, Filament's conversion exact for a dielectric only")


if __name__ == "__main__":
    main()
