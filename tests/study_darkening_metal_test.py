#!/usr/bin/env python3
"""tools/study_darkening_metal.py on a synthetic sweep (no Vulkan device, no gonio binary): its smooth limit at normal
incidence is the series worked by hand (F0 of the coat, the metal's normal-incidence reflectance against the coat,
((n - eta)^2 + k^2) / ((n + eta)^2 + k^2)); at oblique incidence with k = 0 the conductor's Fresnel is the dielectric
one written out here with real numbers; a model's column is the albedo it was given and its RMS error is printed.

usage: study_darkening_metal_test.py    (Python 3 with numpy and matplotlib: /usr/bin/python3 on Debian)
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
sys.path.insert(0, os.path.join(ROOT, "tools"))
import study_darkening_metal  # noqa: E402


def fresnel_real(mu, n1, n2):
    s2 = (1 - mu * mu) * (n1 / n2) ** 2
    mt = math.sqrt(1 - s2)
    rs, rp = (n1 * mu - n2 * mt) / (n1 * mu + n2 * mt), (n2 * mu - n1 * mt) / (n2 * mu + n1 * mt)
    return 0.5 * (rs * rs + rp * rp)


def main():
    n = study_darkening_metal.METAL_N
    # normal incidence, by hand
    for eta, k in ((1.5, 4.0), (2.0, 1.0)):
        f = ((eta - 1) / (eta + 1)) ** 2
        r_b = ((n - eta) ** 2 + k * k) / ((n + eta) ** 2 + k * k)
        want = f + (1 - f) ** 2 * r_b / (1 - f * r_b)
        got = study_darkening_metal.smooth_limit(eta, k, 1.0)
        assert abs(got - want) < 1e-12, (eta, k, got, want)
    # oblique, a metal of k 0 (a dielectric of index n below the coat), with real arithmetic
    for eta in (1.3, 2.0):
        for deg in (30.0, 60.0, 85.0):
            mu = math.cos(math.radians(deg))
            f = fresnel_real(mu, 1.0, eta)
            mu_t = math.sqrt(1 - (1 - mu * mu) / eta ** 2)
            r_b = fresnel_real(mu_t, eta, n)
            want = f + (1 - f) ** 2 * r_b / (1 - f * r_b)
            got = study_darkening_metal.smooth_limit(eta, 0.0, mu)
            assert abs(got - want) < 1e-12, (eta, deg, got, want)

    with tempfile.TemporaryDirectory() as d:
        sweep = os.path.join(d, "sweep")
        os.makedirs(sweep)
        header = ["config", "layer1.ior", "layer2.roughness", "layer2.k", "theta_i", "side", "model",
                  "albedo_model_r", "albedo_reference_r", "reference_paths"]
        rows, i = [], 0
        for eta in (1.5, 2.0):
            for ab in (0.01, 0.5):
                for k in (1.0, 4.0):
                    for ti in (0.0, 70.0):
                        e = study_darkening_metal.smooth_limit(eta, k, math.cos(math.radians(ti)))
                        rows.append([i, eta, ab, k, ti, "R", "reference", "", f"{e:.12g}", 1e12])
                        off = 0.01 if ab == 0.01 else -0.03
                        rows.append([i, eta, ab, k, ti, "R", "some-model", f"{e + off:.12g}", f"{e:.12g}", 1e12])
                        rows.append([i, eta, ab, k, ti, "R", "refusing-model", "", f"{e:.12g}", 1e12])
                    i += 1
        with open(os.path.join(sweep, "sweep.csv"), "w", newline="") as fh:
            csv.writer(fh).writerows([header] + rows)
        with open(os.path.join(sweep, "sweep.json"), "w") as fh:
            json.dump({"sweep_file": "sweeps/synthetic.toml"}, fh)
        data, figure = os.path.join(d, "data.csv"), os.path.join(d, "figure.png")
        run = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "study_darkening_metal.py"), sweep, data,
                              figure], capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
        with open(data) as fh:
            table = list(csv.DictReader(x for x in fh if not x.startswith("#")))
        assert len(table) == 16, len(table)
        for r in table:
            assert abs(float(r["E_smooth"]) - float(r["E_reference"])) < 1e-6, r
            off = 0.01 if float(r["alpha_b"]) == 0.01 else -0.03
            assert abs(float(r["E_some-model"]) - float(r["E_reference"]) - off) < 1e-6, r
        # the printed table: RMS (mean) per roughness, the refusing model's empty column not counted as an error
        line = next(x for x in run.stdout.splitlines() if x.strip().startswith("some-model"))
        assert "0.010 (+0.010) / 0.030 (-0.030)" in line, line
        assert run.stdout.count("largest |E_smooth - E| 0.0000") == 2, run.stdout   # theta_i 0 and 70
        assert os.path.getsize(figure) > 0
        # a glaze over a diffuse (sweeps/coat-darkening-dielectric.toml): the diffuse's albedo as the third key, no
        # smooth limit (it is the metal's)
        with open(os.path.join(sweep, "sweep.csv"), "w", newline="") as fh:
            csv.writer(fh).writerows([[h.replace("layer2.k", "layer3.albedo") for h in header]] + rows)
        run = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "study_darkening_metal.py"), sweep, data,
                              figure], capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
        with open(data) as fh:
            table = list(csv.DictReader(x for x in fh if not x.startswith("#")))
        assert len(table) == 16 and all(r["E_smooth"] == "" and r["albedo"] in ("1", "4") for r in table), table[0]
        assert "smooth limit" not in run.stdout and "diffuse albedos" in run.stdout, run.stdout
    print("study_darkening_metal: the smooth limit as worked by hand, the models' errors read back")


if __name__ == "__main__":
    main()
