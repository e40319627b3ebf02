#!/usr/bin/env python3
"""Mitsuba 3's `roughplastic` BSDF, scored by gonio through files (gonio nodes / gonio score).

    gonio simulate stacks/plastic.toml --theta-i 0,30,60,80 --paths 2e6 --out out/ref
    gonio nodes stacks/plastic.toml --theta-i 0,30,60,80 --out out/nodes
    python3 examples/mitsuba_roughplastic.py out/nodes out/nodes/roughplastic.npy --coat-absorption fold
    gonio score out/nodes --values out/nodes/roughplastic.npy --id mitsuba-roughplastic --reference out/ref --out out/rp

or all four steps at once: `mitsuba_roughplastic.py --gonio build/gonio STACK --coat-absorption fold --out out/rp`
(--theta-i 0,30,60,80 --paths 2e6 --dtheta 1 --dphi 2 by default; the reference in out/rp/ref, the nodes in
out/rp/nodes, the score in out/rp/score).
Needs `pip install mitsuba` (the scalar_rgb variant) and numpy.

The mapping from the stack (nodes.json holds it), both with gonio's conventions checked against Mitsuba's source
(src/bsdfs/roughplastic.cpp, include/mitsuba/render/microfacet.h):
- two layers, a rough dielectric coat over a Lambertian base; anything else is refused with the reason;
- `roughness` -> `alpha`, `distribution` ggx: both are the GGX alpha of D(m) = 1 / (pi a^2 (m_x^2/a^2 + m_y^2/a^2 +
  m_z^2)^2) (docs/PHYSICS.md, Interfaces; stacks/README.md: "roughness is the GGX alpha");
- `ior` -> `int_ior`, `exterior_ior` -> `ext_ior` (one number each: roughplastic's eta is not per channel);
- `albedo` -> `diffuse_reflectance`, with `nonlinear` true: the diffuse term is rho / (1 - rho r_i) (r_i the
  coat's internal diffuse reflectance), the sum over the trips between base and coat that gonio's reference
  traces; nonlinear false divides by 1 - r_i for every colour (--linear, to see what that costs);
- the coat's absorption (`optical_depth`) has no parameter in roughplastic: refused unless --coat-absorption
  fold (rho e^(-2 tau) as diffuse_reflectance: the two crossings at normal incidence, see coat_transmittance) or
  ignore.
Mitsuba's eval(ctx, si, wo) returns f(si.wi, wo) times cos(theta_o) of wo, directions local (z the normal) and
pointing away from the surface, as gonio's. Radiance transport puts the viewer at si.wi and the light at wo, so
si.wi = v, wo = l and f = eval / l.z (roughplastic is symmetric in wi and wo apart from that cosine).
What gonio finds on plastic.toml: docs/MODELS.md, "Mitsuba 3's roughplastic on the plastic stack".
"""
import argparse
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import gonio  # noqa: E402  (python/gonio: gonio's files as arrays)

MODEL_ID = "mitsuba-roughplastic"


class CannotRepresent(ValueError):
    """A stack roughplastic has no parameters for: the message says which key and why."""


def rgb(x):
    """A stack value, a number or [r, g, b], as three floats."""
    return np.broadcast_to(np.asarray(x, dtype=np.float64), (3,)).copy()


def single_number(x, key):
    """roughplastic's eta and alpha are one number: refuse a value that differs between channels."""
    v = rgb(x)
    if not np.all(v == v[0]):
        raise CannotRepresent(f"{key} = {v.tolist()} differs between channels; roughplastic takes one number")
    return float(v[0])


def coat_transmittance(tau):
    """The fold of the coat's absorption into the base's albedo: e^(-2 tau), light crossing the coat of normal
    optical depth tau down and up at normal incidence (stacks/README.md: e^(-tau / cos theta) per crossing). The
    light that leaves crosses at internal angles up to the critical one (cos 0.745 at index 1.5), so this absorbs
    too little away from the normal, and too little for the inter-reflected light, which runs at grazing angles."""
    return np.exp(-2.0 * tau)


def roughplastic_params(stack, coat_absorption="refuse", nonlinear=True):
    """The roughplastic dict (Mitsuba's load_dict) for a gonio stack, or CannotRepresent."""
    layers = stack.get("layer", [])
    kinds = [y.get("interface") for y in layers]
    if kinds != ["dielectric", "lambertian"]:
        raise CannotRepresent(f"layers {kinds}: roughplastic is one rough dielectric coat over a Lambertian base")
    coat, base = layers
    alpha = single_number(coat.get("roughness", 0.0), "roughness")
    if alpha <= 0.0:
        raise CannotRepresent("roughness 0 (a smooth coat): roughplastic needs alpha > 0 (Mitsuba's plastic is the "
                              "smooth one)")
    if np.any(rgb(coat.get("scattering_albedo", 0.0)) != 0.0):
        raise CannotRepresent("the coat scatters (scattering_albedo): roughplastic's coat is a bare interface")
    tau = rgb(coat.get("optical_depth", 0.0))
    albedo = rgb(base["albedo"])
    if np.any(tau != 0.0):
        if coat_absorption == "refuse":
            raise CannotRepresent(f"the coat absorbs (optical_depth {tau.tolist()}): roughplastic has no absorbing coat; "
                                  "--coat-absorption fold puts e^(-2 tau) into the albedo, ignore drops it")
        if coat_absorption == "fold":
            albedo = albedo * coat_transmittance(tau)
    return {"type": "roughplastic", "distribution": "ggx", "alpha": alpha,
            "int_ior": single_number(coat["ior"], "ior"), "ext_ior": float(stack.get("exterior_ior", 1.0)),
            "diffuse_reflectance": {"type": "rgb", "value": [float(a) for a in albedo]}, "nonlinear": nonlinear}


