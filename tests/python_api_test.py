#!/usr/bin/env python3
"""gonio's in-process Python API (python/gonio/api.py over gonio._core) against the command line and against what
is known: the same bytes for one seed, a NumPy model scored as `gonio score` scores its values, a fit recovering a
known parameter, refusals raised as Python exceptions, memory flat over many runs, Ctrl-C.

usage: python_api_test.py GONIO BUILD_DIR   (BUILD_DIR/python holds gonio/_core; run from the repository's root)
"""
import json
import os
import re
import resource
import signal
import subprocess
import sys
import tempfile
import threading
import time

GONIO, BUILD = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
sys.path[:0] = [os.path.join(ROOT, "python"), os.path.join(BUILD, "python")]
import numpy as np  # noqa: E402

import gonio  # noqa: E402

failures = []
TIMING = re.compile(r"(seconds|paths_per_second|ns_per_evaluation|cost_at_equal|^device$|^driver|^host$|^date)")


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def untimed(o):
    """summary.json without what measures time or names the machine (tools/snapshot_outputs.sh's rule)."""
    if isinstance(o, dict):
        return {k: untimed(v) for k, v in o.items() if not TIMING.search(k)}
    if isinstance(o, list):
        return [untimed(v) for v in o]
    return o


def cli(*args):
    r = subprocess.run([GONIO, *args], cwd=ROOT, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stderr)
    return r


def read(path):
    with open(path) as fh:
        return fh.read()


tmp = tempfile.mkdtemp(prefix="gonio-api-")
PLASTIC = "stacks/plastic.toml"
OPTS = dict(theta_i=[0, 45], paths=200000, dtheta=5, dphi=10, seed=3)
CLI_OPTS = ["--theta-i", "0,45", "--paths", "2e5", "--dtheta", "5", "--dphi", "10", "--seed", "3", "--quiet"]
os.chdir(ROOT)

# 1. simulate: the API's run is the command line's, byte for byte (slices.csv, summary.json but its timings)
stack = gonio.Stack.from_toml(PLASTIC)
run = gonio.simulate(stack, progress=False, **OPTS)
check(cli("simulate", PLASTIC, *CLI_OPTS, "--out", f"{tmp}/cli-sim").returncode == 0, "gonio simulate ran")
check(run.core.slices_csv() == read(f"{tmp}/cli-sim/slices.csv"), "simulate: slices.csv's bytes are the CLI's")
api_summary = json.loads(run.core.summary_json())
check(untimed(api_summary) == untimed(json.load(open(f"{tmp}/cli-sim/summary.json"))),
      "simulate: summary.json is the CLI's (timings aside)")
ref = gonio.read_run(f"{tmp}/cli-sim")
check(all(np.array_equal(run.values[k], ref.values[k]) for k in ref.values) and run.keys() == ref.keys(),
      "simulate: the Run's arrays are read_run's of the CLI's files")
run.save(f"{tmp}/api-sim")
check(read(f"{tmp}/api-sim/slices.csv") == read(f"{tmp}/cli-sim/slices.csv"), "run.save writes the CLI's slices.csv")
check(gonio.simulate(PLASTIC, progress=False, **OPTS).core.slices_csv() == run.core.slices_csv(),
      "a stack file's path runs as the Stack read from it")

# spectral: simulate --spectral's summary.json and EXR, in memory
check(cli("simulate", PLASTIC, "--spectral", "--bands", "40", "--theta-i", "30", "--paths", "1e5", "--dtheta", "10",
          "--dphi", "20", "--quiet", "--out", f"{tmp}/cli-spectral").returncode == 0, "gonio simulate --spectral ran")
spec = gonio.simulate(stack, spectral=True, bands=40, theta_i=[30], paths=1e5, dtheta=10, dphi=20)
cli_spec = json.load(open(f"{tmp}/cli-spectral/summary.json"))
check(untimed(spec.summary) == untimed(cli_spec), "spectral: summary.json is the CLI's (timings aside)")
try:
    exr = gonio.read_exr(f"{tmp}/cli-spectral/plastic.exr")
    same = all(np.array_equal(spec.parts[p][c], exr[p][c]) for p in exr for c in exr[p] if c != "header")
    check(same and set(exr) == set(spec.parts)
          and set(spec.parts["theta_i=30 R"]["header"]) == set(exr["theta_i=30 R"]["header"]),
          "spectral: every part and channel is the CLI's EXR's, bit for bit, and its header attributes")
