#!/usr/bin/env python3
"""tools/study_roughening.py on a synthetic sweep (no Vulkan device, no gonio binary): where the fitted effective
roughness is exactly a known tanh form, the script's closed form gives that form's three numbers back and its
residuals vanish; the published rules are computed as they are written (OpenPBR v1.1.1, adobe/openpbr-bsdf, PR #261)
at a configuration worked by hand; a configuration the fit left unconstrained stays out of the fit and the residuals.

usage: study_roughening_test.py    (Python 3 with numpy and matplotlib: /usr/bin/python3 on Debian)
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
KEY = "fit.standard-surface.layer.2.roughness"


def known_form(eta, ac, ab, a=1.1, b=0.9, c=0.8):
    B = (eta - 1) * math.sqrt(1 + eta * eta) / eta
    return c * math.tanh(math.hypot(a * eta * ab, b * B * ac) / c)


def main():
    with tempfile.TemporaryDirectory() as d:
        sweep = os.path.join(d, "sweep")
        os.makedirs(sweep)
        header = ["config", "layer1.ior", "layer1.roughness", "layer2.roughness", "theta_i", "side", "model",
                  KEY, KEY + ".se", KEY + ".status", "fit.standard-surface.loss"]
        rows, i = [], 0
        for eta in (1.3, 1.5, 2.0):
            for ac in (0.0, 0.1, 0.3):
                for ab in (0.05, 0.2, 0.4):
                    unconstrained = (eta, ac, ab) == (1.5, 0.1, 0.2)   # would spoil the fit if it were read
                    value = "" if unconstrained else f"{known_form(eta, ac, ab):.9g}"
                    status = "unconstrained" if unconstrained else "fitted"
                    for model in ("reference", "openpbr"):   # the fit columns repeat on every row
                        rows.append([i, eta, ac, ab, 0, "R", model, value, "" if unconstrained else "1e-4", status,
                                     "0.001"])
                    i += 1
        with open(os.path.join(sweep, "sweep.csv"), "w", newline="") as fh:
            csv.writer(fh).writerows([header] + rows)
        with open(os.path.join(sweep, "sweep.json"), "w") as fh:
            json.dump({"sweep_file": "sweeps/synthetic.toml"}, fh)
        data, figure = os.path.join(d, "data.csv"), os.path.join(d, "figure.png")
        run = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "study_roughening.py"), sweep, data, figure],
                             capture_output=True, text=True)
        assert run.returncode == 0, run.stderr
        assert "26 of 27 configurations fitted" in run.stdout, run.stdout
        with open(data) as fh:
            lines = fh.read().splitlines()
        closed = next(x for x in lines if x.startswith("# closed form"))
        # the known form's a = 1.1, b = 0.9, c = 0.8 back (c on the script's grid of 0.005)
        assert "alpha_eff = 0.800 tanh(sqrt((1.1000 eta alpha_b)^2 + (0.9000 B(eta) alpha_c)^2) / 0.800)" in closed, \
            closed
        table = list(csv.DictReader(x for x in lines if not x.startswith("#")))
        assert len(table) == 27
        for r in table:
            eta, ac, ab = float(r["eta"]), float(r["alpha_c"]), float(r["alpha_b"])
            if r["status"] == "fitted":
                assert abs(float(r["closed_form"]) - float(r["alpha_eff"])) < 1e-5, r
            else:
                assert r["alpha_eff"] == "" and r["status"] == "unconstrained", r
            if (eta, ac, ab) == (2.0, 0.3, 0.2):   # each rule by hand
                assert abs(float(r["openpbr_v1.1.1"]) - math.sqrt(0.04 + 2 * 0.09)) < 1e-6, r
                assert abs(float(r["adobe_openpbr_bsdf"]) - math.sqrt(0.04 + 0.5 * 0.09)) < 1e-6, r
                B = 1.05 * 1.0 * math.sqrt(5.0) / 2.0
                assert abs(float(r["openpbr_pr261"]) - 0.85 * math.tanh(math.hypot(0.4, B * 0.3) / 0.85)) < 1e-6, r
        closed_rms = next(x for x in run.stdout.splitlines() if x.startswith("closed_form"))
        assert float(closed_rms.split()[1]) < 1e-5, closed_rms
        assert os.path.getsize(figure) > 0
    print("study_roughening: the known form recovered, the rules as written")


if __name__ == "__main__":
    main()
