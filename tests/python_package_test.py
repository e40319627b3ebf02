#!/usr/bin/env python3
"""The Python package for gonio's files (python/gonio): bin geometry, readers, refusals.

usage: python_package_test.py [GONIO]   with GONIO, also reads a real simulate output and checks the package's
                                        albedo (f summed over the bins) against gonio's own energy book
"""
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import numpy as np  # noqa: E402

import gonio  # noqa: E402
from gonio.outputs import FormatError, SLICES_HEADER  # noqa: E402

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


# 1. geometry: every bin grid tiles the hemisphere; projected solid angles integrate cos to pi
for dt, dp in [(1, 2), (2, 2), (5, 10), (0.5, 1), (90, 180)]:
    b = gonio.Bins(dt, dp, int(round(90 / dt)), int(round(360 / dp)))
    check(abs(b.solid_angle().sum() - 2 * math.pi) < 1e-9, f"solid angles sum to 2 pi ({dt} x {dp} deg)")
    check(abs(b.projected_solid_angle().sum() - math.pi) < 1e-9, f"projected solid angles sum to pi ({dt} x {dp} deg)")
    d = b.directions()
    check(np.allclose(np.linalg.norm(d, axis=-1), 1.0), f"bin centres are unit vectors ({dt} x {dp} deg)")
b = gonio.Bins(1, 2, 90, 180)
check(b.phi_edges_deg()[0] == -1.0 and b.phi_centres_deg()[1] == 2.0, "phi bins are centred on multiples of dphi")

# 2. a slices.csv written here, read back bin for bin; refusals with file:line
with tempfile.TemporaryDirectory() as tmp:
    b = gonio.Bins(5, 10, 18, 36)
    with open(os.path.join(tmp, "summary.json"), "w") as fh:
        fh.write('{"bins": {"dtheta_deg": 5, "dphi_deg": 10, "n_theta": 18, "n_phi": 36, '
                 '"phi_bins_centred_on_multiples_of_dphi": true}, "angles": [], "x": NaN}')
    te, pe = b.theta_edges_deg(), b.phi_edges_deg()
    rng = np.random.default_rng(7)
    want = rng.random((18, 36, 6))
    with open(os.path.join(tmp, "slices.csv"), "w") as fh:
        fh.write(",".join(SLICES_HEADER) + "\n")
        for t in range(18):
            for p in range(36):
                fh.write(f"m,30,R,{te[t]},{te[t+1]},{pe[p]},{pe[p+1]}," + ",".join(repr(float(x)) for x in want[t, p]) + "\n")
    run = gonio.read_run(tmp)
    check(run.sources() == ["m"] and np.array_equal(run.f("m", 30, "R"), want[..., :3])
          and np.array_equal(run.se("m", 30), want[..., 3:]), "slices.csv read back bin for bin (row t, column p)")
    check(math.isnan(run.summary["x"]), "a non-finite number in summary.json reads as nan")
    check(abs((np.ones((18, 36)) * b.projected_solid_angle()).sum() - math.pi) < 1e-12, "f = 1 has albedo pi")
    with open(os.path.join(tmp, "slices.csv"), "w") as fh:
        fh.write("source,theta,side\n")
    try:
        gonio.read_run(tmp)
        check(False, "a wrong header is refused")
    except FormatError as e:
        check("slices.csv:1:" in str(e), f"a wrong header is refused with file:line ({e})")
    with open(os.path.join(tmp, "slices.csv"), "w") as fh:
        fh.write(",".join(SLICES_HEADER) + "\nm,30,R,0,5,-5,5,1,1,1,0,0,0\n")
    try:
        gonio.read_run(tmp)
        check(False, "a slice with missing bins is refused")
    except FormatError as e:
        check("1 bins, expected 18 x 36" in str(e), f"a slice with missing bins is refused ({e})")

# 3. a real output: the package's albedo from the bins equals gonio's energy book (its independent tally)
if len(sys.argv) > 1:
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([sys.argv[1], "simulate", os.path.join(os.path.dirname(__file__), "..", "stacks", "plastic.toml"),
                        "--theta-i", "0,60", "--paths", "2e5", "--quiet", "--out", tmp], check=True,
                       stdout=subprocess.DEVNULL)
        run = gonio.read_run(tmp)
        for a in run.summary["angles"]:
            book = np.array([a["energy"][c]["reflected"] for c in "RGB"])
            got = run.albedo("reference", a["theta_i"], "R")
            check(np.allclose(got, book, rtol=2e-6, atol=1e-9),
                  f"theta_i {a['theta_i']}: albedo from the bins {got} = the energy book's reflected {book}")
        try:
            import OpenEXR  # noqa: F401
            have_exr = True
        except ImportError:
            have_exr = False
            print("note: OpenEXR is not installed; read_exr not exercised (pip install OpenEXR)")
        if have_exr:
            parts = gonio.read_exr(os.path.join(tmp, "plastic.exr"))
            p = parts["theta_i=60 R"]
            check(np.allclose(p["R"], run.f("reference", 60)[..., 0], rtol=1e-6), "the EXR's R plane equals slices.csv's r")

