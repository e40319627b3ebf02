#!/usr/bin/env python3
"""gonio's reference walk against pbrt-v4's LayeredBxDF driven the same way, in one run, on the
same cores, as ratios. Runs gonio and pbrt_layered alternately (A B A B ...) on each stack, then prints
paths per second, median relative standard error, seconds to a 1% median rse, their ratios, and an agreement
check (binned albedo, azimuthal rings, a few bins). See README.md.

usage: compare.py --pbrt BUILD/pbrt_layered [--gonio /path/to/gonio] [--rounds 2] [--paths 2e7]
                  [--pbrt-paths 2e7] [--stacks plastic,scatter-diffuse,scatter-conductor] [--json OUT]

A transmissive stack (transparent-slab) is compared on both sides: albedo R and T, and the bins and rings of
each side (T: theta from -z, phi of the exit direction, gonio's convention).
"""
import argparse
import csv
import json
import math
import os
import resource
import statistics
import subprocess
import sys
import tempfile


def clear_coat(name, coat_alpha, base, base_alpha):
    """A grey coat of ior 1.5 and optical depth 0.1 (no scattering) over a conductor (ior 1.45, k 2.6) or over air
    (a slab's dielectric base of ior 1.0): gonio's TOML and pbrt_layered's arguments."""
    base_keys = 'ior = 1.45\nk = 2.6\n' if base == "conductor" else 'ior = 1.0\n'
    toml = (f'name = "{name}"\nexterior_ior = 1.0\n[[layer]]\ninterface = "dielectric"\nroughness = {coat_alpha}\n'
            f'ior = 1.5\noptical_depth = 0.1\n[[layer]]\ninterface = "{base}"\nroughness = {base_alpha}\n'
            + base_keys)
    args = ["--base", base, "--coat-ior", "1.5", "--coat-alpha", str(coat_alpha), "--tau", "0.1",
            "--medium-albedo", "0", "--g", "0"]
    if base == "conductor":
        return toml, args + ["--cond-eta", "1.45", "--cond-k", "2.6", "--cond-alpha", str(base_alpha)]
    return toml, args + ["--bottom-ior", "1.0", "--bottom-alpha", str(base_alpha)]

# Each stack: gonio TOML (grey: one value for all channels, so gonio's three channels and pbrt's constant
# spectrum describe the same material) and the matching pbrt_layered arguments.
STACKS = {
    # stacks/plastic.toml's green channel: non-scattering absorbing coat over a Lambertian base.
    "plastic": ("""name = "plastic-grey"
exterior_ior = 1.0
[[layer]]
interface = "dielectric"
roughness = 0.05
ior = 1.5
optical_depth = 0.05
[[layer]]
interface = "lambertian"
albedo = 0.6
""", ["--base", "diffuse", "--coat-ior", "1.5", "--coat-alpha", "0.05", "--tau", "0.05",
      "--medium-albedo", "0", "--g", "0", "--base-albedo", "0.6"]),
    # scattering coat over a Lambertian base: pbrt's CoatedDiffuseBxDF with albedo 0.8, g 0.5, thickness 1.
    "scatter-diffuse": ("""name = "scatter-diffuse"
exterior_ior = 1.0
[[layer]]
interface = "dielectric"
roughness = 0.05
ior = 1.5
optical_depth = 1
scattering_albedo = 0.8
phase_g = 0.5
[[layer]]
interface = "lambertian"
albedo = 0.6
""", ["--base", "diffuse", "--coat-ior", "1.5", "--coat-alpha", "0.05", "--tau", "1",
      "--medium-albedo", "0.8", "--g", "0.5", "--base-albedo", "0.6"]),
    # scattering coat over a rough conductor: pbrt's CoatedConductorBxDF.
    "scatter-conductor": ("""name = "scatter-conductor"
exterior_ior = 1.0
[[layer]]
interface = "dielectric"
roughness = 0.05
ior = 1.5
optical_depth = 1
scattering_albedo = 0.8
phase_g = 0.5
[[layer]]
interface = "conductor"
roughness = 0.2
ior = 1.45
k = 2.6
""", ["--base", "conductor", "--coat-ior", "1.5", "--coat-alpha", "0.05", "--tau", "1",
      "--medium-albedo", "0.8", "--g", "0.5", "--cond-eta", "1.45", "--cond-k", "2.6",
      "--cond-alpha", "0.2"]),
    # the seed's metallic paint and frosted metal (stacks/*.toml), their green channel (k 2.6): a coat with
    # optical depth 0.1 and no scattering over a conductor, pbrt's CoatedConductorBxDF with albedo 0
    "metallic-paint": clear_coat("metallic-paint-grey", 0.001, "conductor", 0.2),
    "frosted-metal": clear_coat("frosted-metal-grey", 0.2, "conductor", 0.001),
    # the seed's transparent slab (stacks/transparent-slab.toml), its green channel (tau 0.1): a smooth top
    # (alpha 0.001) over a non-scattering slab of ior 1.5, a rough bottom (alpha 0.2) with air below. pbrt:
    # LayeredBxDF<DielectricBxDF, DielectricBxDF, false>, bottom eta = 1.0 / 1.5 (pbrt_layered takes the
    # absolute --bottom-ior and divides it by --coat-ior; see its header comment for pbrt's convention).
    "transparent-slab": clear_coat("transparent-slab-grey", 0.001, "dielectric", 0.2),
}
# the stacks with a transmission side (gonio's slices.csv and pbrt_layered's CSV have T rows)
TRANSMISSIVE = {"transparent-slab"}

