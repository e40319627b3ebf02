#!/usr/bin/env python3
"""gonio's spectral mode against pbrt-v4's spectral LayeredBxDF on a coated gold stack, bin by bin and band by
band (README.md, "Spectral cross-check").

gonio: `gonio simulate stacks/coats/coated-gold.toml --spectral --band-paths even --theta-i 30 --paths N` (40 bands
of 10 nm, each at its centre, 385 ... 775 nm). pbrt: pbrt_layered's CoatedConductorBxDF with the conductor's n, k
read by pbrt's PiecewiseLinearSpectrum from the same table (data/spectra/au-johnson-christy-1972.csv) and evaluated
at the band centres, four per run (one per wavelength lane). Per band: over the bins with f above 1% of the peak on
both sides, z = (f_g - f_p) / sqrt(se_g^2 + se_p^2), chi2/dof and its p-value, the fraction of |z| > 3; the albedo
(sum of the bins) of both with its standard error.

The chi2 of the bins is not quite chi-square distributed: each bin's se is estimated from the same paths as its value,
and where a bin holds few paths of unequal weight, a large weight raises both, so E[z^2] < 1 (chi2/dof about 0.9 at
10^6 paths, nearer 1 as the paths grow). --null measures that level: it runs each program a second time with other
seeds and gives the chi2/dof of gonio against gonio and pbrt against pbrt per band (the same statistic where the
answer is known to be "the same"), and p_cal, the p-value of gonio against pbrt with its chi2 divided by the mean of
the two null chi2/dof of that band.

Needs numpy, scipy and the OpenEXR Python module (e.g. a venv: pip install OpenEXR numpy scipy).

usage: spectral_check.py --pbrt /tmp/build-pbrt/pbrt_layered --gonio /tmp/gonio-pbrtx [--paths 2e7]
           [--pbrt-paths 2e7] [--theta-i 30] [--tau 0] [--bands all|405,455,...] [--work DIR] [--json OUT]
           [--markdown OUT] [--reuse-gonio DIR] [--null]
"""
import argparse
import json
import math
import os
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy import stats

try:
    import OpenEXR
except ImportError:
    sys.exit("spectral_check.py needs the OpenEXR Python module (pip install OpenEXR)")

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
STACK = os.path.join(REPO, "stacks", "coats", "coated-gold.toml")
TABLE = os.path.join(REPO, "data", "spectra", "au-johnson-christy-1972.csv")
# stacks/coats/coated-gold.toml in pbrt_layered's terms: coat ior 1.5, GGX alpha 0.05, no medium; gold, alpha 0.1.
PBRT_ARGS = ["--base", "conductor", "--coat-ior", "1.5", "--coat-alpha", "0.05", "--medium-albedo", "0",
             "--g", "0", "--cond-alpha", "0.1", "--cond-nk", TABLE, "--max-depth", "256", "--threads", "2"]
NTHETA, NPHI, DTHETA, DPHI = 90, 180, 1.0, 2.0


def omega():
    """projected solid angle of each bin (90 x 180), as gonio's BinGrid and pbrt_layered."""
    t = np.arange(NTHETA + 1) * math.radians(DTHETA)
    s2 = np.sin(t) ** 2
    return np.repeat((0.5 * (s2[1:] - s2[:-1]) * math.radians(DPHI))[:, None], NPHI, axis=1)


def cpu_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(cmd):
    t0, c0 = time.time(), cpu_children()
    p = subprocess.run(["nice"] + cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr}")
    return p.stdout, time.time() - t0, cpu_children() - c0


def run_gonio(gonio, paths, theta, seed, out):
    cmd = [gonio, "simulate", STACK, "--spectral", "--band-paths", "even", "--theta-i", str(theta),
           "--paths", str(int(float(paths))), "--seed", str(seed), "--quiet", "--out", out]
    _, wall, cpu = run(cmd)
    print(f"gonio: {' '.join(cmd)}  ({wall:.1f} s wall, {cpu:.1f} s CPU)", file=sys.stderr)
    return {"cmd": cmd, "wall_s": wall, "cpu_s": cpu}


def read_gonio(out, theta):
    s = json.load(open(os.path.join(out, "summary.json")))
    a = [a for a in s["angles"] if abs(a["theta_i"] - theta) < 1e-9][0]
    paths = a["paths"]
    if len(set(paths)) != 1:
        sys.exit("gonio run without --band-paths even (passes with different paths)")
    f = OpenEXR.File(os.path.join(out, "coated-gold.exr"))
    part = [p for p in f.parts if p.name() == f"theta_i={theta:g} R"][0]
    bands = {}
    for lam, refl in zip(a["spectral"]["wavelength_nm"], a["spectral"]["reflected"]):
        key = f"{lam:g}"
        F = np.asarray(part.channels[f"band.{key}"].pixels, dtype=np.float64)
        SE = np.asarray(part.channels[f"se.band.{key}"].pixels, dtype=np.float64)
        bands[float(lam)] = {"f": F, "se": SE, "reflected_summary": refl}
    return {"paths": paths[0], "bands": bands, "version": s.get("gonio_version"), "device": s.get("device"),
            "seed": s.get("seed")}


