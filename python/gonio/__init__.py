"""gonio's output files as numpy arrays: `pip install ./python` (numpy; OpenEXR for read_exr).

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
from .bins import Bins
from .nodes import Nodes, read_nodes, write_values
from .outputs import Run, read_run, read_slices, read_summary, read_sweep, read_exr
from . import merl, rgl
from .spectral import SpectralRun, read_colour_error, read_spectral_run
from .table import IsotropicTable, export_merl

__all__ = ["Bins", "Run", "read_run", "read_slices", "read_summary", "read_sweep", "read_exr", "IsotropicTable",
           "export_merl", "Nodes", "read_nodes", "write_values", "SpectralRun", "read_spectral_run", "read_colour_error"]
