#!/usr/bin/env python3
"""The sheen authors' table against gonio's walk, cell by cell.

    tools/ltc_sheen/compare.py SWEEP_DIR [--table data/sheen/ltc-sheen-volume-reflectance.csv] [--out FILE.csv]

SWEEP_DIR is the output of `gonio sweep sweeps/sheen-table.toml` (its sweep.csv: the reference rows' albedo per
fibre_roughness and theta_i). For each cell of the authors' 32 x 32 grid (Zeltner, Burley & Chiang 2022;
data/sheen/README.md) it writes mu, alpha, gonio's reflectance and standard error, the authors' and theirs, and
z = (gonio - authors) / se, the two-proportion z-test (every path's weight is 0 or 1 in the white slab: both are
binomial proportions; se from their pooled proportion), and prints the summary: cells, chi2 / dof, the largest |z|, the share beyond 3. Cells where both are
0 have no z. Exit 1 when a cell of the table is missing from the sweep.
"""
import argparse
import csv
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
AUTHORS_PATHS = 2e6   # per cell, fitting/python/precompute_brdf_values_sheen_volume.py n_samples


def read_table(path):
    cells = {}
    with open(path) as f:
        rows = csv.DictReader(line for line in f if not line.startswith("#"))
        for r in rows:
            cells[(int(r["mu_index"]), int(r["alpha_index"]))] = (float(r["mu"]), float(r["alpha"]),
                                                                  float(r["reflectance"]))
    return cells


def read_sweep(path):
    """(alpha, theta_i) -> (reflectance, paths) from the reference rows (side R)"""
    out = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            if r["model"] != "reference" or r["side"] != "R":
                continue
            out[(float(r["layer1.fibre_roughness"]), float(r["theta_i"]))] = (float(r["albedo_reference_g"]),
                                                                              float(r["reference_paths"]))
    return out


def nearest(sweep, alpha, theta):
    best = min(sweep, key=lambda k: abs(k[0] - alpha) + abs(k[1] - theta))
    return sweep[best] if abs(best[0] - alpha) < 1e-6 and abs(best[1] - theta) < 1e-6 else None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("sweep_dir")
    ap.add_argument("--table", default=os.path.join(ROOT, "data", "sheen", "ltc-sheen-volume-reflectance.csv"))
    ap.add_argument("--out", default=None, help="per-cell CSV (default SWEEP_DIR/ltc-sheen-cells.csv)")
    a = ap.parse_args()
    table = read_table(a.table)
    sweep = read_sweep(os.path.join(a.sweep_dir, "sweep.csv"))
    out = a.out or os.path.join(a.sweep_dir, "ltc-sheen-cells.csv")
    zs, missing = [], 0
    with open(os.path.join(a.sweep_dir, "sweep.json")) as f:
        sweep_json = json.load(f)
    with open(out, "w", newline="") as f:
        f.write("# tools/ltc_sheen/compare.py %s; sweep %s (%s, hash %s); table %s\n" %
                (a.sweep_dir, sweep_json.get("name"), os.path.basename(sweep_json.get("sweep_file", "")),
                 sweep_json.get("hash"), os.path.relpath(a.table, ROOT)))
        w = csv.writer(f)
        w.writerow(["mu_index", "alpha_index", "mu", "alpha", "gonio", "gonio_se", "authors", "authors_se", "z"])
        for (i, j), (mu, alpha, theirs) in sorted(table.items()):
            # the sweep file writes theta_i and alpha with 10 significant digits
            got = nearest(sweep, float("%.10g" % alpha), float("%.10g" % math.degrees(math.acos(mu))))
            if got is None:
                missing += 1
                continue
            ours, n = got
            se_o = math.sqrt(max(ours * (1 - ours), 0) / n)
            se_t = math.sqrt(max(theirs * (1 - theirs), 0) / AUTHORS_PATHS)
            # the two-proportion z-test: under the hypothesis that both estimate one p, its pooled estimate gives
            # both standard errors (a cell of 1e-5 that gonio's fewer paths saw as 0 is not a certainty of 0)
            pooled = (ours * n + theirs * AUTHORS_PATHS) / (n + AUTHORS_PATHS)
            se = math.sqrt(pooled * (1 - pooled) * (1 / n + 1 / AUTHORS_PATHS))
            z = (ours - theirs) / se if se > 0 else None
            if z is not None:
                zs.append(z)
            w.writerow([i, j, mu, alpha, ours, se_o, theirs, se_t, "" if z is None else "%.3f" % z])
    if missing:
        print(f"{missing} cells of the table are not in {a.sweep_dir}/sweep.csv", file=sys.stderr)
        return 1
    chi2 = sum(z * z for z in zs)
    beyond = sum(1 for z in zs if abs(z) > 3)
    print(f"{len(zs)} cells with a z ({len(table) - len(zs)} where both are 0): chi2/dof {chi2 / len(zs):.3f}, "
          f"largest |z| {max(abs(z) for z in zs):.2f}, beyond 3: {beyond} ({100.0 * beyond / len(zs):.2f}%; "
          f"chance 0.27%)")
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
