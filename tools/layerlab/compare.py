#!/usr/bin/env python3
"""gonio's reference walk against layerlab (Jakob, d'Eon, Jakob, Marschner 2014), bin by bin.

layerlab solves the layered BSDF deterministically (Fourier series in azimuth, Gauss-Lobatto nodes in
cos theta, adding-doubling); gonio estimates it by Monte Carlo. For each stack of STACKS this script
  1. writes the gonio TOML (Beckmann microfacets, separable Smith: layerlab's microsurface) and runs
     `gonio simulate` at the incidences asked (two seeds, half the paths each),
  2. builds the same stack in layerlab, channel by channel (Layer.setMicrofacet / setDiffuse /
     setHenyeyGreenstein + expand, addToTop), once at layerlab's own heuristic resolution (n nodes,
     m Fourier orders: parameterHeuristicMicrofacet / parameterHeuristicHG, the recipes' rule) and once
     with n and m raised by --raise (the truncation error estimate),
  3. averages layerlab's BSDF x cos over each of gonio's bins (Gauss-Legendre in sin^2 theta and phi,
     see bin_average) and compares: albedo, and per bin |gonio - layerlab| against
     max(3 se, |layerlab(n, m) - layerlab(raised)|).
See README.md. Not part of gonio's build or tests.

usage: compare.py --layerlab BUILD_DIR [--gonio /tmp/gonio-head/gonio] [--stacks a,b] [--theta-i 0,30,60,75]
                  [--paths 8e6] [--raise 1.5] [--work DIR] [--json OUT] [--markdown OUT]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time

import numpy as np

# ---- the stacks ----------------------------------------------------------------------------------------------------
# Layers top to bottom, in gonio's terms (absolute IORs, exterior 1.0). Per channel values are [R, G, B].
# layerlab's three recipes (recipes/*.py) and the seed study's plastic; the other three seed materials have a
# roughness of 0.001, which layerlab cannot resolve (README.md, "What layerlab cannot express").
AU_N = [0.2227295, 0.4277683, 1.33422]    # gonio's Au (Johnson & Christy) at 611.3, 549.1, 464.3 nm, from
AU_K = [3.2069204, 2.4615037, 1.87149]    # `gonio check stacks/coats/coated-gold.toml`
STACKS = {
    # recipes/coated-diffuse.py: Beckmann coat eta 1.5 alpha 0.02 right on a Lambertian base, albedo [0.5, 0.5, 0.6]
    "coated-diffuse": [dict(kind="dielectric", ior=1.5, alpha=0.02),
                       dict(kind="lambertian", albedo=[0.5, 0.5, 0.6])],
    # recipes/coated-gold.py: coat eta 1.5 alpha 0.1 over gold alpha 0.1 (gold's n, k: gonio's, see README)
    "coated-gold": [dict(kind="dielectric", ior=1.5, alpha=0.1),
                    dict(kind="conductor", ior=AU_N, k=AU_K, alpha=0.1)],
    # recipes/coated-gold-with-scatmedium.py: the same with an HG medium in the coat, g 0.5, tau 0.5,
    # single-scattering albedo [0.25, 0, 0.95]
    "coated-gold-scat": [dict(kind="dielectric", ior=1.5, alpha=0.1, tau=0.5, albedo=[0.25, 0.0, 0.95], g=0.5),
                         dict(kind="conductor", ior=AU_N, k=AU_K, alpha=0.1)],
    # stacks/plastic.toml (seed, Figure 1) with a Beckmann coat of the same alpha 0.05
    "plastic": [dict(kind="dielectric", ior=1.5, alpha=0.05, tau=[0.05, 0.05, 0.3]),
                dict(kind="lambertian", albedo=[0.2, 0.6, 0.3])],
}


def per_channel(v, c):
    return v[c] if isinstance(v, (list, tuple)) else v


def toml_value(v):
    return "[" + ", ".join(repr(float(x)) for x in v) + "]" if isinstance(v, (list, tuple)) else repr(float(v))


def gonio_toml(name, layers):
    """The gonio stack: every rough interface Beckmann with separable Smith shadowing (layerlab's
    microfacet model: Walter et al. 2007's Beckmann BSDF, G = G1(wi) G1(wo))."""
    out = [f'name = "{name}"', "exterior_ior = 1.0"]
    for L in layers:
        out += ["", "[[layer]]", f'interface = "{L["kind"]}"']
        if L["kind"] == "lambertian":
            out.append(f"albedo = {toml_value(L['albedo'])}")
            continue
        out += [f"roughness = {L['alpha']}", 'distribution = "beckmann"', 'shadowing = "separable"',
                f"ior = {toml_value(L['ior'])}"]
        if L["kind"] == "conductor":
            out.append(f"k = {toml_value(L['k'])}")
        for key, gkey in (("tau", "optical_depth"), ("albedo", "scattering_albedo"), ("g", "phase_g")):
            if key in L:
                out.append(f"{gkey} = {toml_value(L[key])}")
    return "\n".join(out) + "\n"


# ---- layerlab ------------------------------------------------------------------------------------------------------
def resolution(ll, layers, scale=1.0, scale_n=None):
    """(n, m): the largest of layerlab's heuristics over the stack's interfaces and media (the recipes take
    n = max over layers, m of the top layer; the max over all layers is never less), times `scale`."""
    ns, ms, n_above = [], [], 1.0
    for L in layers:
        if L["kind"] == "dielectric":
            n_, m_ = ll.parameterHeuristicMicrofacet(eta=L["ior"] / n_above, alpha=L["alpha"])
            ns.append(n_); ms.append(m_)
            if "g" in L:
                n_, m_ = ll.parameterHeuristicHG(g=L["g"])
                ns.append(n_); ms.append(m_)
            n_above = L["ior"]
        elif L["kind"] == "conductor":
            for c in range(3):
                eta = complex(L["ior"][c], L["k"][c]) / n_above
                n_, m_ = ll.parameterHeuristicMicrofacet(eta=eta, alpha=L["alpha"])
                ns.append(n_); ms.append(m_)
    n, m = int(math.ceil(max(ns) * (scale if scale_n is None else scale_n))), int(math.ceil(max(ms) * scale))
    return n + (n % 2), m


def layer_energy(layer):
    """(min, max) over the nodes of the order-0 energy a single interface layer sends out per unit arriving from
    above (reflected + transmitted: 1 minus the microfacet loss) and from below (reflected + transmitted, which in
    layerlab's radiance convention may exceed 1 slightly, but never goes negative). layerlab's Fourier projection
    of the coat's internal reflection near the critical angle breaks down at some node sets (README.md,
    "Findings": a node with energy -5.6 from below at n = 294, alpha 0.1), which this catches."""
    nodes, weights = np.asarray(layer.nodes), np.asarray(layer.weights)
    h = len(nodes) // 2
    mw = nodes[h:] * weights[h:]
    def energy(M):   # as src/layer.cpp's applySurfaceIntegrationWeights scales the columns
        return (np.asarray(M) / mw[None, :]).T @ mw
    top = energy(layer[0].reflectionTop) + energy(layer[0].transmissionTopBottom)
    bottom = energy(layer[0].reflectionBottom) + energy(layer[0].transmissionBottomTop)
    return float(min(top.min(), bottom.min())), float(max(top.max(), bottom.max()))


def broken(checks):
    """A dielectric interface sends out between 1 - (its microfacet loss, a few %) and 1 from either side (up
    to ~1.01 from below in layerlab's radiance convention at grazing nodes): anything outside [0.5, 1.1], or not
    finite, is layerlab's Fourier projection failing (seen at n = 294, 304: energies -5.6 and 0.21; n = 320: NaN)."""
    return any(not (0.5 < lo and hi < 1.1) for lo, hi in checks)


def build_layer(ll, layers, channel, n, m, memo=None, checks=None):
    """The stack in layerlab for one channel, built from the bottom up with addToTop as the recipes do. layerlab's
    interfaces are relative: a layer's eta is n_below / n_above (a conductor's (n + i k) / n_above), so the
    absolute IORs of gonio's TOML are divided by the IOR above them."""
    mu, w = ll.quad.gaussLobatto(n)
    iors = [1.0] + [L.get("ior") for L in layers]          # iors[i]: the medium above layer i
    base = ll.Layer(mu, w, m)
    last = layers[-1]
    if last["kind"] == "lambertian":
        base.setDiffuse(per_channel(last["albedo"], channel))
    elif last["kind"] == "conductor":
        n_above = iors[len(layers) - 1]
        base.setMicrofacet(eta=complex(last["ior"][channel], last["k"][channel]) / n_above, alpha=last["alpha"])
    else:
        raise ValueError("only opaque stacks (reflection side)")
    for i in range(len(layers) - 2, -1, -1):
        L = layers[i]
        tau = per_channel(L.get("tau", 0.0), channel)
        if tau > 0:   # the medium under interface i: HG (albedo 0: pure absorption, Beer-Lambert)
            med = ll.Layer(mu, w, m)
            med.setHenyeyGreenstein(albedo=per_channel(L.get("albedo", 0.0), channel), g=L.get("g", 0.0))
            med.expand(tau)
            base.addToTop(med)
        key = (i, n, m)          # an interface is the same in every channel: built once (addToTop leaves it as is)
        if memo is None or key not in memo:
            top = ll.Layer(mu, w, m)
            top.setMicrofacet(eta=L["ior"] / iors[i], alpha=L["alpha"])
            if checks is not None:
                checks.append(layer_energy(top))
            if memo is not None:
                memo[key] = top
        base.addToTop(memo[key] if memo is not None else top)
    return base


def spline_weights(nodes, x):
    """layerlab's evalSplineWeights (include/layer/spline.h, the non-uniform variant, extrapolating), vectorised:
    4 weights and an offset per x, Catmull-Rom with finite-difference derivatives. Its d0, d1 and factor are
    single precision in layerlab; doubles here (differences ~1e-7 relative)."""
    size = len(nodes)
    idx = np.clip(np.searchsorted(nodes, x, side="right") - 1, 0, size - 2)
    x0, x1 = nodes[idx], nodes[idx + 1]
    width = x1 - x0
    t = (x - x0) / width
    t2, t3 = t * t, t * t * t
    W = np.zeros((len(x), 4))
    W[:, 1] = 2 * t3 - 3 * t2 + 1
    W[:, 2] = -2 * t3 + 3 * t2
    d0, d1 = t3 - 2 * t2 + t, t3 - t2
    has_left = idx > 0
    f0 = np.where(has_left, width / (nodes[np.maximum(idx + 1, 0)] - nodes[np.maximum(idx - 1, 0)]), 0)
    W[:, 2] += np.where(has_left, d0 * f0, d0)
    W[:, 0] -= np.where(has_left, d0 * f0, 0)
    W[:, 1] -= np.where(has_left, 0, d0)
    has_right = idx + 2 < size
    f1 = np.where(has_right, width / (nodes[np.minimum(idx + 2, size - 1)] - nodes[idx]), 0)
    W[:, 3] += np.where(has_right, d1 * f1, 0)
    W[:, 1] -= np.where(has_right, d1 * f1, 0)
    W[:, 2] += np.where(has_right, 0, d1)
    W[:, 1] -= np.where(has_right, 0, d1)
    return idx - 1, W


def fourier_coeffs(layer, mu_i, mu_o):
    """C[l, k]: the coefficient of cos(l phi_d) of layerlab's Layer.eval(-mu_o[k], mu_i, phi_d) * pi (top reflection:
    layerlab's mu is the cosine of the direction of propagation with depth increasing downwards, so light arriving
    from above has mu_i > 0 and the reflected light mu < 0). Reproduces src/layer.cpp Layer::eval term by term:
    spline weights over the positive nodes, the mode's reflectionTop divided by |mu| w (2 for l = 0)."""
    nodes, weights = np.asarray(layer.nodes), np.asarray(layer.weights)
    h = len(nodes) // 2
    tail, wtail = nodes[h:], weights[h:]
    oi, Wi = spline_weights(tail, np.array([mu_i]))
    oo, Wo = spline_weights(tail, np.asarray(mu_o))
    cols = oi[0] + np.arange(4)
    keep = (cols >= 0) & (cols < h) & (Wi[0] != 0)
    cols, wi = cols[keep], Wi[0][keep]
    # the 4 x len(mu_o) gather of rows, as a sparse-free dense matrix (h x len(mu_o))
    rows = oo[:, None] + np.arange(4)[None, :]
    C = np.empty((layer.fourierOrders, len(mu_o)))
    for l in range(layer.fourierOrders):
        Rt = np.asarray(layer[l].reflectionTop)                       # h x h (rows: exit, cols: incident)
        col = Rt[:, cols] @ (wi / (tail[cols] * wtail[cols] * (2 if l == 0 else 1)))
        col = np.concatenate([col, [0.0]])                            # index h: out of range -> 0 weight
        C[l] = np.sum(Wo * col[np.where((rows >= 0) & (rows < h), rows, h)], axis=1)
    return C


def gauss_legendre_01(k):
    x, w = np.polynomial.legendre.leggauss(k)
    return (x + 1) / 2, w / 2


def bin_average(layer, theta_i_deg, n_theta=90, n_phi=180, kt=4, kp=4):
    """layerlab's BSDF averaged over each of gonio's bins: value = int_bin f cos(theta) dw / Omega. With
    s = sin^2 theta, cos(theta) dw = ds dphi / 2, so the bin value is f's plain mean over the bin in (s, phi):
    kt Gauss-Legendre nodes in s per theta bin, kp in phi per phi bin (phi bins centred on multiples of dphi).
    phi_d of layerlab = pi - phi (its phi_d = 0 is the forward, mirror direction; checked against
    layerlab.microfacet and an independent Beckmann BRDF)."""
    dth, dph = math.radians(90 / n_theta), 2 * math.pi / n_phi
    xs, ws = gauss_legendre_01(kt)
    xp, wp = gauss_legendre_01(kp)
    lo = np.sin(np.arange(n_theta) * dth) ** 2
    hi = np.sin((np.arange(n_theta) + 1) * dth) ** 2
    s = (lo[:, None] + (hi - lo)[:, None] * xs[None, :]).ravel()          # n_theta*kt
    mu_o = np.sqrt(1 - s)
    phi = ((np.arange(n_phi) - 0.5)[:, None] * dph + dph * xp[None, :]).ravel()  # centred bins
    C = fourier_coeffs(layer, math.cos(math.radians(theta_i_deg)), mu_o)   # m x (n_theta*kt)
    l = np.arange(C.shape[0])
    cosm = np.cos(np.outer(l, math.pi - phi))                              # m x (n_phi*kp)
    f = np.maximum(C.T @ cosm, 0) / math.pi                                # Layer::eval's clamp and 1/pi
    f = f.reshape(n_theta, kt, n_phi, kp)
    return np.einsum("tapb,a,b->tp", f, ws, wp)


def layerlab_slices(ll, layers, thetas, scale, scale_n, kt, kp, cache):
    """{theta_i: (3, 90, 180)} for the stack at resolution scale `scale`; cached as .npz (the layers are the
    expensive part: minutes each for the smooth coats)."""
    if os.path.exists(cache):
        z = np.load(cache)
        if all(f"t{t}" in z for t in thetas):
            return {t: z[f"t{t}"] for t in thetas}, json.loads(str(z["meta"]))
    n, m = resolution(ll, layers, scale, scale_n)
    skipped = []
    while True:   # an interface that fails layer_energy (negative energy): take n + 10 instead, and say so
        out = {t: np.zeros((3, 90, 180)) for t in thetas}
        secs, memo, checks = [], {}, []
        for c in range(3):
            t0 = time.time()
            layer = build_layer(ll, layers, c, n, m, memo, checks)
            secs.append(time.time() - t0)
            if broken(checks):
                break
            for t in thetas:
                out[t][c] = bin_average(layer, t, kt=kt, kp=kp)
            del layer
        if not broken(checks):
            break
        skipped.append(dict(n=n, energy=checks))
        if len(skipped) == 4:
            return None, dict(n=None, m=m, skipped_n=skipped)
        n += 10
    meta = dict(n=n, m=m, build_seconds=secs, kt=kt, kp=kp, interface_energy=checks, skipped_n=skipped)
    np.savez_compressed(cache, meta=json.dumps(meta), **{f"t{t}": out[t] for t in thetas})
    return out, meta


# ---- gonio ---------------------------------------------------------------------------------------------------------
def run_gonio(gonio, toml_path, thetas, paths, seed, out):
    if not os.path.exists(os.path.join(out, "summary.json")):
        cmd = ["nice", "-n", "15", gonio, "simulate", toml_path, "--theta-i", ",".join(map(str, thetas)),
               "--paths", str(int(paths)), "--seed", str(seed), "--out", out, "--quiet"]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    data = np.genfromtxt(os.path.join(out, "slices.csv"), delimiter=",", names=True, dtype=None, encoding=None)
    res = {}
    for t in thetas:
        sel = (data["theta_i"] == t) & (data["side"] == "R")
        d = data[sel]
        it = np.round(d["theta_lo"]).astype(int)
        ip = (np.round((d["phi_lo"] + d["phi_hi"]) / 2 / 2).astype(int)) % 180
        f = np.zeros((3, 90, 180)); se = np.zeros((3, 90, 180))
        for c, (a, b) in enumerate((("r", "se_r"), ("g", "se_g"), ("b", "se_b"))):
            f[c, it, ip] = d[a]; se[c, it, ip] = d[b]
        res[t] = (f, se)
    summ = json.load(open(os.path.join(out, "summary.json")))
    alb = {a["theta_i"]: [a["energy"][ch]["reflected"] for ch in "RGB"] for a in summ["angles"]}
    return res, alb, summ


def omega():
    th = np.radians(np.arange(91))
    return ((np.sin(th[1:]) ** 2 - np.sin(th[:-1]) ** 2) / 2)[:, None] * np.radians(2) * np.ones((1, 180))


def albedo_se(f, se, N, Om):
    """The albedo's standard error from the bins, as if each path booked one bin (pbrt_layered's README):
    Var = sum_b se_b^2 Omega_b^2 + (sum_b m_b^2 - (sum_b m_b)^2) / (N - 1), m_b = f_b Omega_b. gonio's booking
    estimators let a path book more than one bin (entry reflection + exit), so this is an approximation; the
    half-difference of the two seeds' albedos is printed beside it as a check."""
    m = f * Om
    return math.sqrt(max(np.sum((se * Om) ** 2) + (np.sum(m ** 2) - np.sum(m) ** 2) / (N - 1), 0.0))


def compare_stack(name, layers, args, ll):
    work = os.path.join(args.work, name)
    os.makedirs(work, exist_ok=True)
    toml_path = os.path.join(work, name + ".toml")
    with open(toml_path, "w") as fh:
        fh.write(gonio_toml(name, layers))
    thetas = args.theta_i
    # gonio: --seeds runs of paths/seeds each; the bins pooled, the albedo's se from the seeds' spread (the
    # reconstruction from the bins, albedo_se, is printed beside it: it assumes one bin per path)
    S = args.seeds
    runs = [run_gonio(args.gonio, toml_path, thetas, args.paths / S, seed, os.path.join(work, f"gonio-s{seed}"))
            for seed in range(1, S + 1)]
    # layerlab at its heuristic resolution and raised
    t0 = time.time()
    L0, meta0 = layerlab_slices(ll, layers, thetas, 1.0, 1.0, args.kt, args.kp, os.path.join(work, "layerlab-x1.npz"))
    L1, meta1 = layerlab_slices(ll, layers, thetas, args.raise_, args.raise_n, args.kt, args.kp,
                                os.path.join(work, f"layerlab-m{args.raise_}-n{args.raise_n}.npz"))
    if L1 is None:   # no sound raised resolution found: no truncation estimate (the bound is 3 se alone)
        L1 = L0
    Om = omega()
    rows = []
    N = args.paths / S
    for t in thetas:
        f = sum(r[0][t][0] for r in runs) / S
        se = np.sqrt(sum(r[0][t][1] ** 2 for r in runs)) / S
        for c, ch in enumerate("RGB"):
            alb = np.array([r[1][t][c] for r in runs])
            a_g, a_se = float(alb.mean()), float(alb.std(ddof=1) / math.sqrt(S))
            a_pair = math.sqrt(sum(albedo_se(r[0][t][0][c], r[0][t][1][c], N, Om) ** 2 for r in runs)) / S
            lab, lab_hi = L0[t][c], L1[t][c]
            a_l, a_l_hi = float(np.sum(lab * Om)), float(np.sum(lab_hi * Om))
            trunc = np.abs(lab - lab_hi)
            mask = f[c] > 0.01 * f[c].max()
            bound = np.maximum(3 * se[c], trunc)
            diff = f[c] - lab
            z = diff / np.where(se[c] > 0, se[c], np.inf)
            beyond = mask & (np.abs(diff) > bound)
            zm = np.abs(z[mask])
            iworst = np.unravel_index(np.argmax(np.where(mask, np.abs(z), -1)), z.shape)
            rows.append(dict(
                stack=name, theta_i=t, channel=ch, albedo_gonio=a_g, albedo_gonio_se=a_se, albedo_se_from_bins=a_pair,
                albedo_layerlab=a_l, albedo_layerlab_raised=a_l_hi, albedo_rel=a_l / a_g - 1,
                bins=int(mask.sum()), beyond=int(beyond.sum()), frac_beyond=float(beyond.sum() / max(mask.sum(), 1)),
                frac_z3=float(np.mean(zm > 3)), max_abs_z=float(zm.max()),
                worst_bin=[int(iworst[0]), int(iworst[1]) * 2], worst_gonio=float(f[c][iworst]),
                worst_layerlab=float(lab[iworst]), worst_se=float(se[c][iworst]), worst_trunc=float(trunc[iworst]),
                median_trunc_rel=float(np.median(trunc[mask] / np.maximum(lab[mask], 1e-30))),
                mean_z=float(np.mean(z[mask])), peak=float(f[c].max())))
    return rows, dict(stack=name, layerlab=meta0, layerlab_raised=meta1, layerlab_seconds=time.time() - t0,
                      gonio_seconds=[r[2]["seconds"] for r in runs], toml=gonio_toml(name, layers))


def markdown(rows):
    """The README's RESULTS table: one line per stack, incidence and channel."""
    out = ["| stack | theta_i | ch | albedo gonio ± se | albedo layerlab (raised) | rel | bins > 1% | beyond bound "
           "| abs(z) > 3 | max abs(z) | mean z |", "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        out.append(f"| {r['stack']} | {r['theta_i']} | {r['channel']} | {r['albedo_gonio']:.5f} ± "
                   f"{r['albedo_gonio_se']:.5f} | {r['albedo_layerlab']:.5f} ({r['albedo_layerlab_raised']:.5f}) | "
                   f"{r['albedo_rel'] * 100:+.3f}% | {r['bins']} | {r['frac_beyond'] * 100:.2f}% | "
                   f"{r['frac_z3'] * 100:.2f}% | {r['max_abs_z']:.2f} | {r['mean_z']:+.3f} |")
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--layerlab", required=True, help="folder holding layerlab.cpython-*.so")
    ap.add_argument("--gonio", default="/tmp/gonio-head/gonio")
    ap.add_argument("--stacks", default=",".join(STACKS))
    ap.add_argument("--theta-i", default="0,30,60,75", type=lambda s: [int(x) for x in s.split(",")])
    ap.add_argument("--paths", type=float, default=8e6, help="gonio paths per incidence (two seeds, half each)")
    ap.add_argument("--seeds", type=int, default=4, help="gonio runs (seeds 1..S), paths/S each")
    ap.add_argument("--raise", dest="raise_", type=float, default=1.5,
                    help="factor on layerlab's Fourier orders m for the truncation estimate")
    ap.add_argument("--raise-n", dest="raise_n", type=float, default=1.25,
                    help="factor on layerlab's zenith nodes n for the truncation estimate")
    ap.add_argument("--kt", type=int, default=4, help="Gauss-Legendre nodes per bin in sin^2 theta")
    ap.add_argument("--kp", type=int, default=4, help="Gauss-Legendre nodes per bin in phi")
    ap.add_argument("--work", default="/tmp/layerlab-compare")
    ap.add_argument("--json")
    ap.add_argument("--markdown", help="also write the results table (markdown) here")
    ap.add_argument("--from-json", help="only print the table of an earlier --json (with --markdown)")
    args = ap.parse_args()
    if args.from_json:
        table = markdown(json.load(open(args.from_json))["rows"])
        open(args.markdown, "w").write(table) if args.markdown else print(table)
        return
    sys.path.insert(0, args.layerlab)
    import layerlab as ll
    allrows, metas = [], []
    for name in args.stacks.split(","):
        rows, meta = compare_stack(name, STACKS[name], args, ll)
        allrows += rows; metas.append(meta)
        print(f"## {name}: layerlab n={meta['layerlab']['n']} m={meta['layerlab']['m']} "
              f"(raised n={meta['layerlab_raised']['n']} m={meta['layerlab_raised']['m']}; unsound n skipped: "
              f"{[k['n'] for k in meta['layerlab_raised'].get('skipped_n', [])]})", flush=True)
        for r in rows:
            print(f"{r['stack']:17s} {r['theta_i']:3d} {r['channel']}  albedo gonio {r['albedo_gonio']:.5f} "
                  f"+- {r['albedo_gonio_se']:.5f}  layerlab "
                  f"{r['albedo_layerlab']:.5f} ({r['albedo_rel']*100:+.3f}%, raised {r['albedo_layerlab_raised']:.5f})"
                  f"  bins {r['bins']:5d} beyond {r['frac_beyond']*100:5.2f}%  |z|>3 {r['frac_z3']*100:5.2f}%"
                  f"  max|z| {r['max_abs_z']:6.2f} at {r['worst_bin']} ({r['worst_gonio']:.4g} vs "
                  f"{r['worst_layerlab']:.4g}, se {r['worst_se']:.2g}, trunc {r['worst_trunc']:.2g})  mean z "
                  f"{r['mean_z']:+.3f}", flush=True)
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(dict(rows=allrows, stacks=metas, args=vars(args)), fh, indent=1)
    if args.markdown:
        with open(args.markdown, "w") as fh:
            fh.write(markdown(allrows))


if __name__ == "__main__":
    main()
