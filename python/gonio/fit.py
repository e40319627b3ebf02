"""gonio.fit: the parameters of a NumPy model that bring it closest to a run's reference, with standard errors from
the reference's noise (Levenberg-Marquardt over the bins; docs/PYTHON.md, "Fitting a model in NumPy")."""
import json
import math
from dataclasses import dataclass, field

import numpy as np

from ._core_loader import core
from .api import Model, _model, _model_bins, _require_core_run, _run_of, run_nodes


def _g(f):
    """The log loss's remapping (model_fit.h FitLoss::Log): g(f) = log(1 + sqrt f), and dg/df."""
    s = np.sqrt(np.maximum(f, 0.0))
    return np.log1p(s), np.where(s > 0, 0.5 / (np.maximum(s, 1e-300) * (1 + s)), 0.0)


@dataclass
class FitResult:
    """What gonio.fit found: each free parameter's start, value and standard error (the reference's noise through
    the linearised fit), the loss at the start and at the fit, and the run with the model at both (ids ID and
    ID@fit, as `gonio fit` writes them)."""
    model: str
    loss: str
    parameters: list   # [{"name", "start", "value", "se"}], in the order of `free`
    loss_start: float
    loss_best: float
    iterations: int
    stopped: str
    run: object = field(repr=False, default=None)
    json: dict = field(repr=False, default=None)   # a built-in's: fit.json, as `gonio fit` writes it

    def value(self, name):
        return next(p["value"] for p in self.parameters if p["name"] == name)

    def se(self, name):
        return next(p["se"] for p in self.parameters if p["name"] == name)


class _Target:
    """The reference's bins the model is scored on: every incident angle and side the model has values on."""

    def __init__(self, run, model, loss):
        self.nodes = run_nodes(run, model.k)
        self.loss = loss
        nodes = self.nodes   # which slice each node's bin is in: angle, then side
        self.index = nodes.meta["angle"].astype(np.int64) * 2 + (nodes.side == "T")
        self.bin = nodes.bin
        n_bins = run.bins.n_theta * run.bins.n_phi
        self.slot = self.index * n_bins + self.bin   # a node's bin over all slices
        self.n_slots = (self.index.max() + 1) * n_bins
        ref = np.zeros((self.n_slots, 3))
        se = np.zeros((self.n_slots, 3))
        omega = np.tile(run.bins.projected_solid_angle().reshape(-1), int(self.index.max()) + 1)
        used = np.zeros(self.n_slots, bool)
        for a, theta in enumerate(run.theta_i):
            for side_index, side in enumerate("RT"):
                key = ("reference", float(theta), side)
                if key not in run.values:
                    continue
                s = (2 * a + side_index) * n_bins
                ref[s:s + n_bins] = run.values[key][..., :3].reshape(-1, 3)
                se[s:s + n_bins] = run.values[key][..., 3:].reshape(-1, 3)
                used[s:s + n_bins] = True
        used &= np.isin(np.arange(self.n_slots), self.slot)
        if loss == "chi2":
            used &= (se > 0).all(axis=1)
        self.used, self.ref, self.se, self.omega = used, ref[used], se[used], omega[used]

    def bins(self, values):
        """The bins' averages: the sum over each bin's nodes of weight x f."""
        out = np.zeros((self.n_slots, 3))
        np.add.at(out, self.slot, values * self.nodes.weight[:, None])
        return out[self.used]

    def residuals(self, m):
        """r with loss = mean(r^2), and dr/d(reference) per residual."""
        if self.loss == "log":
            gm, _ = _g(m)
            gr, dgr = _g(self.ref)
            return (gm - gr).ravel(), -dgr.ravel()
        if self.loss == "cosine":
            w = np.sqrt(self.omega)[:, None] * np.ones((1, 3))
            return ((m - self.ref) * w).ravel(), -w.ravel()
        return ((m - self.ref) / self.se).ravel(), (-1.0 / self.se).ravel()


def _fit_builtin(run, model, free, loss, start):
    """gonio fit --reference on the run in memory: fit.json's bytes, the run with the model at both ends."""
    free = dict.fromkeys(free) if not isinstance(free, dict) else dict(free)
    args = ["--model", model, "--free", ",".join(free), "--loss", loss]
    for key, value in list(free.items()) + list((start or {}).items()):
        for v in (value if isinstance(value, (list, tuple)) else [value]):
            if v is not None:
                args += ["--start", f"{key}={float(v)!r}"]
    got = core().fit(run.core, args)
    j = json.loads(got.fit_json, parse_constant=lambda c: math.nan)
    parameters = [dict(name=k, **v) for k, v in j["parameters"].items()]
    return FitResult(j["model"], j["loss"]["name"], parameters, j["loss"]["start"], j["loss"]["best"],
                     j["iterations"], j["stopped"], _run_of(got.run), j)


