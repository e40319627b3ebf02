"""An isotropic BRDF table from a gonio run over many incident angles: f(wi, wo) for any pair of directions.

Lookup (reflection side): by reciprocity the pair is ordered so that the smaller polar angle is the incident one
(gonio tabulates f for the light at theta_i, phi_i = 0); f is interpolated linearly in theta_i between the two
tabulated angles around it, each read from the bin holding wo (rotated so that wi lies at phi = 0) turned in the
plane of incidence by the difference of the angles, so that a lobe around the mirror direction is interpolated along
its motion (each bin is a bin average of f). Pairs beyond the last tabulated angle, or below the horizon, have no data (nan).
"""
import numpy as np

from . import merl


class TableError(ValueError):
    """A table that cannot serve the lookup asked of it; the message says why."""


class IsotropicTable:
    """quantity "f" (the bin averages) or "se" (their standard errors; between tabulated angles interpolated
    linearly like f, an approximation of the interpolated estimate's se)."""

    def __init__(self, run, source="reference", quantity="f"):
        if run.phi_i != 0.0:   # an isotropic BRDF's table is the plane of incidence's, phi_i = 0
            raise TableError(f"the run is at the incident azimuth phi_i {run.phi_i:g} (simulate --phi-i); an isotropic "
                             f"table takes phi_i = 0")
        self.bins = run.bins
        angles = sorted({k[1] for k in run.values if k[0] == source and k[2] == "R"})
        if not angles:
            raise TableError(f"the run has no reflection slices of {source!r}")
        self.theta_i = np.array(angles)
        read = run.f if quantity == "f" else run.se
        self.slices = np.stack([read(source, t, "R") for t in angles])   # (n_angles, n_theta, n_phi, 3)

    def check_dense(self, max_step_deg, last_at_least_deg, what):
        """Refuse a table too sparse in theta_i for `what`, with the reason."""
        t = self.theta_i
        steps = np.diff(t)
        if t[0] != 0 or t[-1] < last_at_least_deg or (steps.size and steps.max() > max_step_deg) or t.size < 2:
            raise TableError(
                f"{what} needs incident angles from 0 to at least {last_at_least_deg} degrees at most {max_step_deg} "
                f"degrees apart (e.g. --theta-i 0,2,4,...,88); the run has {', '.join(f'{x:g}' for x in t)}")

    def f(self, wi, wo):
        """(..., 3) f in 1/sr for unit directions wi, wo (..., 3) pointing away from the surface."""
        wi, wo = np.asarray(wi, dtype=np.float64), np.asarray(wo, dtype=np.float64)
        swap = wo[..., 2] > wi[..., 2]   # reciprocity: the smaller polar angle is the incident one
        a = np.where(swap[..., None], wo, wi)
        b = np.where(swap[..., None], wi, wo)
        ti = np.degrees(np.arccos(np.clip(a[..., 2], -1, 1)))
        to = np.degrees(np.arccos(np.clip(b[..., 2], -1, 1)))
        phi = np.degrees(np.arctan2(b[..., 1], b[..., 0]) - np.arctan2(a[..., 1], a[..., 0]))
        valid = (a[..., 2] > 0) & (b[..., 2] > 0) & (ti <= self.theta_i[-1])
        # the two tabulated angles around ti and the weight of the upper one
        k = np.clip(np.searchsorted(self.theta_i, ti, side="right") - 1, 0, self.theta_i.size - 2)
        t0, t1 = self.theta_i[k], self.theta_i[k + 1]
        w = np.clip((ti - t0) / (t1 - t0), 0.0, 1.0)[..., None]
        # b in a's frame (a at phi = 0), read from each of the two slices turned about y by the difference of the
        # incident angles, so that the mirror direction of ti falls on the slice's own: a lobe that follows the
        # mirror direction is interpolated along its motion, not across it (where the turn takes b below the
        # horizon, the slice is read at b itself)
        r = np.radians(phi)
        st, ct = np.sin(np.radians(to)), np.cos(np.radians(to))
        bx, by, bz = st * np.cos(r), st * np.sin(r), ct
        out = 0.0
        for kk, weight in ((k, 1 - w), (k + 1, w)):
            d = np.radians(ti - self.theta_i[kk])
            cx, cz = bx * np.cos(d) + bz * np.sin(d), -bx * np.sin(d) + bz * np.cos(d)
            below = cz <= 0
            cx, cz = np.where(below, bx, cx), np.where(below, bz, cz)
            t2 = np.degrees(np.arccos(np.clip(cz, -1, 1)))
            p2 = np.degrees(np.arctan2(by, cx))
            row = np.clip((t2 / self.bins.dtheta_deg).astype(np.int64), 0, self.bins.n_theta - 1)
            col = np.mod(np.floor(p2 / self.bins.dphi_deg + 0.5).astype(np.int64), self.bins.n_phi)
            out = out + weight * self.slices[kk, row, col]
        return np.where(valid[..., None], out, np.nan)


def export_merl(run, path, source="reference"):
    """Write a run's reflection table as a MERL .binary file (python/gonio/merl.py). Needs incident angles from 0
    to at least 80 degrees, at most 5 degrees apart. Returns the fraction of cells with data."""
    table = IsotropicTable(run, source)
    table.check_dense(5, 80, "a MERL export")
    wi, wo = merl.half_diff_to_directions(*merl.cell_angles())
    f = table.f(wi, wo)                                           # (90, 90, 180, 3)
    merl.write(path, np.moveaxis(f, -1, 0))
    return float(np.isfinite(f[..., 0]).mean())