def roughplastic_f(params, l, v):
    """(n, 3) f of roughplastic at the nodes, 1/sr, cosine excluded; 0 where l or v is below the surface."""
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    bsdf, ctx = mi.load_dict(params), mi.BSDFContext()
    si = mi.SurfaceInteraction3f()
    f = np.zeros((len(l), 3))
    above = np.flatnonzero((l[:, 2] > 0.0) & (v[:, 2] > 0.0))
    for i, vi, li in zip(above, v[above].tolist(), l[above].tolist()):   # lists: no numpy scalar per call
        si.wi = mi.Vector3f(vi)   # the viewer at si.wi, the light at wo: eval = f cos(theta of wo)
        f[i] = bsdf.eval(ctx, si, mi.Vector3f(li))
    f[above] /= l[above, 2:3]
    return f


def write_roughplastic_values(nodes_dir, values_path, coat_absorption="refuse", nonlinear=True):
    """Read the nodes, evaluate roughplastic with the stack's parameters, write the values; the params back."""
    nodes = gonio.read_nodes(nodes_dir)
    params = roughplastic_params(nodes.stack(), coat_absorption, nonlinear)
    gonio.write_values(values_path, roughplastic_f(params, nodes.l, nodes.v), nodes)
    return params


def run_gonio(gonio_bin, *args):
    """One gonio command; its output printed; stops on failure with gonio's exit status."""
    r = subprocess.run([gonio_bin, *args], capture_output=True, text=True)
    sys.stdout.write(r.stdout)
    if r.returncode != 0:
        sys.stderr.write(r.stderr)
        sys.exit(r.returncode)
    return r.stdout


def pipeline(gonio_bin, stack, out, coat_absorption="refuse", nonlinear=True, theta_i="0,30,60,80", paths="2e6",
             bins=("1", "2"), report=False):
    """simulate (out/ref), nodes (out/nodes), roughplastic's values, score (out/score) on bins (dtheta, dphi in
    degrees); the score directory."""
    grid = ["--theta-i", theta_i, "--dtheta", bins[0], "--dphi", bins[1]]
    run_gonio(gonio_bin, "simulate", stack, *grid, "--paths", paths, "--quiet", "--out", f"{out}/ref")
    run_gonio(gonio_bin, "nodes", stack, *grid, "--out", f"{out}/nodes")
    values = f"{out}/nodes/roughplastic.npy"
    print("roughplastic:", write_roughplastic_values(f"{out}/nodes", values, coat_absorption, nonlinear))
    run_gonio(gonio_bin, "score", f"{out}/nodes", "--values", values, "--id", MODEL_ID, "--reference", f"{out}/ref",
              "--out", f"{out}/score", *([] if report else ["--no-report"]))
    return f"{out}/score"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("inputs", nargs="+", help="NODES_DIR VALUES(.npy|.csv), or with --gonio: STACK.toml")
    ap.add_argument("--coat-absorption", choices=["refuse", "fold", "ignore"], default="refuse")
    ap.add_argument("--linear", action="store_true", help="roughplastic's nonlinear false (see above)")
    ap.add_argument("--gonio", help="the gonio binary: run simulate, nodes, this model and score")
    ap.add_argument("--theta-i", default="0,30,60,80")
    ap.add_argument("--paths", default="2e6")
    ap.add_argument("--dtheta", default="1")
    ap.add_argument("--dphi", default="2")
    ap.add_argument("--out", help="with --gonio: the output directory")
    ap.add_argument("--report", action="store_true", help="with --gonio: score writes the figures and report.html")
    a = ap.parse_args()
    try:
        if a.gonio:
            if len(a.inputs) != 1 or not a.out:
                ap.error("with --gonio: one STACK.toml and --out DIR")
            pipeline(a.gonio, a.inputs[0], a.out, a.coat_absorption, not a.linear, a.theta_i, a.paths,
                     (a.dtheta, a.dphi), a.report)
        else:
            if len(a.inputs) != 2:
                ap.error("NODES_DIR VALUES.npy (or VALUES.csv)")
            print("roughplastic:", write_roughplastic_values(*a.inputs, a.coat_absorption, not a.linear))
    except CannotRepresent as e:
        print(f"mitsuba_roughplastic.py: roughplastic cannot represent this stack: {e}", file=sys.stderr)
        sys.exit(2)


if __name__ == "__main__":
    main()