# (label, extra gonio arguments); the Lambertian series only applies to the non-scattering plastic, the booking
# estimators (docs/PHYSICS.md) to the others: each is also run without.
GONIO_VARIANTS = {"plastic": [("gonio", []), ("gonio --no-series", ["--no-series"])]}
for _name in ("scatter-diffuse", "scatter-conductor", "metallic-paint", "frosted-metal", "transparent-slab"):
    GONIO_VARIANTS[_name] = [("gonio", []), ("gonio --no-branching", ["--no-branching"])]


def to_1pct(paths, rse, pps):
    n = paths * (rse / 0.01) ** 2
    return n, n / pps


def child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_gonio(gonio, toml, theta, paths, seed, out, extra):
    cmd = ["nice", gonio, "simulate", toml, "--theta-i", str(theta), "--paths", str(paths), "--seed",
           str(seed), "--out", out, "--quiet"] + extra
    c0 = child_cpu()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    cpu = child_cpu() - c0   # the whole process: Vulkan/lavapipe start-up and shader JIT included
    s = json.load(open(os.path.join(out, "summary.json")))
    a = s["angles"][0]
    return {"paths": a["paths"], "seconds": a["seconds"], "pps": a["paths_per_second"],
            "median_rse": a["relative_se"]["median"], "albedo": a["energy"]["G"]["reflected"],
            "albedo_t": a["energy"]["G"]["transmitted"], "device": s.get("device", "?"), "csv": os.path.join(out, "slices.csv"), "cpu": cpu}


def run_pbrt(pbrt, args, theta, paths, seed, max_depth, csv_path):
    cmd = ["nice", pbrt] + args + ["--theta-i", str(theta), "--paths", str(paths), "--seed", str(seed),
                                   "--max-depth", str(max_depth), "--threads", "2", "--csv", csv_path]
    c0 = child_cpu()
    d = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
    cpu = child_cpu() - c0
    return {"paths": d["paths"], "seconds": d["seconds"], "pps": d["paths_per_second"],
            "median_rse": d["median_rse"], "albedo": d["reflected"], "albedo_se": d["reflected_se"],
            "albedo_t": d.get("transmitted", 0.0), "albedo_t_se": d.get("transmitted_se", 0.0),
            "csv": csv_path, "cpu": cpu}


