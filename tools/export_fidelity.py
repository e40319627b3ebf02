#!/usr/bin/env python3
"""How faithful an export is to the bins it came from, per tabulated incident angle.

usage: export_fidelity.py DIR [--theta-i A,B,...] [--merl] [--rgl]

DIR is a simulate output over incident angles 0 to 88 (--theta-i 0,2,...,88). Each file is written here (MERL
with gonio.table.export_merl, RGL with gonio.rgl.export_rgl) and read back by a reader of its own: the MERL cells by
the format's index functions (as BRDF Explorer's BRDFRead.cpp finds them), the RGL file by Mitsuba 3's `measured`
plugin. Its f is averaged over each bin at 3 x 3 points spread evenly in the bin's projected solid angle (the measure
the bins average f over), and compared with the bins lit above 5% of the peak (luminance): the median relative
departure beside the bins' own median relative standard error, the 90th percentile, and the directional albedo
against the energy book (largest channel). Exit 0; 2 for a run that cannot be exported.
"""
import argparse
import math
import os
import sys
import tempfile
import warnings

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import gonio  # noqa: E402
from gonio import merl  # noqa: E402
from gonio.rgl import LUMA  # noqa: E402
from gonio.table import TableError, export_merl  # noqa: E402


def merl_reader(raw):
    """f of a MERL file for pairs (wi, wo) (..., 3): the cell BRDFRead.cpp's index functions find, nan for no data."""
    def lookup(wi, wo):
        h = wi + wo
        h /= np.linalg.norm(h, axis=-1, keepdims=True)
        th, ph = np.arccos(np.clip(h[..., 2], -1, 1)), np.arctan2(h[..., 1], h[..., 0])
        c, s = np.cos(-ph), np.sin(-ph)
        d = np.stack([c * wi[..., 0] - s * wi[..., 1], s * wi[..., 0] + c * wi[..., 1], wi[..., 2]], axis=-1)
        c, s = np.cos(-th), np.sin(-th)
        d = np.stack([c * d[..., 0] + s * d[..., 2], d[..., 1], -s * d[..., 0] + c * d[..., 2]], axis=-1)
        td, pd = np.arccos(np.clip(d[..., 2], -1, 1)), np.arctan2(d[..., 1], d[..., 0])
        pd = np.where(pd < 0, pd + np.pi, pd)
        ih = np.clip(np.sqrt(th / (np.pi / 2) * 90 * 90).astype(int), 0, 89)
        idd = np.clip((td / (np.pi / 2) * 90).astype(int), 0, 89)
        ip = np.clip((pd / np.pi * 180).astype(int), 0, 179)
        return np.moveaxis(raw[:, ih, idd, ip], 0, -1)
    return lookup


def rgl_reader(path):
    import mitsuba as mi
    if not mi.variant():
        mi.set_variant("scalar_rgb")
    bsdf, ctx = mi.load_dict({"type": "measured", "filename": path}), mi.BSDFContext()

    def lookup(wi, wo):
        si = mi.SurfaceInteraction3f()
        si.wi = mi.Vector3f(*wi.reshape(-1, 3)[0])
        flat = wo.reshape(-1, 3)
        out = np.array([np.array(bsdf.eval(ctx, si, mi.Vector3f(*w))) / w[2] for w in flat])
        return out.reshape(wo.shape)
    return lookup


def report(name, run, lookup, angles):
    b = run.bins
    nodes = b.subsample(3)
    for ti in angles:
        t = math.radians(ti)
        wi = np.broadcast_to(np.array([math.sin(t), 0.0, math.cos(t)]), nodes.shape).copy()
        with np.errstate(invalid="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)   # a bin all of whose points have no data: nan
            f = np.nanmean(lookup(wi, nodes), axis=2)
        Y, se = run.f("reference", ti) @ LUMA, run.se("reference", ti) @ LUMA
        lit = Y > 0.05 * Y.max()
        dep = np.abs((f @ LUMA)[lit] / Y[lit] - 1)
        albedo = np.nansum(f * b.projected_solid_angle()[..., None], axis=(0, 1))
        book = run.albedo("reference", ti)
        print(f"{name} theta_i {ti:4g}: median departure {100 * np.nanmedian(dep):5.2f}% (the bins' median rse "
              f"{100 * np.median(se[lit] / Y[lit]):5.2f}%), 90th percentile {100 * np.nanpercentile(dep, 90):5.1f}%, "
              f"albedo {100 * np.abs(albedo / book - 1).max():5.2f}% off the energy book ({lit.sum()} bins lit)",
              flush=True)


def main():
    ap = argparse.ArgumentParser(prog="export_fidelity.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("dir")
    ap.add_argument("--theta-i", help="the tabulated angles to compare (default: all)")
    ap.add_argument("--merl", action="store_true", help="the MERL export only")
    ap.add_argument("--rgl", action="store_true", help="the RGL export only")
    a = ap.parse_args()
    try:
        run = gonio.read_run(a.dir)
        angles = sorted({k[1] for k in run.values if k[0] == "reference" and k[2] == "R"})
        if a.theta_i:
            want = [float(x) for x in a.theta_i.split(",")]
            missing = [x for x in want if x not in angles]
            if missing:
                raise TableError(f"{a.dir} has no slice at {', '.join(f'{x:g}' for x in missing)} degrees")
            angles = want
        with tempfile.TemporaryDirectory() as tmp:
            if not a.rgl:
                export_merl(run, os.path.join(tmp, "f.binary"))
                report("MERL", run, merl_reader(merl.read(os.path.join(tmp, "f.binary"))), angles)
            if not a.merl:
                from gonio import rgl
                rgl.export_rgl(run, os.path.join(tmp, "f.bsdf"))
                report("RGL ", run, rgl_reader(os.path.join(tmp, "f.bsdf")), angles)
    except (TableError, FileNotFoundError, ValueError) as e:
        print(f"export_fidelity.py: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