# 4. a MERL export of a table over incident angles, read back by a reader written here from the format's
# description (BRDFRead.cpp's index functions), not by the package's own
def merl_lookup(raw, wi, wo):
    h = wi + wo
    h /= np.linalg.norm(h, axis=-1, keepdims=True)
    th, ph = np.arccos(np.clip(h[..., 2], -1, 1)), np.arctan2(h[..., 1], h[..., 0])
    def rot_z(v, a):
        c, s = np.cos(a), np.sin(a)
        return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1], v[..., 2]], axis=-1)
    def rot_y(v, a):
        c, s = np.cos(a), np.sin(a)
        return np.stack([c * v[..., 0] + s * v[..., 2], v[..., 1], -s * v[..., 0] + c * v[..., 2]], axis=-1)
    d = rot_y(rot_z(wi, -ph), -th)
    td, pd = np.arccos(np.clip(d[..., 2], -1, 1)), np.arctan2(d[..., 1], d[..., 0])
    ih = np.clip((np.sqrt(th / (np.pi / 2) * 90 * 90)).astype(int), 0, 89)
    idd = np.clip((td / (np.pi / 2) * 90).astype(int), 0, 89)
    pd = np.where(pd < 0, pd + np.pi, pd)
    ip = np.clip((pd / np.pi * 180).astype(int), 0, 179)
    ind = ip + 180 * (idd + 90 * ih)
    n = 90 * 90 * 180
    scale = np.array([1 / 1500, 1.15 / 1500, 1.66 / 1500])
    return np.stack([raw[ind + c * n] * scale[c] for c in range(3)], axis=-1), (ih, idd, ip)