def read_gonio_bins(path, side="R"):
    bins = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            if r["side"] != side:
                continue
            bins[(round(float(r["theta_lo"])), round(float(r["phi_lo"])))] = (float(r["g"]), float(r["se_g"]))
    return bins


def read_pbrt_bins(path, side="R"):
    """pbrt_layered's CSV; rows without a side column (older builds) are the R side."""
    bins = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            if r.get("side", "R") != side:
                continue
            bins[(round(float(r["theta_lo"])), round(float(r["phi_lo"])))] = (float(r["f"]), float(r["se"]))
    return bins


def proj_omega(t_lo, dt=1.0, dphi=2.0):
    lo, hi = math.radians(t_lo), math.radians(t_lo + dt)
    return 0.5 * (math.sin(hi) ** 2 - math.sin(lo) ** 2) * math.radians(dphi)


def agreement(gcsv, pcsv, side="R"):
    g, p = read_gonio_bins(gcsv, side), read_pbrt_bins(pcsv, side)
    peak = max(v[0] for v in g.values())
    z, z_low = [], []   # bins above 1% of gonio's peak of this side; above 0.01% (a peaked side: its tail too)
    for k, (fg, sg) in g.items():
        fp, sp = p[k]
        if fg > 1e-4 * peak and (sg > 0 or sp > 0):
            z_low.append((fp - fg) / math.hypot(sg, sp))
            if fg > 0.01 * peak:
                z.append(z_low[-1])
    within2 = sum(1 for v in z if abs(v) < 2) / max(1, len(z))
    within2_low = sum(1 for v in z_low if abs(v) < 2) / max(1, len(z_low))
    rings = []
    for t0 in range(0, 90, 10):   # azimuthally integrated energy in 10-degree theta rings
        eg = ep = vg = vp = 0.0
        for t in range(t0, t0 + 10):
            om = proj_omega(t)
            for ph in range(-1, 359, 2):
                fg, sg = g[(t, ph)]
                fp, sp = p[(t, ph)]
                eg += fg * om; ep += fp * om
                vg += (sg * om) ** 2; vp += (sp * om) ** 2
        rings.append((t0, eg, ep, (ep - eg) / math.sqrt(vg + vp) if vg + vp > 0 else 0.0))
    picks = [(30, 179), (0, -1), (10, -1), (30, -1), (45, 89), (60, 179), (80, 179)]   # (theta_lo, phi_lo)
    few = [(k, g[k], p[k]) for k in picks]
    return {"bins": len(z), "within_2sigma": within2, "mean_z": statistics.fmean(z) if z else 0,
            "bins_low": len(z_low), "within_2sigma_low": within2_low,
            "mean_z_low": statistics.fmean(z_low) if z_low else 0,
            "rings": rings, "few": few}


def parse_arguments():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--gonio", default="/work/main/build/gonio")
    ap.add_argument("--pbrt", required=True, help="the pbrt_layered binary")
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--paths", type=float, default=2e7, help="gonio paths per run")
    ap.add_argument("--pbrt-paths", type=float, default=2e7, help="pbrt paths per run")
    ap.add_argument("--theta-i", type=float, default=30)
    ap.add_argument("--stacks", default=",".join(STACKS))
    ap.add_argument("--depths", default="256,10", help="pbrt maxDepth values")
    ap.add_argument("--work", default=None)
    ap.add_argument("--json", default=None)
    return ap.parse_args()


