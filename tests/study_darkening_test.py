#!/usr/bin/env python3
"""tools/study_darkening.py on a synthetic sweep (no Vulkan device, no gonio binary): where the reference's albedo is
exactly the interfaced Lambertian, E(mu) = F(mu) + E_b (1 - F(mu)) (1 - K) / (1 - E_b K) with K = 1 - (1 - E_F) /
eta^2 (E_F integrated here by Gauss-Legendre, independently of the script's midpoint rule), the script's Delta of
the reference is that factor at every configuration, its black base gives E_0 = F, MaterialX's factor is the one
worked by hand, and a model's column is the albedo it was given.

usage: study_darkening_test.py    (Python 3 with numpy and matplotlib: /usr/bin/python3 on Debian)
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


def fresnel(mu, eta):
    s2 = (1 - mu * mu) / (eta * eta)
    mt = math.sqrt(1 - s2)
    rs, rp = (mu - eta * mt) / (mu + eta * mt), (eta * mu - mt) / (eta * mu + mt)
    return 0.5 * (rs * rs + rp * rp)


def fresnel_albedo(eta):   # 2 int_0^1 F(mu) mu dmu, 64-point Gauss-Legendre
    x, w = np.polynomial.legendre.leggauss(64)
    mu = 0.5 * (x + 1)
    return float(np.sum(0.5 * w * 2 * mu * np.array([fresnel(m, eta) for m in mu])))


def main():
    with tempfile.TemporaryDirectory() as d:
        sweep = os.path.join(d, "sweep")
        os.makedirs(sweep)
        header = ["config", "layer1.ior", "layer1.roughness", "layer1.optical_depth", "layer2.albedo", "theta_i", "side",
                  "model", "albedo_model_r", "albedo_reference_r", "reference_paths"]
        rows, i, want = [], 0, {}
        for eta in (1.3, 1.5):
            k = 1 - (1 - fresnel_albedo(eta)) / eta ** 2
            for e_b in (0.0, 0.2, 0.8):
                for ti in (0.0, 60.0):
                    f = fresnel(math.cos(math.radians(ti)), eta)
                    delta = (1 - k) / (1 - e_b * k)
                    e = f + e_b * (1 - f) * delta
                    want[(eta, e_b, ti)] = (e, f, delta)
                    rows.append([i, eta, 0, 0, e_b, ti, "R", "reference", "", f"{e:.12g}", 1e12])
                    rows.append([i, eta, 0, 0, e_b, ti, "R", "some-model", f"{e + 0.01:.12g}", f"{e:.12g}", 1e12])
                i += 1
        with open(os.path.join(sweep, "sweep.csv"), "w", newline="") as fh:
            csv.writer(fh).writerows([header] + rows)
        with open(os.path.join(sweep, "sweep.json"), "w") as fh:
            json.dump({"sweep_file": "sweeps/synthetic.toml"}, fh)
        data, figure = os.path.join(d, "data.csv"), os.path.join(d, "figure.png")
        run = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "study_darkening.py"), sweep, data, figure],
                             capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
        with open(data) as fh:
            table = list(csv.DictReader(x for x in fh if not x.startswith("#")))
        assert len(table) == 12, len(table)
        for r in table:
            eta, e_b, ti = float(r["eta"]), float(r["E_b"]), float(r["theta_i"])
            e, f, delta = want[(eta, e_b, ti)]
            assert abs(float(r["E_reference"]) - e) < 1e-6 and abs(float(r["E_0"]) - f) < 1e-6, r
            assert abs(float(r["E_some-model"]) - (e + 0.01)) < 1e-6, r
            if e_b == 0:
                assert r["delta_reference"] == "", r
                continue
            assert abs(float(r["delta_reference"]) - delta) < 1e-5, (r, delta)
            assert abs(float(r["delta_exact_E_F"]) - delta) < 1e-5, (r, delta)
            if (eta, e_b) == (1.5, 0.2):   # MaterialX's K = 1 - (1 - F0) / eta^2, F0 = 0.04
                k_mx = 1 - 0.96 / 2.25
                assert abs(float(r["delta_materialx_F0"]) - (1 - k_mx) / (1 - 0.2 * k_mx)) < 1e-6, r
            if (eta, ti) == (1.5, 0.0):   # the glTF draft at normal incidence: R = (F0 + F0 + 0.5) / 2 = 0.29
                assert abs(float(r["delta_gltf_draft"]) - 0.71 ** 2) < 1e-6, r
                # Schlick's hemispherical albedo 0.04 + 0.96 / 21: R = (0.04 + 0.04 + 0.96 / 21) / 2
                assert abs(float(r["delta_gltf_draft_hemispherical"]) - (1 - (0.08 + 0.96 / 21) / 2) ** 2) < 1e-6, r
        assert os.path.getsize(figure) > 0
    print("study_darkening: the interfaced Lambertian's factor read back, MaterialX's and the glTF draft's as written")


if __name__ == "__main__":
    main()
