#!/usr/bin/env python3
"""tools/study_rgb_vs_spectral.py on a subset (gold, rough, clear coat, 2e4 paths): its data set holds, per reduction
and angle, the numbers of the runs' own rgb-vs-spectral.json; its first line says how to regenerate it; the figure is
written; the f0 reduction's row names what it clipped (gold's red); a second call reads the runs instead of repeating
them (the files unchanged).

usage: study_rgb_vs_spectral_test.py GONIO
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
TOOL = os.path.join(ROOT, "tools", "study_rgb_vs_spectral.py")
failures = 0


def check(ok, what):
    global failures
    print(("ok   " if ok else "FAIL ") + what)
    failures += 0 if ok else 1


def main():
    gonio = sys.argv[1]
    with tempfile.TemporaryDirectory() as tmp:
        work, data, fig = os.path.join(tmp, "work"), os.path.join(tmp, "data.csv"), os.path.join(tmp, "fig.png")
        cmd = [sys.executable, TOOL, work, data, fig, "--paths", "2e4", "--gonio", gonio, "--metals", "Au",
               "--finishes", "rough", "--coats", "clear"]
        out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
        with open(data) as fh:
            first = fh.readline()
            rows = list(csv.DictReader(fh))
        check(first.startswith("# ") and "regenerate: python3 tools/study_rgb_vs_spectral.py" in first, first.strip())
        check(len(rows) == 6, f"two reductions x three angles: {len(rows)} rows")
        for r in rows:
            with open(os.path.join(work, f"Au-rough-clear-{r['reduction']}", "rgb-vs-spectral.json")) as fh:
                j = json.load(fh)
            a = [x for x in j["angles"] if x["theta_i"] == float(r["theta_i"])][0]
            check(abs(float(r["albedo_de2000"]) - a["albedo"]["de2000"]) < 1e-3 and
                  abs(float(r["median_de2000"]) - a["de2000"]["median"]) < 1e-3,
                  f"{r['reduction']} at {r['theta_i']}: the run's albedo and median CIEDE2000")
            check(("Au red" in r["clipped"]) == (r["reduction"] == "f0"), f"{r['reduction']}: clipped '{r['clipped']}'")
        check(os.path.getsize(fig) > 1000, "the figure is written")
        check("| Au | rough | clear |" in out and "dominant: mean albedo dE00" in out, "the tables are printed")
        before = os.path.getmtime(os.path.join(work, "Au-rough-clear-f0", "rgb-vs-spectral.json"))
        subprocess.run(cmd, check=True, capture_output=True)
        check(os.path.getmtime(os.path.join(work, "Au-rough-clear-f0", "rgb-vs-spectral.json")) == before,
              "a second call reads the runs it finds")
        bad = subprocess.run(cmd[:-2] + ["--coats", "purple"], capture_output=True, text=True)
        check(bad.returncode != 0 and "unknown 'purple'" in bad.stderr, "an unknown coat is refused")
    print(f"study_rgb_vs_spectral: {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