def fit(run, model, free, loss="log", params=None, max_iterations=40, start=None):
    """The values of a model's parameters that bring it closest to run's reference (a gonio.simulate run).

    A built-in model (its id) or a model file (FILE.glsl) is fitted as `gonio fit --reference` fits it, in memory:
    free is a list of stack keys (layer.N.KEY, exterior_ior, param.NAME) or a dict of them to their starts (None:
    the stack's value); start={key: [v, ...]} starts from several points; FitResult.json is fit.json. For a NumPy
    model:

    model: a gonio.Model or f(l, v, params) -> (N, 3); free: {name: start} (the parameters fitted; the others
    from params, then the model's own); loss: "log" (compare's remapped error, squared: mean of (g(model) -
    g(reference))^2 with g(f) = log(1 + sqrt f)), "cosine" (mean of (model - reference)^2 times each bin's
    projected solid angle) or "chi2" (mean of ((model - reference) / se)^2 over the bins with se > 0), taken over
    the bins of every incident angle and side. Levenberg-Marquardt with central differences; each standard error
    is the reference's noise (its bins' se) through the linearised fit. Returns a FitResult.
    """
    _require_core_run(run, "gonio.fit")
    if isinstance(model, str):
        return _fit_builtin(run, model, free, loss, start)
    if loss not in ("log", "cosine", "chi2"):
        raise ValueError(f"loss {loss!r}: expected log, cosine or chi2")
    m = _model(model)
    if not free:
        raise ValueError("free: at least one parameter, {name: start}")
    names = list(free)
    fixed = dict(m.params)
    fixed.update(params or {})
    target = _Target(run, m, loss)

    def residuals(x):
        p = dict(fixed)
        p.update(zip(names, map(float, x)))
        return target.residuals(target.bins(m.values(target.nodes, p)))

    def jacobian(x, r0):
        cols = []
        for i in range(len(x)):
            h = 1e-5 * max(1.0, abs(x[i]))
            up, down = x.copy(), x.copy()
            up[i] += h
            down[i] -= h
            cols.append((residuals(up)[0] - residuals(down)[0]) / (2 * h))
        return np.stack(cols, axis=1)

    x = np.array([float(free[n]) for n in names])
    r, _ = residuals(x)
    if not np.all(np.isfinite(r)):
        raise ValueError(f"model {m.id}: values that are not finite at the start {dict(zip(names, x))}")
    loss_start = cost = float(np.mean(r * r))
    lam, stopped, it = 1e-3, f"{max_iterations} iterations", 0
    for it in range(1, max_iterations + 1):
        J = jacobian(x, r)
        A, g = J.T @ J, J.T @ r
        improved = False
        while lam < 1e12:
            step = np.linalg.solve(A + lam * np.diag(np.maximum(np.diag(A), 1e-300)), -g)
            r_new, _ = residuals(x + step)
            c_new = float(np.mean(r_new * r_new)) if np.all(np.isfinite(r_new)) else np.inf
            if c_new < cost:
                x, r, improved = x + step, r_new, True
                lam = max(lam / 10, 1e-12)
                break
            lam *= 10
        if not improved:
            stopped = "no step lowers the loss"
            break
        if cost - c_new <= 1e-12 * max(cost, 1e-300) or np.all(np.abs(step) <= 1e-9 * np.maximum(1, np.abs(x))):
            cost = c_new
            stopped = "converged"
            break
        cost = c_new
    # the reference's noise through the linearised fit: dx = -(J^T J)^-1 J^T dr, dr = (dr/dref) dref, dref ~ se
    r, dr_dref = residuals(x)
    J = jacobian(x, r)
    A_inv = np.linalg.pinv(J.T @ J)
    se_ref = target.se.ravel()
    B = A_inv @ J.T * (dr_dref * se_ref)[None, :]
    se = np.sqrt(np.sum(B * B, axis=1))
    best = dict(fixed)
    best.update(zip(names, map(float, x)))
    start = dict(fixed)
    start.update({n: float(free[n]) for n in names})
    at_start = Model(m.f, m.id, start, m.k)
    at_fit = Model(m.f, m.id + "@fit", best, m.k)
    both = _run_of(run.core.with_models([], [_model_bins(run, at_start), _model_bins(run, at_fit)]))
    parameters = [{"name": n, "start": float(free[n]), "value": float(v), "se": float(s)}
                  for n, v, s in zip(names, x, se)]
    return FitResult(m.id, loss, parameters, loss_start, float(np.mean(r * r)), it, stopped, both)


try:   # help(gonio.fit) says what `gonio fit --help` says of the options a built-in's fit takes
    fit.__doc__ += "\n" + core().command_help("fit")
except ImportError:
    pass