except ImportError:
    print("note: OpenEXR is not installed; the spectral EXR not compared (pip install OpenEXR)")
check(spec.xyz(30).shape == (9, 18, 3) and spec.bands(30).shape == (9, 18, 10) and len(spec.wavelength_nm) == 10,
      "spectral: a SpectralRun of 10 bands of 40 nm")

# 2. compare: the models' metrics and verdicts as gonio compare's, on the same reference
MODELS = "ww-corrected,openpbr"
cmp = gonio.compare(stack, models=MODELS.split(","), progress=False, **OPTS)
check(cli("compare", PLASTIC, *CLI_OPTS, "--models", MODELS, "--no-report", "--out", f"{tmp}/cli-cmp").returncode == 0,
      "gonio compare ran")
cli_cmp = json.load(open(f"{tmp}/cli-cmp/summary.json"))
check(untimed(json.loads(cmp.core.summary_json())) == untimed(cli_cmp),
      "compare: summary.json's metrics and verdicts are the CLI's (timings aside)")
check(cmp.core.slices_csv() == read(f"{tmp}/cli-cmp/slices.csv"), "compare: slices.csv's bytes are the CLI's")
on_run = gonio.compare(stack, run, models=MODELS.split(","))
check(on_run.core.slices_csv() == cmp.core.slices_csv(), "compare on a run made before: the same bytes")
one = gonio.evaluate("ww-corrected", run)
check(np.array_equal(one.f("ww-corrected", 45), cmp.f("ww-corrected", 45)), "evaluate: one model's bins as compare's")


# 3. a NumPy model: in-process, the bytes of gonio nodes + gonio score through files
def lambert_under_fresnel(l, v, params):
    """examples/python_model.py's model, as f(l, v, params)."""
    eta, albedo = params["eta"], np.asarray(params["albedo"])

    def fresnel(c):
        s2 = (1 - c * c) / (eta * eta)
        ct = np.sqrt(np.maximum(1 - s2, 0))
        rs, rp = (c - eta * ct) / (c + eta * ct), (eta * c - ct) / (eta * c + ct)
        return 0.5 * (rs * rs + rp * rp)
    lit = v[:, 2] > 0
    t = (1 - fresnel(l[:, 2])) * (1 - fresnel(np.where(lit, v[:, 2], 1.0)))
    return np.where(lit[:, None], albedo[None, :] / np.pi * t[:, None], 0.0)


model = gonio.Model(lambert_under_fresnel, id="lambert-under-fresnel", params={"eta": 1.5, "albedo": [0.2, 0.6, 0.3]})
mine = gonio.compare(stack, run, models=[model])
nodes = gonio.run_nodes(run)
check(cli("nodes", PLASTIC, "--theta-i", "0,45", "--dtheta", "5", "--dphi", "10", "--out", f"{tmp}/nodes").returncode == 0,
      "gonio nodes ran")
file_nodes = gonio.read_nodes(f"{tmp}/nodes")
check(np.array_equal(nodes.l, file_nodes.l) and np.array_equal(nodes.v, file_nodes.v)
      and np.array_equal(nodes.weight, file_nodes.weight), "run_nodes: gonio nodes' nodes, bit for bit")
np.save(f"{tmp}/values.npy", model.values(file_nodes))
check(cli("score", f"{tmp}/nodes", "--values", f"{tmp}/values.npy", "--id", "lambert-under-fresnel", "--reference",
          f"{tmp}/cli-sim", "--out", f"{tmp}/score", "--no-report").returncode == 0, "gonio score ran")
check(mine.core.slices_csv() == read(f"{tmp}/score/slices.csv"), "a NumPy model: slices.csv's bytes are gonio score's")
scored = untimed(json.loads(mine.core.summary_json()))["models"]
by_score = untimed(json.load(open(f"{tmp}/score/summary.json")))["models"]
for m in scored + by_score:   # the file the values came from
    m.pop("file", None)
check(scored == by_score, "a NumPy model: its metrics and verdicts are gonio score's")