def run_pbrt(pbrt, lambdas, paths, theta, tau, seed, csv_path):
    cmd = [pbrt] + PBRT_ARGS + ["--tau", f"{tau:g}", "--theta-i", str(theta), "--paths", str(int(float(paths))),
                                "--seed", str(seed), "--lambda", ",".join(f"{l:g}" for l in lambdas),
                                "--csv", csv_path]
    out, wall, cpu = run(cmd)
    j = json.loads(out)
    print(f"pbrt: {' '.join(cmd)}  ({wall:.1f} s wall, {cpu:.1f} s CPU, {j['paths_per_second']:.3g} paths/s, "
          f"non-finite f or pdf in {j.get('nonfinite_fraction', float('nan')):.3g} of the paths)",
          file=sys.stderr)
    data = np.genfromtxt(csv_path, delimiter=",", names=True, deletechars="")
    res = {}
    for lane in j["lanes"]:
        lam = lane["lambda_nm"]
        key = [l for l in lambdas if abs(l - lam) < 1e-3][0]
        F = np.asarray(data[f"f.{key:g}"], dtype=np.float64).reshape(NTHETA, NPHI)
        SE = np.asarray(data[f"se.{key:g}"], dtype=np.float64).reshape(NTHETA, NPHI)
        res[float(key)] = {"f": F, "se": SE, "lane": lane}
    return res, {"cmd": cmd, "wall_s": wall, "cpu_s": cpu, "paths_per_second": j["paths_per_second"],
                 "no_sample_fraction": j["no_sample_fraction"],
                 "nonfinite_fraction": j.get("nonfinite_fraction")}


def albedo(F, SE, N, om):
    """sum over the bins of the bin mean, and its standard error reconstructed exactly from the per-bin se
    (both programs: se_b = sqrt((S2_b/N - m_b^2)/(N-1)) / Omega_b, one bin per path): with m_b = F_b Omega_b,
    Var(sum) = sum_b (se_b Omega_b)^2 + (sum_b m_b^2 - (sum_b m_b)^2) / (N - 1)."""
    m = F * om
    s = SE * om
    A = m.sum()
    var = (s ** 2).sum() + ((m ** 2).sum() - A * A) / (N - 1)
    return A, math.sqrt(max(var, 0.0))


def compare_band(g, p, Ng, Np, om, cut):
    Fg, Sg, Fp, Sp = g["f"], g["se"], p["f"], p["se"]
    sel = (Fg > cut * Fg.max()) & (Fp > cut * Fp.max()) & (Sg ** 2 + Sp ** 2 > 0)
    z = (Fg[sel] - Fp[sel]) / np.sqrt(Sg[sel] ** 2 + Sp[sel] ** 2)
    chi2 = float((z ** 2).sum())
    dof = int(sel.sum())
    Ag, sAg = albedo(Fg, Sg, Ng, om)
    Ap, sAp = albedo(Fp, Sp, Np, om)
    return {"bins": dof, "chi2": chi2, "chi2_dof": chi2 / dof, "p": float(stats.chi2.sf(chi2, dof)),
            "frac_z3": float((np.abs(z) > 3).mean()), "mean_z": float(z.mean()), "max_abs_z": float(np.abs(z).max()),
            "albedo_g": Ag, "albedo_g_se": sAg, "albedo_p": Ap, "albedo_p_se": sAp,
            "albedo_z": (Ag - Ap) / math.hypot(sAg, sAp), "peak_g": float(Fg.max()), "peak_p": float(Fp.max())}


def parse_arguments():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pbrt", required=True)
    ap.add_argument("--gonio", required=True)
    ap.add_argument("--paths", default="2e7", help="gonio paths per pass (--band-paths even)")
    ap.add_argument("--pbrt-paths", default="2e7", help="pbrt paths per run (4 bands per run, one per lane)")
    ap.add_argument("--theta-i", type=float, default=30)
    ap.add_argument("--tau", type=float, default=0, help="pbrt's coat thickness (0: pbrt's Tr() is exactly 1)")
    ap.add_argument("--bands", default="all", help="'all' or band centres in nm, e.g. 405,455,505")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cut", type=float, default=0.01, help="bins with f above this fraction of the peak on both")
    ap.add_argument("--work", default=None)
    ap.add_argument("--reuse-gonio", default=None, help="a gonio output DIR from an earlier run of the same command")
    ap.add_argument("--json", default=None)
    ap.add_argument("--null", action="store_true",
                    help="also run gonio (seed + 100) and pbrt (seed + 1000) again: the null chi2/dof per band")
    ap.add_argument("--markdown", default=None)
    return ap.parse_args()


