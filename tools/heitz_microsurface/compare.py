#!/usr/bin/env python3
"""gonio's reference walk on ONE rough interface against the authors' code of Heitz, Hanika, d'Eon, Dachsbacher
2016 ("Multiple-Scattering Microfacet BSDFs with the Smith Model"), driven by heitz_microsurface. Per case it
writes a one-layer gonio stack, runs `gonio simulate` and the driver side by side (two processes, under nice), and
reports per side (R; and T for a dielectric): the albedos with their standard errors, and the bin-by-bin agreement
z = (gonio - heitz) / sqrt(se_g^2 + se_h^2) (each se^2 taken at the two programs' pooled value: agreement()) over
the bins above 1% of the side's peak: fraction with |z| > 3, max |z|, chi-square (sum of z^2) and its p-value.
See README.md.

Two modes:
  --single   the driver's order-1 paths only (--only-order 1) against gonio's single-scattering walk (its
             default, today). For a dielectric it also compares T with the driver's order-1 exits reweighted to
             gonio's transmission G2 ("T rw"; heitz_microsurface.cpp's header says why).
  (default)  the driver's full walk (or its orders <= --heitz-max-order) against gonio with MULTIPLE_KEY added to
             the interface layer (gonio's multiple-scattering microsurface, when it exists: until then gonio refuses
             the stack, exit 2, and this script says so).

usage: compare.py --heitz /tmp/build-heitz/heitz_microsurface [--gonio /tmp/gonio-head/gonio] [--single]
                  [--paths 2e6] [--heitz-paths N] [--seed 1] [--interfaces conductor,dielectric-out,dielectric-in]
                  [--distributions ggx,beckmann] [--alphas 0.3,1.0] [--thetas 0,45,75] [--work DIR] [--json OUT]
"""
import argparse
import csv
import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time

# The gonio layer key of the multiple-scattering microsurface (default mode): (key, value). If the key lands under
# another name or value, this one line is the change.
MULTIPLE_KEY = ("microfacets", "multiple")

# The interface kinds of the issue: (heitz --interface, heitz --eta, gonio's exterior_ior, the layer's keys).
# Heitz's conductor has no Fresnel (F = 1 on every facet); gonio's closest conductor inside its key ranges (ior in
# [0.01, 20], k in [0, 100]) is n = 0.01, k = 100: 1 - F = 4.0e-6 at normal incidence, at most 1.0e-4 (at 89.4
# degrees). The dielectric from outside: air (1) over glass (1.5), eta 1.5; from inside: glass over air,
# gonio's exterior_ior 1.5 and the layer's ior 1.0, Heitz's eta 1/1.5.
INTERFACES = {
    "conductor": ("conductor", 1.5, 1.0, 'interface = "conductor"\nior = 0.01\nk = 100\n'),
    "dielectric-out": ("dielectric", 1.5, 1.0, 'interface = "dielectric"\nior = 1.5\n'),
    "dielectric-in": ("dielectric", 1.0 / 1.5, 1.5, 'interface = "dielectric"\nior = 1.0\n'),
}


def stack_toml(name, interface, distribution, alpha, multiple):
    _, _, exterior, keys = INTERFACES[interface]
    extra = f'{MULTIPLE_KEY[0]} = "{MULTIPLE_KEY[1]}"\n' if multiple else ""
    return (f'name = "{name}"\nexterior_ior = {exterior}\n[[layer]]\n{keys}roughness = {alpha}\n'
            f'distribution = "{distribution}"\n{extra}')


def proj_omega(t_lo, dt=1.0, dphi=2.0):
    lo, hi = math.radians(t_lo), math.radians(t_lo + dt)
    return 0.5 * (math.sin(hi) ** 2 - math.sin(lo) ** 2) * math.radians(dphi)


def read_bins(path, side, fcol, secol):
    """{(theta_lo, phi_lo): (f, se)} of one side of a gonio slices.csv or a heitz_microsurface CSV."""
    out = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            if r["side"] == side:
                out[(round(float(r["theta_lo"])), round(float(r["phi_lo"])))] = (float(r[fcol]), float(r[secol]))
    return out


def total_se(bins, n):
    """The standard error of a side's albedo from its bins, for an estimator that books each path in one bin
    (then E[W^2] = sum over bins of S2/N): S2/N = (se Omega)^2 (N - 1) + (f Omega)^2 per bin."""
    tot = m2 = 0.0
    for (t, _), (f, se) in bins.items():
        om = proj_omega(t)
        tot += f * om
        m2 += (se * om) ** 2 * (n - 1) + (f * om) ** 2
    return math.sqrt(max(0.0, m2 - tot * tot) / (n - 1))


def chi2_sf(x, k):
    """P(chi2_k > x): scipy's if present, else the Wilson-Hilferty normal approximation (good for k > 30)."""
    try:
        from scipy.stats import chi2
        return float(chi2.sf(x, k))
    except ImportError:
        z = ((x / k) ** (1 / 3) - (1 - 2 / (9 * k))) / math.sqrt(2 / (9 * k))
        return 0.5 * math.erfc(z / math.sqrt(2))