# a NumPy port of ww-corrected (examples/numpy_ww_corrected.py) scores as the built-in does, on a coat rough enough
# for 8 x 8 nodes a bin to integrate its lobe
sys.path.insert(0, os.path.join(ROOT, "examples"))
from numpy_ww_corrected import params_of, ww_corrected  # noqa: E402
coat = gonio.Stack({"name": "rough-coat", "layer": [
    {"interface": "dielectric", "ior": 1.5, "roughness": 0.3, "optical_depth": [0.1, 0.2, 0.3]},
    {"interface": "lambertian", "albedo": [0.5, 0.3, 0.2]}]})
coat_run = gonio.simulate(coat, theta_i=[0, 30, 60], paths=1e6, dtheta=5, dphi=10, seed=2, progress=False)
ported = gonio.compare(coat, coat_run, models=["ww-corrected", gonio.Model(ww_corrected, "ww-numpy", params_of(coat), k=8)])
by_id = {m["id"]: m for m in ported.summary["models"] if m.get("scored")}
for a_builtin, a_numpy in zip(by_id["ww-corrected"]["angles"], by_id["ww-numpy"]["angles"]):
    rb, rn = a_builtin["rmse_remapped"], a_numpy["rmse_remapped"]
    check(abs(rn - rb) < 0.01 * rb and a_numpy["verdict"] == a_builtin["verdict"]
          and abs(a_numpy["chi2_per_dof"] - a_builtin["chi2_per_dof"]) < 0.02 * a_builtin["chi2_per_dof"],
          f"ww-corrected in NumPy at theta_i {a_builtin['theta_i']:g}: RMSE {rn:.6f} against the built-in's {rb:.6f}, "
          f"chi2/dof {a_numpy['chi2_per_dof']:.3g} against {a_builtin['chi2_per_dof']:.3g}, the same verdict")
wrong = gonio.compare(coat, coat_run, models=[gonio.Model(
    lambda l, v, p: ww_corrected(l, v, dict(p, albedo=np.asarray(p["albedo"]) * 1.5 ** 2 / 1.5)), "no-eta",
    params_of(coat), k=8)])   # the negative control: the solid-angle factor 1 / eta^2 as 1 / eta
rw = next(m for m in wrong.summary["models"] if m["id"] == "no-eta")["angles"][1]["rmse_remapped"]
check(abs(rw - by_id["ww-corrected"]["angles"][1]["rmse_remapped"]) > 0.05 * rw,
      f"the check can fail: a port with 1 / eta for 1 / eta^2 scores RMSE {rw:.6f}")

# a model as GLSL text: compare --model FILE's bytes
check(cli("compare", PLASTIC, *CLI_OPTS, "--models", "ww09,schlick-coat", "--model", "examples/user_model.glsl", "--no-report",
          "--out", f"{tmp}/cli-user").returncode == 0, "gonio compare --model FILE ran")
user = gonio.compare(stack, run, models=["ww09", read("examples/user_model.glsl")])
check(user.core.slices_csv() == read(f"{tmp}/cli-user/slices.csv"), "a GLSL model as text: compare --model's slices.csv")
scored = untimed(json.loads(user.core.summary_json()))["models"]
by_file = untimed(json.load(open(f"{tmp}/cli-user/summary.json")))["models"]
for m in scored + by_file:
    m.pop("file", None)
check(scored == by_file, "a GLSL model as text: its metrics are compare --model's")

# 4. fit: a known parameter recovered within its standard error, on a stack whose f is known (a bare Lambertian)
lambert = gonio.Stack({"name": "grey", "layer": [{"interface": "lambertian", "albedo": [0.4, 0.4, 0.4]}]})
grey = gonio.simulate(lambert, theta_i=[0, 40], paths=200000, dtheta=5, dphi=10, seed=5, progress=False)


def constant(l, v, params):
    return np.full((len(l), 3), params["albedo"] / np.pi)


for loss in ("log", "chi2"):
    f = gonio.fit(grey, constant, free={"albedo": 0.1}, loss=loss)
    a, se = f.value("albedo"), f.se("albedo")
    check(abs(a - 0.4) < 4 * se and 0 < se < 0.01, f"fit ({loss}): albedo {a:.5f} +- {se:.5f}, the stack's 0.4")
    check(f.loss_best < f.loss_start and ("constant@fit", 40.0, "R") in f.run.values,
          f"fit ({loss}): the loss fell, the model at the fit is in its run")
