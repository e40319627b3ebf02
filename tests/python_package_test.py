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

print(f"python package: {len(failures)} failed")
sys.exit(1 if failures else 0)