def compare_bands(a, want, G, P, G2=None, P2=None):
    """Per band: gonio against pbrt bin by bin (and, with the null runs, each against itself)."""
    om = omega()
    Np = int(float(a.pbrt_paths))
    rows = []
    for w in want:
        r = compare_band(G["bands"][w], P[w], G["paths"], Np, om, a.cut)
        r["lambda_nm"] = w
        r["pbrt_n"], r["pbrt_k"] = P[w]["lane"]["n"], P[w]["lane"]["k"]
        r["gonio_reflected_summary"] = G["bands"][w]["reflected_summary"]
        r["pbrt_reflected_json"] = P[w]["lane"]["reflected"]
        if a.null:
            gg = compare_band(G["bands"][w], G2["bands"][w], G["paths"], G2["paths"], om, a.cut)
            pp = compare_band(P[w], P2[w], Np, Np, om, a.cut)
            r["null_gg"] = {k: gg[k] for k in ("bins", "chi2_dof", "frac_z3", "albedo_z")}
            r["albedo_g_null"] = gg["albedo_p"]   # the second gonio run's albedo
            r["null_pp"] = {k: pp[k] for k in ("bins", "chi2_dof", "frac_z3", "albedo_z")}
            c = 0.5 * (gg["chi2_dof"] + pp["chi2_dof"])
            r["p_cal"] = float(stats.chi2.sf(r["chi2"] / c, r["bins"]))
        rows.append(r)

    return rows


def summarise(a, rows):
    chi2 = sum(r["chi2"] for r in rows)
    dof = sum(r["bins"] for r in rows)
    ps = [r["p"] for r in rows]
    summary = {"bands": len(rows), "chi2_dof_all": chi2 / dof, "dof_all": dof,
               "p_all": float(stats.chi2.sf(chi2, dof)),
               "bands_p_below_0.01": sum(p < 0.01 for p in ps),
               "max_abs_albedo_z": max(abs(r["albedo_z"]) for r in rows),
               "albedo_z_chi2_dof": sum(r["albedo_z"] ** 2 for r in rows) / len(rows),
               "frac_z3_all": sum(r["frac_z3"] * r["bins"] for r in rows) / dof}
    if a.null:
        for k in ("null_gg", "null_pp"):
            summary[k + "_chi2_dof_all"] = (sum(r[k]["chi2_dof"] * r[k]["bins"] for r in rows) /
                                            sum(r[k]["bins"] for r in rows))
            summary[k + "_frac_z3_all"] = (sum(r[k]["frac_z3"] * r[k]["bins"] for r in rows) /
                                           sum(r[k]["bins"] for r in rows))
            summary[k + "_max_abs_albedo_z"] = max(abs(r[k]["albedo_z"]) for r in rows)
        summary["bands_p_cal_below_0.01"] = sum(r["p_cal"] < 0.01 for r in rows)
        # gonio's albedo se from its two runs: albedo() assumes one bin per path, which gonio's booking estimators
        # (a path booked in several bins, docs/PHYSICS.md) break; the pooled spread of the two runs' albedos over the
        # bands does not (sd = sqrt(mean (A1 - A2)^2 / 2))
        s_g = math.sqrt(sum((r["albedo_g"] - r["albedo_g_null"]) ** 2 for r in rows) / (2 * len(rows)))
        for r in rows:
            r["albedo_z_null_pair_se"] = (r["albedo_g"] - r["albedo_p"]) / math.hypot(s_g, r["albedo_p_se"])
        summary["gonio_albedo_se_null_pair"] = s_g
        summary["max_abs_albedo_z_null_pair_se"] = max(abs(r["albedo_z_null_pair_se"]) for r in rows)
        summary["albedo_z_null_pair_se_chi2_dof"] = sum(r["albedo_z_null_pair_se"] ** 2 for r in rows) / len(rows)

    return summary