half = gonio.fit(grey, lambda l, v, p: np.full((len(l), 3), p["albedo"] / (2 * np.pi)), free={"albedo": 0.1})
check(abs(half.value("albedo") - 0.8) < 4 * half.se("albedo"), "fit: a model with half the lobe fits twice the albedo")

# a built-in's fit: fit.json as `gonio fit` writes it for the same stack, options and seed
check(cli("fit", PLASTIC, *CLI_OPTS, "--model", "ww-corrected", "--free", "layer.1.roughness", "--no-report", "--out",
          f"{tmp}/cli-fit").returncode == 0, "gonio fit ran")
built_in = gonio.fit(run, "ww-corrected", free=["layer.1.roughness"])
check(untimed(built_in.json) == untimed(json.load(open(f"{tmp}/cli-fit/fit.json"))),
      f"a built-in's fit: fit.json is gonio fit's (roughness {built_in.value('layer.1.roughness'):.5f})")
check(built_in.run.core.slices_csv() == read(f"{tmp}/cli-fit/slices.csv"), "a built-in's fit: slices.csv is gonio fit's")

# render: the images gonio render writes
RENDER = ["--env", "studio", "--size", "24", "--spp", "4", "--paths", "2e4", "--theta-i", "0:80:20", "--models",
          "ww-corrected"]
check(cli("render", PLASTIC, *RENDER, "--no-report", "--quiet", "--out", f"{tmp}/cli-render").returncode == 0,
      "gonio render ran")
pic = gonio.render(stack, env="studio", size=24, spp=4, paths=2e4, theta_i="0:80:20", models="ww-corrected")
check(set(pic.images) == {"reference", "reference-half-a", "reference-half-b", "ww-corrected"}
      and pic.images["reference"].shape == (24, 24, 4), "render: the reference, its halves and the model, 24 x 24")
try:
    for name in ("reference", "ww-corrected"):
        e = gonio.read_exr(f"{tmp}/cli-render/{name}.exr")
        part = next(iter(e.values()))
        check(all(np.array_equal(pic.images[name][..., i], part[c]) for i, c in enumerate("RGBA")),
              f"render: {name}'s image is the CLI's {name}.exr, bit for bit")
except ImportError:
    print("note: OpenEXR is not installed; the render's images not compared with the CLI's")

# 5. refusals raise Python exceptions, never end the interpreter
bad = gonio.Stack({"name": "bad", "layer": [{"interface": "dielectric", "ior": 1.5, "roughness": 2.0},
                                            {"interface": "lambertian", "albedo": [0.5, 0.5, 0.5]}]})
try:
    gonio.simulate(bad, paths=1000, progress=False)
    check(False, "a roughness of 2 is refused")
except gonio.StackError as e:
    check(e.key == "layers[0].roughness" and "roughness" in e.reason, f"a dict's bad key is named: {e}")
r = cli("check", "tests/bad_stacks/albedo-above-one.toml")
try:
    gonio.Stack.from_toml("tests/bad_stacks/albedo-above-one.toml")
    check(False, "a bad stack file is refused")
except gonio.StackError as e:
    check(f"gonio: {e}" == r.stderr.strip() and e.line > 0, f"a bad file's refusal is the CLI's: {e}")
for opts, what in ((dict(dtheta=7), "a bin width that does not divide 90"), (dict(out="x"), "an option that writes"),
                   (dict(no_such_option=1), "an unknown option"), (dict(paths=-1), "a negative path count")):
    try:
        gonio.simulate(stack, progress=False, **opts)
        check(False, f"{what} is refused")
    except ValueError as e:
        check(True, f"{what} is refused: {e}")
for f, what in ((lambda l, v, p: np.zeros(len(l)), "a model of the wrong shape"),
                (lambda l, v, p: 1 / 0, "a model that raises")):
    try:
        gonio.compare(stack, run, models=[f])
        check(False, f"{what} is refused")
    except (ValueError, ZeroDivisionError) as e:
        check(True, f"{what} raises {type(e).__name__}")
for value, what in ((np.nan, "NaN"), (-1.0, "negative")):
    try:
        gonio.compare(stack, run, models=[gonio.Model(lambda l, v, p: np.full((len(l), 3), value), id="bad")])
        check(False, f"a model's {what} values are refused")
    except ValueError as e:
        check("nothing is clamped" in str(e), f"a model's {what} values are refused, as gonio score refuses them")

