"""gonio in this process: the reference, the models, compare and fit, with results in memory as the readers give
them (gonio.Run) and your model as a NumPy function. docs/PYTHON.md is the guide; the options are the command
line's (help(gonio.simulate) prints `gonio simulate --help`), given as keywords: theta_i=[0, 30] is --theta-i 0,30,
paths=1e7 --paths 1e7, no_series=True --no-series.

    import gonio
    stack = gonio.Stack.from_toml("stacks/plastic.toml")
    run = gonio.simulate(stack, theta_i=[0, 30, 60], paths=1e6, seed=1)
    cmp = gonio.compare(stack, run, models=["ww-corrected", my_model])   # cmp.summary["models"]: the metrics
    fit = gonio.fit(run, my_model, free={"albedo": 0.5})                   # fit.parameters: values and se

Conventions (docs/PHYSICS.md): directions point away from the surface, z is the normal, the light arrives from
(theta_i, phi_i); f is in 1/sr without the cosine; a bin's value is f's average over its projected solid angle.
A model is f(l, v, params) -> (N, 3), l and v (N, 3) unit vectors, v.z < 0 on the transmission side.
"""
import io
import json
import math
from dataclasses import dataclass

import numpy as np

from ._core_loader import StackError, checked, core
from .bins import Bins
from .nodes import SIDES, Nodes
from .outputs import Run, parse_slices
from .stack import Stack

__all__ = ["Stack", "StackError", "Model", "Render", "simulate", "compare", "evaluate", "render", "run_nodes", "fit"]


def _option_value(v):
    if isinstance(v, (list, tuple, np.ndarray)):
        return ",".join(_option_value(x) for x in (v.tolist() if isinstance(v, np.ndarray) else v))
    if isinstance(v, (float, np.floating)) and float(v).is_integer() and abs(v) < 1e18:
        return str(int(v))
    return str(v.item() if isinstance(v, np.generic) else v)


def _args(options):
    """Keyword options as the command line's: theta_i=[0, 30] -> --theta-i 0,30; flag=True -> --flag."""
    args = []
    for key, value in options.items():
        if value is None or value is False:
            continue
        flag = "--" + key.replace("_", "-")
        args += [flag] if value is True else [flag, _option_value(value)]
    return args


def _progress(progress):
    """The callable the walk calls with (paths done, paths in all): tqdm's bar where installed and asked (None or
    True), a caller's callable as it is, nothing for False."""
    if callable(progress):
        return progress, None
    if progress is False:
        return None, None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None, None
    bar = tqdm(total=0, unit="path", unit_scale=True, leave=False)

    def update(done, total):
        bar.total = total
        bar.n = done
        bar.refresh()
    return update, bar


def _run_of(core_run):
    summary = json.loads(core_run.summary_json(), parse_constant=lambda c: math.nan)
    bins = Bins.from_summary(summary)
    values = parse_slices(io.StringIO(core_run.slices_csv()), bins, "slices.csv (in memory)")
    return Run(summary, bins, values, core=core_run)


def _stack(stack):
    if isinstance(stack, Stack):
        return stack
    if isinstance(stack, dict):
        return Stack(stack)
    if isinstance(stack, str):
        return Stack.from_toml(stack)
    raise TypeError(f"a stack is a gonio.Stack, a dict of its keys or a stack file's path, not {type(stack).__name__}")


def _run_stack(stack, options, compare_models, progress):
    call, bar = _progress(progress)
    try:
        return _run_of(checked(_stack(stack), lambda text, path: core().run(text, path, _args(options),
                                                                           compare_models, call)))
    finally:
        if bar is not None:
            bar.close()


def simulate(stack, progress=None, spectral=False, **options):
    """The reference of `stack` (a gonio.Stack, a dict, or a stack file's path) in memory: a gonio.Run, as
    gonio.read_run reads `gonio simulate`'s outputs, the same bytes for the same options (run.save(DIR) writes
    them). Options are simulate's, as keywords (below); those that write files (out, resume,
    checkpoint_seconds) are refused. progress: None (a tqdm bar where tqdm is installed), False, or a callable
    (paths done, paths in all). Ctrl-C stops the run (KeyboardInterrupt).
    spectral=True: simulate --spectral (bands=, band_points=, band_paths=), a gonio.SpectralRun as
    gonio.read_spectral_run reads its files, the values its EXR holds.
    """
    if spectral:
        from .spectral import SpectralRun
        call, bar = _progress(progress)
        try:
            summary, parts = checked(_stack(stack), lambda text, path: core().spectral_run(text, path, _args(options),
                                                                                          call))
        finally:
            if bar is not None:
                bar.close()
        return SpectralRun(json.loads(summary, parse_constant=lambda c: math.nan), parts)
    return _run_stack(stack, options, False, progress)