def print_report(a, rows, summary):
    """The per-band table (returned, as markdown) and the summary lines."""
    dof = summary["dof_all"]
    hdr = ("| band (nm) | pbrt n, k | albedo gonio ± se | albedo pbrt ± se | albedo z | bins | chi2/dof | p | "
           "frac abs(z) > 3 |")
    sep = "|---:|---|---:|---:|---:|---:|---:|---:|---:|"
    if a.null:
        hdr += " null chi2/dof g-g, p-p | p_cal |"
        sep += "---|---:|"
    lines = [hdr, sep]
    for r in rows:
        line = (f"| {r['lambda_nm']:g} | {r['pbrt_n']:.4f}, {r['pbrt_k']:.4f} | "
                f"{r['albedo_g']:.5f} ± {r['albedo_g_se']:.5f} | {r['albedo_p']:.5f} ± {r['albedo_p_se']:.5f} | "
                f"{r['albedo_z']:+.2f} | {r['bins']} | {r['chi2_dof']:.3f} | {r['p']:.3f} | "
                f"{100 * r['frac_z3']:.2f}% |")
        if a.null:
            line += f" {r['null_gg']['chi2_dof']:.3f}, {r['null_pp']['chi2_dof']:.3f} | {r['p_cal']:.3f} |"
        lines.append(line)
    table = "\n".join(lines)
    print(table)
    print(f"\nall bands: chi2/dof {summary['chi2_dof_all']:.4f} over {dof} bins (p {summary['p_all']:.3g}); "
          f"|z| > 3 in {100 * summary['frac_z3_all']:.2f}% (0.27% for a normal); bands with p < 0.01: "
          f"{summary['bands_p_below_0.01']} of {len(rows)}; albedo: max |z| {summary['max_abs_albedo_z']:.2f}, "
          f"sum z^2 / bands {summary['albedo_z_chi2_dof']:.3f} (neighbouring bands share paths: not independent)")
    if a.null:
        print(f"null: chi2/dof gonio-gonio {summary['null_gg_chi2_dof_all']:.4f}, pbrt-pbrt "
              f"{summary['null_pp_chi2_dof_all']:.4f}; |z| > 3 in {100 * summary['null_gg_frac_z3_all']:.2f}%, "
              f"{100 * summary['null_pp_frac_z3_all']:.2f}%; max |albedo z| {summary['null_gg_max_abs_albedo_z']:.2f}, "
              f"{summary['null_pp_max_abs_albedo_z']:.2f}; bands with p_cal < 0.01: "
              f"{summary['bands_p_cal_below_0.01']} of {len(rows)}")
        print(f"albedo with gonio's se from its two runs ({summary['gonio_albedo_se_null_pair']:.2g}): max |z| "
              f"{summary['max_abs_albedo_z_null_pair_se']:.2f}, sum z^2 / bands "
              f"{summary['albedo_z_null_pair_se_chi2_dof']:.3f}")
    return table


def main():
    a = parse_arguments()
    work = a.work or tempfile.mkdtemp(prefix="spectral-check-")
    os.makedirs(work, exist_ok=True)
    runs = {}
    gdir = a.reuse_gonio or os.path.join(work, "gonio")
    if not a.reuse_gonio:
        runs["gonio"] = run_gonio(a.gonio, a.paths, a.theta_i, a.seed, gdir)
    G = read_gonio(gdir, a.theta_i)
    centres = sorted(G["bands"])
    want = centres if a.bands == "all" else [float(x) for x in a.bands.split(",")]
    for w in want:
        if w not in G["bands"]:
            sys.exit(f"no band centred on {w:g} nm in gonio's run ({centres[0]:g} ... {centres[-1]:g})")

    def pbrt_all(seed0, tag):
        P, infos = {}, []
        for i in range(0, len(want), 4):
            lam = want[i:i + 4]
            res, info = run_pbrt(a.pbrt, lam, a.pbrt_paths, a.theta_i, a.tau, seed0 + i // 4,
                                 os.path.join(work, f"pbrt{tag}-{i // 4}.csv"))
            P.update(res)
            infos.append(info)
        return P, infos

    P, runs["pbrt"] = pbrt_all(a.seed, "")
    G2 = P2 = None
    if a.null:
        g2 = os.path.join(work, "gonio-null")
        runs["gonio_null"] = run_gonio(a.gonio, a.paths, a.theta_i, a.seed + 100, g2)
        G2 = read_gonio(g2, a.theta_i)
        P2, runs["pbrt_null"] = pbrt_all(a.seed + 1000, "-null")
    rows = compare_bands(a, want, G, P, G2, P2)
    summary = summarise(a, rows)
    table = print_report(a, rows, summary)
    if a.markdown:
        open(a.markdown, "w").write(table + "\n")
    if a.json:
        json.dump({"summary": summary, "bands": rows, "runs": runs, "gonio_paths_per_pass": G["paths"],
                   "pbrt_paths_per_run": int(float(a.pbrt_paths)), "gonio_version": G["version"],
                   "device": G["device"], "theta_i": a.theta_i, "tau": a.tau, "cut": a.cut}, open(a.json, "w"),
                  indent=1)


if __name__ == "__main__":
    main()
