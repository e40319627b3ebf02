#!/usr/bin/env python3
"""What gonio's unpolarised walk costs on a smooth coat over a smooth conductor (docs/SPECTRAL.md, "Polarisation").

usage: polarisation_cost.py [--coat-ior 1.5] [--table data/spectra/au-johnson-christy-1972.csv] [--csv OUT]

The walk averages s and p at every event (as pbrt-v4 does): its reflectance is the Fresnel series of the averaged
reflectances, F + (1 - F)^2 R_b / (1 - F R_b) with F = (F_s + F_p) / 2 at the coat and R_b = (R_s + R_p) / 2 at the
base. On a smooth stack s and p never mix (every event keeps the plane of incidence), so the polarised answer for
unpolarised light is the mean of the two series, each with its own polarisation's reflectances (the coat thick
enough for its reflections to add incoherently). Printed per 10 nm band centre (385 to 775 nm) and incident angle:
both, and (polarised - unpolarised) / unpolarised.
"""
import argparse
import csv
import os
import sys

import numpy as np


def fresnel(n1, n2, cos_i):
    """|r_s|^2 and |r_p|^2 from a medium of real index n1 into n2 (complex for a conductor), cos_i in n1."""
    sin2_t = (n1 / n2) ** 2 * (1 - cos_i ** 2)
    cos_t = np.sqrt(1 - sin2_t + 0j)
    rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t)
    rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t)
    return np.abs(rs) ** 2, np.abs(rp) ** 2


def series(f, rb):
    return f + (1 - f) ** 2 * rb / (1 - f * rb)


def read_table(path):
    rows = []
    with open(path) as fh:
        for line in fh:
            if line.startswith("#") or not line.strip() or not line[0].isdigit():
                continue
            rows.append([float(x) for x in line.split(",")[:3]])
    t = np.asarray(rows)
    return t[:, 0], t[:, 1], t[:, 2]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--coat-ior", type=float, default=1.5)
    ap.add_argument("--table", default=os.path.join(here, "..", "data", "spectra", "au-johnson-christy-1972.csv"))
    ap.add_argument("--csv", help="also write every band and angle to this file")
    a = ap.parse_args()
    nm_t, n_t, k_t = read_table(a.table)
    nm = np.arange(385.0, 780.0, 10.0)
    metal = np.interp(nm, nm_t, n_t) + 1j * np.interp(nm, nm_t, k_t)
    angles = [0, 15, 30, 45, 60, 70, 75, 80, 85]
    rows = []
    for theta in angles:
        ci = np.cos(np.radians(theta))
        fs, fp = fresnel(1.0, a.coat_ior, ci)
        cc = np.sqrt(1 - (np.sin(np.radians(theta)) / a.coat_ior) ** 2)   # in the coat
        bs, bp = fresnel(a.coat_ior, metal, cc)
        pol = 0.5 * (series(fs, bs) + series(fp, bp))
        unpol = series(0.5 * (fs + fp), 0.5 * (bs + bp))
        for k in range(len(nm)):
            rows.append((theta, nm[k], pol[k], unpol[k], (pol[k] - unpol[k]) / unpol[k]))
    r = np.asarray(rows)
    print(f"coat ior {a.coat_ior} over {os.path.basename(a.table)}: (polarised - unpolarised) / unpolarised, %")
    print("theta_i  " + "  ".join(f"{int(x):>5d}" for x in nm[::4]) + "   min (band)")
    for theta in angles:
        d = r[r[:, 0] == theta]
        worst = int(np.argmin(d[:, 4]))
        print(f"{theta:>7d}  " + "  ".join(f"{100 * x:5.2f}" for x in d[::4, 4]) +
              f"   {100 * d[worst, 4]:.2f} ({int(d[worst, 1])} nm)")
    if a.csv:
        with open(a.csv, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["theta_i", "nm", "polarised", "unpolarised", "relative_difference"])
            w.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
