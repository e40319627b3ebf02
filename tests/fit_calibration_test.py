#!/usr/bin/env python3
"""gonio fit is unbiased and its standard errors are honest, over many seeds (docs/MODELS.md, "Fitting a model").

On an index-matched smooth coat over a rough conductor (alpha 0.3) ww-corrected is the conductor's own microfacet
BRDF, so the base roughness it is fitted to is known: 0.3. For SEEDS (20) independent references (1e7 paths at each of
0, 30 and 60 degrees) `gonio fit --reference` fits layer.2.roughness from 0.2. Asserted:
  * no bias: |mean - 0.3| < 3 standard errors of the mean (the reported se's RMS over sqrt(SEEDS));
  * honest errors: the spread of the values over the RMS of the reported se in [0.7, 1.4];
  * each reported se within a factor 2 of the spread (the se one fit can be trusted to);
  * the negative control: the same fits without the bias corrections (one descent over cells that close on the
    reference's own fluctuations, the log residual uncorrected: the fit before they were added, biased by about one
    se) fail the bias test. A test that passed both would not be testing the bias.
usage: fit_calibration_test.py GONIO OUT_DIR
"""
import json
import math
import os
import subprocess
import sys

SEEDS = 20
TRUTH = 0.3
STACK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "stacks", "matched-coat-conductor.toml")

def run(*args):
    r = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: {' '.join(args)} exited {r.returncode}: {r.stderr[-2000:]}")


def fits(gonio, out, refs, corrected):
    values, ses = [], []
    for k, ref in enumerate(refs):
        fit_dir = os.path.join(out, f"fit-{'c' if corrected else 'u'}-{k}")
        args = [gonio, "fit", "--reference", ref, "--model", "ww-corrected", "--free", "layer.2.roughness",
                "--start", "layer.2.roughness=0.2", "--quiet", "--no-report", "--out", fit_dir]
        if not corrected:
            args.append("--without-bias-corrections")
        run(*args)
        p = json.load(open(os.path.join(fit_dir, "fit.json")))["parameters"]["layer.2.roughness"]
        if not p["constrained"] or p["se"] is None:
            sys.exit(f"FAIL: seed {k}: the roughness came out unconstrained: {p}")
        values.append(p["value"])
        ses.append(p["se"])
    return values, ses


def statistics(values, ses):
    n = len(values)
    mean = sum(values) / n
    spread = math.sqrt(sum((v - mean) ** 2 for v in values) / (n - 1))
    se_rms = math.sqrt(sum(s * s for s in ses) / n)
    return mean, spread, se_rms, (mean - TRUTH) / (se_rms / math.sqrt(n))


def main():
    gonio, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    stack = STACK
    refs = []
    for k in range(SEEDS):
        ref = os.path.join(out, f"ref-{k}")
        run(gonio, "simulate", stack, "--theta-i", "0,30,60", "--paths", "1e7", "--seed", str(101 + k), "--quiet",
            "--out", ref)
        refs.append(ref)
    failures, checks = [], 3 + SEEDS + 1
    values, ses = fits(gonio, out, refs, True)
    mean, spread, se_rms, bias = statistics(values, ses)
    print(f"fit over {SEEDS} seeds: mean {mean:.7f} (truth {TRUTH}), bias {bias:+.2f} se of the mean, "
          f"spread {spread:.3g}, reported se {se_rms:.3g} (RMS), spread/se {spread / se_rms:.3f}")
    if not abs(mean - TRUTH) < 0.01:
        failures.append(f"the fits do not find the roughness: mean {mean:.5f}, truth {TRUTH}")
    if not abs(bias) < 3:
        failures.append(f"biased: the mean is {bias:+.2f} standard errors of the mean from {TRUTH}")
    if not 0.7 <= spread / se_rms <= 1.4:
        failures.append(f"the reported se is not the spread: spread/se {spread / se_rms:.3f}, outside [0.7, 1.4]")
    for k, s in enumerate(ses):
        if not spread / 2 < s < 2 * spread:
            failures.append(f"seed {k}: se {s:.3g} more than a factor 2 from the spread {spread:.3g}")
    u_values, u_ses = fits(gonio, out, refs, False)
    u_mean, u_spread, u_se, u_bias = statistics(u_values, u_ses)
    print(f"negative control, without the bias corrections: mean {u_mean:.7f}, bias {u_bias:+.2f} se of the mean, "
          f"spread/se {u_spread / u_se:.3f}")
    if abs(u_bias) < 3:
        failures.append(f"the negative control passes the bias test ({u_bias:+.2f}): the test cannot see the bias")
    for f in failures:
        print("FAIL:", f)
    print(f"{checks - len(failures)} passed, {len(failures)} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