def run_stack(a, name, work, depths, gpaths, ppaths):
    """Both runners on one stack, alternating over the rounds: per runner, its runs."""
    toml_text, pargs = STACKS[name]
    toml = os.path.join(work, name + ".toml")
    open(toml, "w").write(toml_text)
    variants = GONIO_VARIANTS.get(name, [("gonio", [])])
    runs = {lab: [] for lab, _ in variants}
    runs.update({f"pbrt maxDepth {d}": [] for d in depths})
    fixed = {}
    for lab, extra in variants:   # gonio's fixed CPU cost (start-up, JIT): a 2^16-path run
        fixed[lab] = run_gonio(a.gonio, toml, a.theta_i, 65536, 1,
                               os.path.join(work, f"{name}-{lab.replace(' ', '_')}-small"), extra)["cpu"]
    for r in range(a.rounds):   # alternate A B A B on the same cores
        seed = r + 1
        for lab, extra in variants:
            out = os.path.join(work, f"{name}-{lab.replace(' ', '_')}-{r}")
            runs[lab].append(run_gonio(a.gonio, toml, a.theta_i, gpaths, seed, out, extra))
            print(f"{name:18s} round {r} {lab:20s} {runs[lab][-1]['pps'] / 1e6:7.3f} Mpaths/s  "
                  f"median rse {runs[lab][-1]['median_rse']:.4f}", file=sys.stderr)
        for d in depths:
            lab = f"pbrt maxDepth {d}"
            runs[lab].append(run_pbrt(a.pbrt, pargs, a.theta_i, ppaths, seed, d,
                                      os.path.join(work, f"{name}-pbrt{d}-{r}.csv")))
            print(f"{name:18s} round {r} {lab:20s} {runs[lab][-1]['pps'] / 1e6:7.3f} Mpaths/s  "
                  f"median rse {runs[lab][-1]['median_rse']:.4f}", file=sys.stderr)
    for lab, _ in variants:
        for x in runs[lab]:
            x["cpu_net"] = max(1e-9, x["cpu"] - fixed[lab])
    return runs


def run_all(a, work, depths, gpaths, ppaths):
    return {name: run_stack(a, name, work, depths, gpaths, ppaths) for name in a.stacks.split(",")}


def summarise(a, results, gpaths, ppaths):
    """The table of the runners' means over rounds, printed; per stack and runner, the summary."""
    print(f"\ntheta_i {a.theta_i}, {a.rounds} alternating rounds; gonio {gpaths:.3g} paths/run, pbrt "
          f"{ppaths:.3g} paths/run (2 threads); values: mean over rounds")
    hdr = (f"{'stack':18s} {'runner':20s} {'Mpaths/s':>9s} {'med rse':>8s} {'N to 1%':>9s} {'s to 1%':>9s} "
           f"{'albedo':>9s} {'alb T':>9s} {'cpu-s/Mp':>9s} {'net':>7s}")
    print(hdr)
    summary = {}
    for name, runs in results.items():
        summ = {}
        for lab, rs in runs.items():
            pps = statistics.fmean(x["pps"] for x in rs)
            rse = statistics.fmean(x["median_rse"] for x in rs)
            paths = rs[0]["paths"]
            n1, s1 = to_1pct(paths, rse, pps)
            alb = statistics.fmean(x["albedo"] for x in rs)
            alb_t = statistics.fmean(x.get("albedo_t", 0.0) for x in rs)
            cpu = statistics.fmean(x["cpu"] for x in rs) / (paths / 1e6)   # CPU seconds per Mpath
            net = statistics.fmean(x.get("cpu_net", x["cpu"]) for x in rs) / (paths / 1e6)
            summ[lab] = {"pps": pps, "median_rse": rse, "paths": paths, "n_1pct": n1, "s_1pct": s1,
                         "albedo": alb, "albedo_t": alb_t, "pps_rounds": [x["pps"] for x in rs], "cpu_s_per_mpath": cpu,
                         "net_cpu_s_per_mpath": net, "cpu_s_to_1pct": net * n1 / 1e6}
            alb_t_s = f"{alb_t:9.5f}" if name in TRANSMISSIVE else f"{'-':>9s}"
            print(f"{name:18s} {lab:20s} {pps / 1e6:9.3f} {rse:8.4f} {n1:9.3g} {s1:9.1f} {alb:9.5f} {alb_t_s} "
                  f"{cpu:9.3f} {net:7.3f}")
        summary[name] = summ
    return summary