class Model:
    """Your model as a NumPy function f(l, v, params) -> (N, 3): l, v (N, 3) unit vectors away from the surface
    (v.z < 0: the transmission side), f in 1/sr without the cosine; params a dict of its parameters (those it
    fits). Its bins are the averages over each bin of k x k Gauss-Legendre nodes (gonio nodes), as gonio score
    puts a model's values on the bins."""

    def __init__(self, f, id=None, params=None, k=4):
        self.f, self.id = f, id or getattr(f, "__name__", "model")
        self.params, self.k = dict(params or {}), int(k)

    def values(self, at, params=None):
        p = dict(self.params)
        p.update(params or {})
        v = np.asarray(self.f(at.l, at.v, p), dtype=np.float64)
        if v.shape != (len(at), 3):
            raise ValueError(f"model {self.id}: f returned shape {v.shape}, expected ({len(at)}, 3): one r, g, b "
                             f"per pair of directions")
        return v


def _model(m):
    return m if isinstance(m, Model) else Model(m)


def run_nodes(run, k=4):
    """Where a model given as values is evaluated on run's bins (gonio nodes' nodes, in memory): a gonio.Nodes."""
    d = run.core.nodes(int(k))
    theta = np.asarray(run.theta_i)[d["angle"]]
    return Nodes(theta, SIDES[d["side"]], d["bin"].astype(np.int64), d["l"], d["v"], d["weight"],
                 {"k": int(k), "angle": d["angle"]})


def _model_bins(run, model, params=None):
    m = _model(model)
    return run.core.values_model(m.id, m.k, m.values(run_nodes(run, m.k), params))


def _require_core_run(run, what):
    if not isinstance(run, Run) or run.core is None:
        raise TypeError(f"{what} takes a run made in this process (gonio.simulate), not a run read from files")


def compare(stack, run=None, models=None, progress=None, **options):
    """The models on the reference's bins and their comparison with it, as `gonio compare` scores them: a gonio.Run
    whose summary holds the metrics and verdicts (summary["models"]) and whose values hold each model's bins.
    With run (a gonio.simulate run of the stack), its reference is kept and only the models run. models: None
    (every model compare runs), or a list of built-in ids (gonio models), gonio.Model and NumPy functions
    f(l, v, params), and models as GLSL text (a model file's: its first line // gonio-model: ID, docs/MODELS.md
    "Your own model"). Options are compare's (below)."""
    ids = [m for m in (models or []) if isinstance(m, str) and "\n" not in m]
    glsl = [m for m in (models or []) if isinstance(m, str) and "\n" in m]
    mine = [m for m in (models or []) if not isinstance(m, str)]
    if ids:
        options = dict(options, models=",".join(ids))
    if run is None:
        if not mine and not glsl:
            return _run_stack(stack, options, True, progress)
        run = _run_stack(stack, {k: v for k, v in options.items() if k not in _MODEL_OPTIONS}, False, progress)
    _require_core_run(run, "gonio.compare")
    extra = [_model_bins(run, m) for m in mine]
    return _run_of(run.core.with_models(_args({k: v for k, v in options.items() if k in _MODEL_OPTIONS}), extra, glsl))


_MODEL_OPTIONS = ("models", "model", "no_belcour_tables")


@dataclass
class Render:
    """gonio render's images in memory: images {"reference", "reference-half-a", "reference-half-b", model id:
    (size, size, 4) float32 RGBA, linear, row 0 at the top, A = 1 on the sphere}, the models not rendered with why,
    and the environment."""
    images: dict
    not_rendered: dict
    environment: str


def render(stack, progress=None, **options):
    """The reference and every model that can represent the stack on a sphere under an environment map, as
    `gonio render` renders them (its options, as keywords: env, size, spp, paths, theta_i, seed, models, model;
    not out, reference or spectral): a gonio.Render, the images render.exr would hold. progress and Ctrl-C as
    simulate's, while the table is traced."""
    call, bar = _progress(progress)
    try:
        images, not_rendered, env = checked(_stack(stack), lambda text, path: core().render(text, path, _args(options),
                                                                                           call))
    finally:
        if bar is not None:
            bar.close()
    return Render(images, not_rendered, env)


def evaluate(model, run, params=None):
    """One model's bins on run's grid (a built-in id, a gonio.Model or a NumPy function): a gonio.Run holding the
    reference and the model (run.f(id, theta_i, side))."""
    _require_core_run(run, "gonio.evaluate")
    if isinstance(model, str):
        return _run_of(run.core.with_models(["--models", model], []))
    return _run_of(run.core.with_models([], [_model_bins(run, model, params)]))


for _f, _command in ((simulate, "simulate"), (compare, "compare"), (render, "render")):
    try:
        _f.__doc__ += "\n" + core().command_help(_command)
    except ImportError:
        pass


from .fit import fit  # noqa: E402  (fit uses the functions above)