def agreement(g, h, ng, nh):
    """Bin-by-bin z over the bins whose pooled value fm (the paths-weighted mean of g and h) is above 1% of the
    side's peak of fm. Each program's variance is taken at fm, as the null hypothesis (both estimate one value)
    has it: se^2 fm / f (at a bin's fixed weight distribution the variance is proportional to the mean), and
    fm / (N Omega) for a program with no path in the bin (its weights are <= 1). With each program's own se instead,
    a bin where one of them happened to get 0 to 2 paths of an expected 5 to 10 gets an se near 0 and a |z| of 5
    to 10 (such bins are many at grazing exits, 1% of the peak is a handful of paths there)."""
    z = []
    fm = {k: (ng * g[k][0] + nh * h[k][0]) / (ng + nh) for k in g}
    peak = max(fm.values(), default=0.0)
    for k, m in fm.items():
        if m <= 0.01 * peak:
            continue
        om = proj_omega(k[0])
        var = 0.0
        for (f, se), n in ((g[k], ng), (h[k], nh)):
            var += se * se * m / f if f > 0 else m / (n * om)
        z.append((g[k][0] - h[k][0]) / math.sqrt(var))
    if not z:
        return {"bins": 0}
    chi2 = sum(v * v for v in z)
    return {"bins": len(z), "frac_abs_z_gt_3": sum(1 for v in z if abs(v) > 3) / len(z),
            "max_abs_z": max(abs(v) for v in z), "mean_z": sum(z) / len(z), "chi2": chi2,
            "chi2_per_dof": chi2 / len(z), "p": chi2_sf(chi2, len(z))}