# 6. memory: many runs in a loop hold it flat
N = int(os.environ.get("GONIO_API_LOOP", "1000"))
small = dict(theta_i=[30], paths=1000, dtheta=15, dphi=30, progress=False)
for _ in range(20):
    gonio.simulate(stack, **small)
before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
t0 = time.time()
for i in range(N):
    gonio.simulate(stack, seed=i + 1, **small)
grew = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - before
check(grew < 20000, f"{N} simulate calls in {time.time() - t0:.0f} s: peak memory grew {grew} KiB (< 20 MiB)")

# 7. Ctrl-C stops a long run with KeyboardInterrupt; the next run works
threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
t0 = time.time()
try:
    gonio.simulate(stack, theta_i=[0], paths=1e11, progress=False)
    check(False, "Ctrl-C stops a run")
except KeyboardInterrupt:
    check(time.time() - t0 < 30, f"Ctrl-C stopped a run of 1e11 paths after {time.time() - t0:.1f} s")
check(gonio.simulate(stack, progress=False, **OPTS).core.slices_csv() == run.core.slices_csv(),
      "after Ctrl-C, a run gives its bytes")
for what, call in (("a spectral run", lambda: gonio.simulate(stack, spectral=True, theta_i=[0], paths=1e10,
                                                             progress=False)),
                   ("a render's table", lambda: gonio.render(stack, paths=1e10, theta_i="0:80:40", progress=False))):
    threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
    t0 = time.time()
    try:
        call()
        check(False, f"Ctrl-C stops {what}")
    except KeyboardInterrupt:
        check(time.time() - t0 < 60, f"Ctrl-C stopped {what} after {time.time() - t0:.1f} s")
# the GIL is released while the device works: a Python thread counts on meanwhile
count, stop = [0], threading.Event()


def counting():
    while not stop.is_set():
        count[0] += 1


counter = threading.Thread(target=counting)
counter.start()
t0 = time.time()
gonio.simulate(stack, theta_i=[0, 30, 60], paths=3e6, dtheta=5, dphi=10, progress=False)
during = time.time() - t0
stop.set()
counter.join()
check(count[0] > 100000 * during, f"the GIL is released: a thread counted to {count[0]} in the run's {during:.1f} s")
calls = []
gonio.simulate(stack, progress=lambda done, total: calls.append((done, total)), **OPTS)
check(len(calls) > 0 and calls[-1][0] == calls[-1][1] == 400000, f"progress: called {len(calls)} times, to the end")

# 8. help(gonio.simulate) says what `gonio simulate --help` says
check(cli("simulate", "--help").stdout in gonio.simulate.__doc__, "gonio.simulate's docstring holds simulate --help")
check(cli("compare", "--help").stdout in gonio.compare.__doc__, "gonio.compare's docstring holds compare --help")
check(cli("render", "--help").stdout in gonio.render.__doc__, "gonio.render's docstring holds render --help")
check(cli("fit", "--help").stdout in gonio.fit.__doc__, "gonio.fit's docstring holds fit --help")

# 9. examples/notebook.py runs and draws its figure
nb = subprocess.run([sys.executable, os.path.join(ROOT, "examples", "notebook.py"), "--out", f"{tmp}/notebook.png",
                     "--paths", "2e5"], capture_output=True, text=True,
                    env=dict(os.environ, PYTHONPATH=os.pathsep.join([os.path.join(ROOT, "python"),
                                                                     os.path.join(BUILD, "python")])))
fitted = re.search(r"fitted alpha ([0-9.]+) \+- ([0-9.]+)", nb.stdout)
check(nb.returncode == 0 and os.path.getsize(f"{tmp}/notebook.png") > 10000 and fitted is not None
      and abs(float(fitted[1]) - 0.25) < 4 * float(fitted[2]) + 0.01,
      f"examples/notebook.py drew its figure and fitted alpha {fitted[1] if fitted else '?'} (the stack's 0.25)"
      + ("" if nb.returncode == 0 else nb.stderr[-2000:]))

print(f"{len(failures)} failures" if failures else "all checks passed")
sys.exit(1 if failures else 0)