def print_ratios(summary):
    print("\nratios (gonio / pbrt): paths per wall second; pbrt's wall seconds to 1% median rse / gonio's;"
          " the same two by CPU seconds (gonio's start-up subtracted), which the load of other processes"
          " disturbs less")
    for name, summ in summary.items():
        for glab in [k for k in summ if k.startswith("gonio")]:
            for plab in [k for k in summ if k.startswith("pbrt")]:
                g, p = summ[glab], summ[plab]
                print(f"{name:18s} {glab:18s} vs {plab:18s} paths/s x{g['pps'] / p['pps']:6.2f}   "
                      f"time to 1% x{p['s_1pct'] / g['s_1pct']:6.2f}   by CPU: paths x"
                      f"{p['net_cpu_s_per_mpath'] / g['net_cpu_s_per_mpath']:6.2f}  to 1% x"
                      f"{p['cpu_s_to_1pct'] / g['cpu_s_to_1pct']:6.2f}")


def print_agreement(results, summary, depths):
    print("\nagreement (round 0, gonio default vs pbrt maxDepth %d; G channel):" % depths[0])
    for name, runs in results.items():
        glab = [k for k in runs if k.startswith("gonio")][0]
        g0, p0 = runs[glab][0], runs[f"pbrt maxDepth {depths[0]}"][0]
        sides = ["R", "T"] if name in TRANSMISSIVE else ["R"]
        summary[name]["agreement"] = {}
        for side in sides:
            ag = agreement(g0["csv"], p0["csv"], side)
            key, key_se = ("albedo", "albedo_se") if side == "R" else ("albedo_t", "albedo_t_se")
            rel = (p0[key] - g0[key]) / g0[key]
            what = "albedo" if len(sides) == 1 else f"albedo {side}"
            print(f"{name}{'' if len(sides) == 1 else ' side ' + side}: {what} gonio {g0[key]:.5f}  pbrt "
                  f"{p0[key]:.5f} +- {p0[key_se]:.5f}  (pbrt/gonio - 1 = {rel * 100:+.3f}%, "
                  f"{(p0[key] - g0[key]) / p0[key_se] if p0[key_se] > 0 else 0:+.1f} pbrt se)")
            print(f"  bins above 1% of peak: {ag['bins']}, |z| < 2 in {ag['within_2sigma'] * 100:.1f}% "
                  f"(95% if equal), mean z {ag['mean_z']:+.3f}")
            if side == "R" and ag["bins"] < 100:   # a peaked side (the slab's mirror spike): its tail as well
                print(f"  bins above 0.01% of peak: {ag['bins_low']}, |z| < 2 in "
                      f"{ag['within_2sigma_low'] * 100:.1f}%, mean z {ag['mean_z_low']:+.3f}")
            print("  10-degree rings (energy gonio, pbrt, z): " + "  ".join(
                f"{t0}:{eg:.4f}/{ep:.4f}/{zz:+.1f}" for t0, eg, ep, zz in ag["rings"]))
            print("  bins (theta_lo, phi_lo): f gonio +- se | f pbrt +- se")
            for k, (fg, sg), (fp, sp) in ag["few"]:
                print(f"    {k}: {fg:.4f} +- {sg:.4f} | {fp:.4f} +- {sp:.4f}")
            entry = {"albedo_rel": rel, **{k: v for k, v in ag.items() if k != "few"}}
            if len(sides) == 1:
                summary[name]["agreement"] = entry
            else:
                summary[name]["agreement"][side] = entry


def main():
    a = parse_arguments()
    work = a.work or tempfile.mkdtemp(prefix="pbrt_layered_")
    os.makedirs(work, exist_ok=True)
    depths = [int(x) for x in a.depths.split(",")]
    gpaths, ppaths = int(a.paths), int(a.pbrt_paths)
    results = run_all(a, work, depths, gpaths, ppaths)
    summary = summarise(a, results, gpaths, ppaths)
    print_ratios(summary)
    print_agreement(results, summary, depths)
    if a.json:
        json.dump(summary, open(a.json, "w"), indent=1)


if __name__ == "__main__":
    main()
