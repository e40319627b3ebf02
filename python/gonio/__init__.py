"""gonio in Python: its output files as numpy arrays, and (with the compiled module gonio._core, which `pip install
./python` builds) gonio itself in this process: gonio.simulate, gonio.compare, gonio.fit (docs/PYTHON.md).

    stack = gonio.Stack.from_toml("stacks/plastic.toml")
    run = gonio.simulate(stack, theta_i=[0, 30, 60], paths=1e6, seed=1)   # a gonio.Run, in memory

    import gonio
    run = gonio.read_run("out/plastic")          # summary.json + slices.csv of a simulate / compare output
    f = run.f("reference", 60, "R")              # (n_theta, n_phi, 3), bin averages of f in 1/sr (cosine excluded)
    se = run.se("reference", 60, "R")            # their standard errors (0 for a model)
    run.bins.solid_angle()                       # (n_theta, n_phi) steradians; sums to 2 pi per side
    albedo = (f * run.bins.projected_solid_angle()[..., None]).sum(axis=(0, 1))
    gonio.export_merl(run, "plastic.binary")     # a run over theta_i 0, 2, ..., 88 as a MERL file
    gonio.rgl.export_rgl(run, "plastic.bsdf")    # ... as an RGL .bsdf for Mitsuba 3's measured (needs mitsuba)
    spec = gonio.read_spectral_run("out/gold")   # simulate --spectral: spec.bands(30), spec.xyz(30), wavelength_nm
    summary, bins = gonio.read_colour_error("out/gold-rvs")   # compare --rgb-vs-spectral: per-bin CIEDE2000, ITP
    nodes = gonio.read_nodes("out/nodes")        # where `gonio nodes` asks for f: nodes.l, nodes.v, nodes.weight
    gonio.write_values("out/values.npy", f_at_nodes)   # (n, 3) f there, for `gonio score --values`

Conventions (docs/PHYSICS.md): directions point away from the surface, z is the stack normal, the light arrives
from (theta_i, phi_i = 0); row t of a side is the theta bin [t dtheta, (t+1) dtheta) measured from +z (R) or from
-z (T); column p is the phi bin centred on p dphi.
"""
import pkgutil

# gonio._core, the compiled module, where pip installed it (here) or beside a build (build/python/gonio, on PYTHONPATH)
__path__ = pkgutil.extend_path(__path__, __name__)

from .bins import Bins
from .nodes import Nodes, read_nodes, write_values
from .outputs import Run, read_run, read_slices, read_summary, read_sweep, read_exr
from . import merl, rgl
from .spectral import SpectralRun, read_colour_error, read_spectral_run
from .table import IsotropicTable, export_merl
from .stack import Layer, Stack
from ._core_loader import StackError
from .api import Model, Render, compare, evaluate, fit, render, run_nodes, simulate

__all__ = ["Bins", "Run", "read_run", "read_slices", "read_summary", "read_sweep", "read_exr", "IsotropicTable",
           "export_merl", "Nodes", "read_nodes", "write_values", "SpectralRun", "read_spectral_run", "read_colour_error",
           "Stack", "Layer", "StackError", "Model", "Render", "simulate", "compare", "evaluate", "render", "run_nodes",
           "fit"]
