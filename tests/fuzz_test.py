#!/usr/bin/env python3
"""Seeded fuzzing of gonio's inputs: random valid stacks (gonio random-stack), the same stacks broken in random ways,
random option sets and random sweep files, through `gonio check`, `gonio simulate` and `gonio sweep`.

Every run must exit 0 (it ran) or 2 (it was refused, saying why); never 1, a crash or a signal. A run that exits 0
must write a summary.json that holds only finite numbers (JSON has no NaN: parse_constant refuses them) whose
energy book sums to 1 per channel (to 1e-5: every path is booked once; where the Lambertian series applies its
exits are estimates, so there within the run's noise, see below), and a sweep.csv of finite numbers.

usage: fuzz_test.py path/to/gonio [seed] [cases]   (from the repository root; seed 1, 60 cases by default)
"""
import csv
import json
import math
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile


def refuse_constant(c):
    raise ValueError(f"summary.json holds {c}")


def run(cmd, timeout=300):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    return p.returncode, p.stdout + p.stderr


def break_stack(text, rng):
    """One random defect in a valid stack file, or None if the chosen defect does not apply."""
    lines = text.splitlines()
    numeric = [i for i, l in enumerate(lines) if re.match(r"^(roughness|ior|k|optical_depth|scattering_albedo|phase_g|albedo|exterior_ior) = ", l)]
    kind = rng.choice(["value", "value", "value", "delete", "unknown", "duplicate", "truncate", "kind"])
    if kind == "value" and numeric:
        i = rng.choice(numeric)
        key = lines[i].split(" = ")[0]
        bad = rng.choice(["-1", "nan", "inf", "1e10", "1e-44", "1e-30", "\"x\"", "[1, 2]", "true", "1e39", "-0.0001", "101", "0"])
        lines[i] = f"{key} = {bad}"
    elif kind == "delete" and numeric:
        del lines[rng.choice(numeric)]
    elif kind == "unknown":
        lines.insert(rng.randrange(1, len(lines) + 1), "thickness = 1")
    elif kind == "duplicate" and numeric:
        i = rng.choice(numeric)
        lines.insert(i, lines[i])
    elif kind == "truncate":
        return text[: rng.randrange(1, max(2, len(text) - 1))]
    elif kind == "kind":
        i = next((j for j, l in enumerate(lines) if l.startswith("interface = ")), None)
        if i is None:
            return None
        lines[i] = "interface = " + rng.choice(['"glass"', '"lambertian"', '"conductor"', "3"])
    else:
        return None
    return "\n".join(lines) + "\n"


def options(rng):
    """A random option set for simulate: mostly valid, sometimes not."""
    o = ["--quiet", "--seed", str(rng.randrange(1, 1000)), "--paths", rng.choice(["2e4", "5e4", "1e5"])]
    angles = rng.sample([0, 10, 30, 45, 60, 75, 80, 85, 89, 89.9], rng.randrange(1, 4))
    bad = rng.random() < 0.25
    if bad:
        choice = rng.randrange(8)
        if choice == 0: angles = [30, 30]
        elif choice == 1: angles = [90]
        elif choice == 2: o[o.index("--paths") + 1] = rng.choice(["0", "-5", "1e20", "lots", "1.5"])
        elif choice == 3: o += ["--dtheta", rng.choice(["7", "0", "-1", "0.005"])]
        elif choice == 4: o += ["--dphi", rng.choice(["7", "0", "400"])]
        elif choice == 5: o += ["--max-events", rng.choice(["0", "5000", "x"])]
        elif choice == 6: o += ["--rse", rng.choice(["0", "1", "2", "-0.1"])]
        else: o += ["--bogus"]
    o = ["--theta-i", ",".join(f"{a:g}" for a in angles)] + o
    if not bad:
        if rng.random() < 0.3: o += ["--dtheta", rng.choice(["2", "5", "10"]), "--dphi", rng.choice(["4", "10", "20"])]
        if rng.random() < 0.2: o += ["--orders"]
        if rng.random() < 0.2: o += ["--max-events", rng.choice(["1", "3", "16"])]
        if rng.random() < 0.5: o += ["--no-series"]
    return o


def check_summary(path, why):
    s = json.load(open(path), parse_constant=refuse_constant)
    series = s["walk"]["lambertian_series"]["applied"]
    for a in s["angles"]:
        for c in "RGB":
            e = a["energy"][c]
            for k, v in e.items():
                assert isinstance(v, (int, float)) and math.isfinite(v), f"{why}: {k} = {v}"
            assert e["invalid"] == 0, f"{why}: invalid paths {e}"
            # the full walk books every path exactly once; the series' exits weigh S times the trip's (up to 64):
            # there the sum is an estimate of 1 whose noise is below 64 / sqrt(paths)
            tol = 64 / math.sqrt(a["paths"]) if series else 1e-5
            assert abs(e["sum"] - 1) <= tol, f"{why}: energy sum {e['sum']} (tolerance {tol})"