if len(sys.argv) > 1:
    import struct
    from gonio import merl
    from gonio.table import IsotropicTable, TableError, export_merl
    with tempfile.TemporaryDirectory() as tmp:
        stack = os.path.join(os.path.dirname(__file__), "..", "stacks", "plastic.toml")
        subprocess.run([sys.argv[1], "simulate", stack, "--theta-i", ",".join(str(t) for t in range(0, 89, 4)),
                        "--paths", "4e6", "--quiet", "--out", tmp], check=True, stdout=subprocess.DEVNULL)
        run = gonio.read_run(tmp)
        path = os.path.join(tmp, "plastic.binary")
        covered = export_merl(run, path)
        with open(path, "rb") as fh:
            dims = struct.unpack("<3i", fh.read(12))
            raw = np.frombuffer(fh.read(), dtype="<f8")
        check(dims == (90, 90, 180) and raw.size == 3 * 90 * 90 * 180, f"MERL header {dims}, {raw.size} doubles")
        check(0.5 < covered < 1.0, f"MERL cells with data: {covered:.3f} (the others below the horizon: -1)")
        # cell by cell: the reader finds the value written for a cell's centre in that cell
        rng = np.random.default_rng(3)
        th, td, pd = [a.ravel() for a in merl.cell_angles()]
        pick = rng.choice(th.size, 4000, replace=False)
        wi, wo = merl.half_diff_to_directions(th[pick], td[pick], pd[pick])
        got, (ih, idd, ip) = merl_lookup(raw, wi, wo)
        idx = np.unravel_index(pick, (90, 90, 180))
        check(np.array_equal(ih, idx[0]) and np.array_equal(idd, idx[1]) and np.array_equal(ip, idx[2]),
              "the independent reader finds each written cell at its own index")
        want = IsotropicTable(run).f(wi, wo)
        have = np.isfinite(want[:, 0])
        check(np.allclose(np.where(got < 0, np.nan, got)[have], want[have], rtol=1e-12) and
              np.all(got[~have] < 0), "the reader's values = the table's, scales applied, no data negative")
        # the file's directional albedo, integrated by the reader, against the energy book
        for ti in (20.0, 44.0):
            t = np.radians(ti)
            wi1 = np.array([np.sin(t), 0.0, np.cos(t)])
            to, po = np.meshgrid(np.radians(np.arange(0.25, 90, 0.5)), np.radians(np.arange(0.25, 360, 0.5)), indexing="ij")
            wo1 = np.stack([np.sin(to) * np.cos(po), np.sin(to) * np.sin(po), np.cos(to)], axis=-1)
            f1, _ = merl_lookup(raw, np.broadcast_to(wi1, wo1.shape).copy(), wo1)
            dw = np.sin(to) * np.cos(to) * np.radians(0.5) ** 2
            alb = (np.maximum(f1, 0) * dw[..., None]).sum(axis=(0, 1))
            book = np.array([a["energy"][c]["reflected"] for a in run.summary["angles"] if a["theta_i"] == ti for c in "RGB"])
            rel = np.abs(alb / book - 1)
            check(rel.max() < 0.015, f"MERL albedo at {ti:g} deg {alb} vs the energy book {book}: {rel.max():.4f} off")
        # a table too sparse is refused with the reason
        try:
            sparse = gonio.Run(run.summary, run.bins, {k: v for k, v in run.values.items() if k[1] in (0.0, 40.0, 80.0)})
            export_merl(sparse, path)
            check(False, "a sparse table is refused")
        except TableError as e:
            check("at most 5 degrees apart" in str(e), f"a sparse table is refused ({e})")
        # the command-line tool: written, and refusals with exit 2
        tool = os.path.join(os.path.dirname(__file__), "..", "tools", "export.py")
        r = subprocess.run([sys.executable, tool, tmp, "--format", "merl", "--out", path], capture_output=True, text=True)
        check(r.returncode == 0 and "wrote" in r.stdout, f"tools/export.py writes the file (exit {r.returncode})")
        r = subprocess.run([sys.executable, tool, tmp, "--format", "merl", "--out", path, "--source", "no-such-model"],
                           capture_output=True, text=True)
        check(r.returncode == 2 and "no-such-model" in r.stderr, f"an unknown source is refused with exit 2 ({r.stderr.strip()})")

        # 5. the RGL .bsdf export, loaded by Mitsuba 3's measured plugin: its f at the bins' centres against the bins
        try:
            import mitsuba as mi
            mi.set_variant("scalar_rgb")
        except ImportError:
            mi = None
            print("note: mitsuba is not installed; the RGL export not exercised (pip install mitsuba)")
        if mi is not None:
            from gonio import rgl
            bsdf_path = os.path.join(tmp, "plastic.bsdf")
            rgl.export_rgl(run, bsdf_path)
            fields = rgl.read_tensor_file(bsdf_path)
            check(sorted(fields) == sorted(["theta_i", "phi_i", "ndf", "sigma", "vndf", "luminance", "rgb",
                                            "description", "jacobian", "gonio_se_rgb"]) and fields["rgb"].dtype == np.float32,
                  "the RGL file has the fields Mitsuba's measured plugin reads, in float32, and gonio's se")
            lit = fields["rgb"] > 1e-3 * fields["rgb"].max()
            ratio = np.median(fields["gonio_se_rgb"][lit] / fields["rgb"][lit])
            check(0 < ratio < 0.5, f"the se field is in rgb's units (median se / rgb {ratio:.3f})")
            bsdf = mi.load_dict({"type": "measured", "filename": bsdf_path})
            ctx, b = mi.BSDFContext(), run.bins
            dirs = b.directions()
            for ti in (20.0, 44.0, 60.0):
                si = mi.SurfaceInteraction3f()
                si.wi = mi.Vector3f(math.sin(math.radians(ti)), 0.0, math.cos(math.radians(ti)))
                f = np.array([[np.array(bsdf.eval(ctx, si, mi.Vector3f(*dirs[i, j]))) / dirs[i, j, 2]
                               for j in range(b.n_phi)] for i in range(b.n_theta)])
                Y, se = run.f("reference", ti) @ gonio.rgl.LUMA, run.se("reference", ti) @ gonio.rgl.LUMA
                lit = Y > 0.01 * Y.max()
                med, noise = np.median(np.abs((f @ gonio.rgl.LUMA)[lit] / Y[lit] - 1)), np.median(se[lit] / Y[lit])
                alb = (f * b.projected_solid_angle()[..., None]).sum(axis=(0, 1))
                book = run.albedo("reference", ti)
                check(med < noise + 0.03 and np.abs(alb / book - 1).max() < 0.03,
                      f"Mitsuba's f of the RGL file at {ti:g} deg: median relative error {med:.4f} (the bins' own "
                      f"median rse {noise:.4f}), albedo {alb} vs the energy book {book}")

            # 6. examples/render_in_mitsuba.py under the white furnace: a pixel is the albedo at its view angle
            sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples"))
            from render_in_mitsuba import render
            image, view, on = render(tmp, os.path.join(tmp, "render"), "furnace", size=64, spp=64)
            worst = 0.0
            for a in run.summary["angles"]:
                ring = on & (np.abs(view - a["theta_i"]) < 2)
                if a["theta_i"] > 60 or not ring.any():
                    continue
                book = np.array([a["energy"][c]["reflected"] for c in "RGB"])
                worst = max(worst, float(np.abs(image[ring].mean(axis=0) / book - 1).max()))
            check(worst < 0.03, f"Mitsuba's render of the RGL file in the white furnace: each ring of view angles "
                                f"0 to 60 deg within {100 * worst:.1f}% of the energy book's albedo there")

print(f"python package: {len(failures)} failed")
sys.exit(1 if failures else 0)
