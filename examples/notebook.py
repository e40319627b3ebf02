#!/usr/bin/env python3
"""gonio in a notebook, as a script: build a stack, simulate it, score a NumPy model beside a built-in, fit the
NumPy model's roughness, sweep the coat's roughness in a loop, and draw it all. No file is written but the figure.

    PYTHONPATH=python:build/python python3 examples/notebook.py --out notebook.png   (./run build first)

Each cell of a notebook is a block below; CI runs it (tests/python_api_test.py) and checks the figure.
"""
import argparse
import os
import sys

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [os.path.join(here, "..", "python"), os.path.join(here, "..", "build", "python"), here]
import gonio  # noqa: E402
from numpy_ww_corrected import params_of, ww_corrected  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("--out", default="notebook.png", help="the figure (PNG)")
parser.add_argument("--paths", type=float, default=1e6, help="paths per incident angle")
args = parser.parse_args()

# a stack from a dict of the vocabulary's keys (stacks/README.md): a rough clear coat over a red Lambertian
stack = gonio.Stack({"name": "rough-red", "layer": [
    {"interface": "dielectric", "ior": 1.5, "roughness": 0.25, "optical_depth": [0.05, 0.1, 0.2]},
    {"interface": "lambertian", "albedo": [0.6, 0.15, 0.1]}]})
print(stack.check())

# the reference, in memory
run = gonio.simulate(stack, theta_i=[0, 30, 60], paths=args.paths, dtheta=5, dphi=10, seed=1, progress=False)
print("albedo at 30 degrees:", run.albedo("reference", 30))

# a NumPy model scored beside the built-ins, as gonio compare scores them
mine = gonio.Model(ww_corrected, "ww-numpy", params_of(stack), k=8)
cmp = gonio.compare(stack, run, models=["ww-corrected", "openpbr", mine])
scores = {m["id"]: m for m in cmp.summary["models"] if m.get("scored")}
for mid, m in scores.items():
    print(f"{mid:14s} RMSE at 30 degrees {m['angles'][1]['rmse_remapped']:.4f}: {m['angles'][1]['verdict']}")

# the NumPy model's roughness fitted to the reference, with its standard error
fit = gonio.fit(run, mine, free={"alpha": 0.1})
print(f"fitted alpha {fit.value('alpha'):.4f} +- {fit.se('alpha'):.4f} (the stack's 0.25)")

# a sweep is a loop: the albedo at 30 degrees against the coat's roughness
alphas = [0.05, 0.25, 0.5]
albedos = []
for a in alphas:
    stack.layers[0].roughness = a
    albedos.append(gonio.simulate(stack, theta_i=[30], paths=args.paths / 4, dtheta=5, dphi=10,
                                  progress=False).albedo("reference", 30))

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
fig, ax = plt.subplots(1, 2, figsize=(10, 4))
theta = run.bins.theta_centres_deg()
for source, style in (("reference", "k."), ("ww-corrected", "b-"), ("openpbr", "g-"), ("ww-numpy", "r--")):
    f = cmp.f(source, 30)[:, run.bins.n_phi // 2, 0]   # the plane of incidence, the mirror side (phi 180), red
    ax[0].plot(theta, f, style, label=source)
ax[0].set(xlabel="theta_o (degrees)", ylabel="f, red (1/sr)", title="theta_i 30, phi_o 180", yscale="log")
ax[0].legend()
ax[1].plot(alphas, np.array(albedos), "o-")
ax[1].set(xlabel="coat roughness", ylabel="albedo at theta_i 30", title="a sweep in a loop")
fig.tight_layout()
fig.savefig(args.out, dpi=80)
print("wrote", args.out)