def main(gonio, seed, cases):
    rng = random.Random(seed)
    tmp = tempfile.mkdtemp(prefix="gonio-fuzz-")
    counts = {"check": [0, 0], "simulate": [0, 0], "sweep": [0, 0]}   # [ran, refused]
    failures = []
    try:
        rc, text = run([gonio, "random-stack", "--seed", str(seed), "--count", str(cases), "--out", tmp + "/valid"])
        assert rc == 0, text
        valid = sorted(os.path.join(tmp, "valid", f) for f in os.listdir(tmp + "/valid"))
        # a third of the stacks get scattering media: every medium of optical depth above 0 scatters, with a random
        # single-scattering albedo (1, conservative, one time in 8) and Henyey-Greenstein g
        for v in valid:
            if rng.random() < 1 / 3:
                out = []
                for line in open(v).read().splitlines():
                    out.append(line)
                    if line.startswith("optical_depth = ") and line != "optical_depth = 0":
                        albedo = 1.0 if rng.random() < 1 / 8 else round(rng.random(), 3)
                        out += [f"scattering_albedo = {albedo}", f"phase_g = {round(rng.uniform(-0.95, 0.95), 3)}"]
                open(v, "w").write("\n".join(out) + "\n")
        for i in range(cases):
            stack = valid[i]
            if rng.random() < 0.25:   # a broken copy
                broken = break_stack(open(stack).read(), rng)
                if broken is not None:
                    stack = os.path.join(tmp, f"broken-{i}.toml")
                    open(stack, "w").write(broken)
            what = rng.choice(["check", "simulate", "simulate", "sweep"])
            out = os.path.join(tmp, f"out-{i}")
            if what == "check":
                cmd = [gonio, "check", stack]
            elif what == "simulate":
                cmd = [gonio, "simulate", stack] + options(rng) + ["--out", out]
            else:
                base = open(valid[i]).read()
                layers = base.count("[[layer]]")
                # mostly a parameter the top layer has, with valid values; sometimes none of that
                layer = 1 if rng.random() < 0.7 else rng.randrange(0, layers + 2)   # 0 and layers + 1: out of range
                key = rng.choice(["roughness", "roughness", "ior", "optical_depth", "k", "albedo", "exterior_ior", "colour",
                                  "scattering_albedo", "phase_g"])
                values = rng.choice(["[0.1, 0.5]", "[1.0, 1.2]", "[0.0, 1.0]"] if rng.random() < 0.7 else ["[-0.1]", "[1e-30]", "[1e6]"])
                sw = os.path.join(tmp, f"sweep-{i}.toml")
                vary = f'key = "{key}"\nvalues = {values}\n' if key == "exterior_ior" else f'layer = {layer}\nkey = "{key}"\nvalues = {values}\n'
                open(sw, "w").write(f'name = "fuzz-{i}"\nstack = "{os.path.abspath(stack)}"\ntheta_i = [30]\npaths = 4000\n'
                                    f'seed = {i + 1}\n\n[[vary]]\n{vary}')
                cmd = [gonio, "sweep", sw, "--quiet", "--out", out]
            rc, text = run(cmd)
            name = " ".join(os.path.basename(c) if c.startswith(tmp) else c for c in cmd)
            if rc not in (0, 2):
                failures.append(f"{name}: exit {rc}: {text[-600:]}")
                continue
            counts[what][1 if rc == 2 else 0] += 1
            if os.environ.get("FUZZ_VERBOSE"):
                print(f"{rc} {name}: {text.strip().splitlines()[-1] if text.strip() else ''}")
            try:
                if rc == 2:
                    assert text.strip(), f"{name}: refused without a word"
                elif what == "simulate":
                    check_summary(os.path.join(out, "summary.json"), name)
                elif what == "sweep":
                    with open(os.path.join(out, "sweep.csv")) as fh:
                        rows = list(csv.reader(fh))
                    assert len(rows) >= 1 and rows[0][0] == "config", f"{name}: sweep.csv has no header"
                    for row in rows[1:]:
                        for v in row:
                            if re.match(r"^-?[0-9.]+(e[-+]?[0-9]+)?$|^-?nan$|^-?inf$", v):
                                assert math.isfinite(float(v)), f"{name}: sweep.csv holds {v}"
            except (AssertionError, ValueError, OSError) as e:
                failures.append(str(e))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    for f in failures:
        print("FAIL:", f)
    print("fuzz: " + ", ".join(f"{k} {v[0]} ran / {v[1]} refused" for k, v in counts.items()))
    ran = sum(v[0] for v in counts.values())
    refused = sum(v[1] for v in counts.values())
    # the cases must exercise both outcomes, or the fuzzing tests nothing
    if ran == 0 or refused == 0:
        failures.append("every case had the same outcome")
    print(f"fuzz: {cases - len(failures)} passed, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    sys.exit(main(os.path.abspath(sys.argv[1]), int(sys.argv[2]) if len(sys.argv) > 2 else 1,
                  int(sys.argv[3]) if len(sys.argv) > 3 else 60))