def run_case(a, case, work):
    """Runs gonio and heitz_microsurface on one case (at the same time); returns their outputs' paths and JSON."""
    interface, distribution, alpha, theta = case
    label = f"{interface}-{distribution}-a{alpha:g}-t{theta:g}"
    h_iface, h_eta, _, _ = INTERFACES[interface]
    toml = os.path.join(work, label + ".toml")
    with open(toml, "w") as f:
        f.write(stack_toml(label, interface, distribution, alpha, not a.single))
    gdir, hcsv = os.path.join(work, label + "-gonio"), os.path.join(work, label + "-heitz.csv")
    gcmd = ["nice", "-n", "15", a.gonio, "simulate", toml, "--theta-i", f"{theta:g}", "--paths", str(int(a.paths)),
            "--seed", str(a.seed), "--quiet", "--out", gdir]
    hcmd = ["nice", "-n", "15", a.heitz, "--interface", h_iface, "--distribution", distribution, "--alpha",
            f"{alpha:g}", "--eta", repr(h_eta), "--theta-i", f"{theta:g}", "--paths", str(int(a.heitz_paths)),
            "--seed", str(a.seed), "--csv", hcsv]
    if a.single:
        hcmd += ["--only-order", "1"]
    elif a.heitz_max_order > 0:
        hcmd += ["--max-order", str(a.heitz_max_order)]
    gp = subprocess.Popen(gcmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    hp = subprocess.Popen(hcmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    hout, herr = hp.communicate()
    _, gerr = gp.communicate()
    if gp.returncode != 0:
        msg = f"gonio exited {gp.returncode} on {toml}: {gerr.strip()}"
        if gp.returncode == 2 and not a.single:
            msg += (f"\n(default mode needs gonio's `{MULTIPLE_KEY[0]} = \"{MULTIPLE_KEY[1]}\"` layer key; "
                    "this gonio refuses it. --single runs today.)")
        sys.exit(msg)
    if hp.returncode != 0:
        sys.exit(f"heitz_microsurface exited {hp.returncode}: {herr.strip()}")
    return label, gdir, hcsv, json.loads(hout), " ".join(gcmd[3:]), " ".join(hcmd[3:])


def compare_case(a, case, work):
    interface = case[0]
    label, gdir, hcsv, hj, gcmd, hcmd = run_case(a, case, work)
    summ = json.load(open(os.path.join(gdir, "summary.json")))
    ang = summ["angles"][0]
    ng, nh = ang["paths"], hj["paths"]
    walk = summ.get("walk", {})
    one_exit = not walk.get("entry_branch", False) and not walk.get("exit_estimates", 0)
    res = {"case": label, "interface": interface, "distribution": case[1], "alpha": case[2], "theta_i": case[3],
           "gonio_command": gcmd, "heitz_command": hcmd, "gonio_paths": ng, "heitz_paths": nh,
           "gonio_seconds": ang["seconds"], "heitz_seconds": hj["seconds"], "gonio_walk": walk,
           "gonio_albedo_se_exact": one_exit, "gonio_energy": ang["energy"]["G"], "heitz": hj, "sides": {}}
    sides = [("R", "f", "se", "reflected")]
    if interface != "conductor":
        sides.append(("T", "f", "se", "transmitted"))
        if a.single:
            sides.append(("T rw", "f_rw", "se_rw", "transmitted_rw"))
    for side, fcol, secol, key in sides:
        s = side.split()[0]
        g = read_bins(os.path.join(gdir, "slices.csv"), s, "g", "se_g")
        h = read_bins(hcsv, s, fcol, secol)
        alb_g = ang["energy"]["G"]["reflected" if s == "R" else "transmitted"]
        se_g = total_se(g, ng)
        alb_h, se_h = hj[key], hj[key + "_se"]
        ag = agreement(g, h, ng, nh)
        ag.update({"albedo_gonio": alb_g, "albedo_gonio_se": se_g, "albedo_heitz": alb_h, "albedo_heitz_se": se_h,
                   "albedo_z": (alb_g - alb_h) / math.hypot(se_g, se_h) if se_g or se_h else 0.0})
        res["sides"][side] = ag
    return res


def print_row(r):
    for side, s in r["sides"].items():
        if s["bins"] == 0:   # nothing above 1% of a peak of 0: both sides empty (or one program's only)
            print(f"{r['case']:34s} {side:4s} {s['albedo_gonio']:.5f}+-{s['albedo_gonio_se']:.5f} "
                  f"{s['albedo_heitz']:.5f}+-{s['albedo_heitz_se']:.5f} {s['albedo_z']:+6.2f}      0 (no bins)")
            continue
        flag = "ok" if s["p"] >= 1e-3 and abs(s["albedo_z"]) < 4 else "DIFF"
        print(f"{r['case']:34s} {side:4s} {s['albedo_gonio']:.5f}+-{s['albedo_gonio_se']:.5f} "
              f"{s['albedo_heitz']:.5f}+-{s['albedo_heitz_se']:.5f} {s['albedo_z']:+6.2f} {s['bins']:6d} "
              f"{100 * s['frac_abs_z_gt_3']:6.2f}% {s['max_abs_z']:6.2f} {s['mean_z']:+6.3f} "
              f"{s['chi2_per_dof']:6.3f} {s['p']:8.2e} {flag}", flush=True)


def parse_arguments():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--heitz", required=True, help="the heitz_microsurface binary")
    ap.add_argument("--gonio", default="/tmp/gonio-head/gonio")
    ap.add_argument("--single", action="store_true", help="order 1 against gonio's single-scattering walk")
    ap.add_argument("--paths", type=float, default=2e6, help="gonio paths per case")
    ap.add_argument("--heitz-paths", type=float, default=None, help="heitz paths per case (default: --paths)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--heitz-max-order", type=int, default=0,
                    help="default mode: bin only the driver's paths of order <= K (0: all, the full walk)")
    ap.add_argument("--interfaces", default=",".join(INTERFACES))
    ap.add_argument("--distributions", default="ggx,beckmann")
    ap.add_argument("--alphas", default="0.3,1.0")
    ap.add_argument("--thetas", default="0,45,75")
    ap.add_argument("--work", default=None, help="folder for the stacks and outputs (default: a new temp folder)")
    ap.add_argument("--json", default=None, help="write every case's results here")
    a = ap.parse_args()
    a.heitz_paths = a.heitz_paths or a.paths
    return a


def machine():
    model = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
    return {"cpu": model, "cpus": os.cpu_count(), "loadavg": open("/proc/loadavg").read().split()[:3],
            "python": platform.python_version()}


def main():
    a = parse_arguments()
    work = a.work or tempfile.mkdtemp(prefix="heitz_microsurface_")
    os.makedirs(work, exist_ok=True)
    cases = [(i, d, float(al), float(t)) for i in a.interfaces.split(",") for d in a.distributions.split(",")
             for al in a.alphas.split(",") for t in a.thetas.split(",")]
    mode = "single (heitz order 1 vs gonio's single scattering)" if a.single else \
        f"multiple (heitz full walk vs gonio {MULTIPLE_KEY[0]} = \"{MULTIPLE_KEY[1]}\")"
    print(f"mode: {mode}; gonio {a.paths:.3g} paths, heitz {a.heitz_paths:.3g} paths per case, seed {a.seed}; "
          f"work {work}")
    print(f"{'case':34s} side albedo gonio +- se  heitz +- se      z   bins  |z|>3  max|z| mean z chi2/dof        p")
    start, m0 = time.time(), machine()
    results = []
    for case in cases:
        r = compare_case(a, case, work)
        print_row(r)
        results.append(r)
    out = {"mode": "single" if a.single else "multiple", "paths": a.paths, "heitz_paths": a.heitz_paths,
           "seed": a.seed, "gonio": a.gonio, "heitz": a.heitz, "wall_seconds": time.time() - start,
           "machine_before": m0, "machine_after": machine(), "cases": results}
    print(f"{len(results)} cases in {out['wall_seconds']:.0f} s; load average before {m0['loadavg']}, after "
          f"{out['machine_after']['loadavg']}")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
