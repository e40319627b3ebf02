"""The hemisphere bins gonio tallies into (summary.json's "bins"): geometry and solid angles."""
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Bins:
    dtheta_deg: float
    dphi_deg: float
    n_theta: int
    n_phi: int
    phi_centred: bool = True   # column p covers [p dphi - dphi/2, p dphi + dphi/2)

    @staticmethod
    def from_summary(summary):
        b = summary["bins"]
        return Bins(float(b["dtheta_deg"]), float(b["dphi_deg"]), int(b["n_theta"]), int(b["n_phi"]),
                    bool(b.get("phi_bins_centred_on_multiples_of_dphi", True)))

    def theta_edges_deg(self):
        """n_theta + 1 edges in degrees, 0 to 90, from the side's pole."""
        return np.arange(self.n_theta + 1) * self.dtheta_deg

    def phi_edges_deg(self):
        """n_phi + 1 edges in degrees; the light arrives from phi = 0."""
        shift = -0.5 * self.dphi_deg if self.phi_centred else 0.0
        return np.arange(self.n_phi + 1) * self.dphi_deg + shift

    def theta_centres_deg(self):
        return (np.arange(self.n_theta) + 0.5) * self.dtheta_deg

    def phi_centres_deg(self):
        e = self.phi_edges_deg()
        return 0.5 * (e[:-1] + e[1:])

    def solid_angle(self):
        """(n_theta, n_phi) solid angle of each bin in sr: (cos theta_lo - cos theta_hi) dphi."""
        t = np.radians(self.theta_edges_deg())
        band = np.cos(t[:-1]) - np.cos(t[1:])
        return np.repeat(band[:, None], self.n_phi, axis=1) * np.radians(self.dphi_deg)

    def projected_solid_angle(self):
        """(n_theta, n_phi) integral of cos theta over each bin in sr: (sin^2 theta_hi - sin^2 theta_lo) / 2 dphi.
        The sum of f times it over a side is that side's directional albedo (f is a bin average of f)."""
        t = np.radians(self.theta_edges_deg())
        band = 0.5 * (np.sin(t[1:]) ** 2 - np.sin(t[:-1]) ** 2)
        return np.repeat(band[:, None], self.n_phi, axis=1) * np.radians(self.dphi_deg)

    def index(self, w):
        """(row, col) of the bins holding unit directions w (..., 3) of the reflection side, the light at phi = 0."""
        w = np.asarray(w, dtype=np.float64)
        theta = np.degrees(np.arccos(np.clip(np.abs(w[..., 2]), -1, 1)))
        phi = np.degrees(np.arctan2(w[..., 1], w[..., 0]))
        row = np.clip((theta / self.dtheta_deg).astype(np.int64), 0, self.n_theta - 1)
        shift = 0.5 if self.phi_centred else 0.0
        col = np.mod(np.floor(phi / self.dphi_deg + shift).astype(np.int64), self.n_phi)
        return row, col

    def subsample(self, n):
        """(n_theta, n_phi, n * n, 3) directions spread evenly in each bin's projected solid angle (n x n points,
        uniform in sin^2 theta and phi): the nodes of a bin's cos-weighted mean, the measure its f averages over."""
        te, pe = np.radians(self.theta_edges_deg()), np.radians(self.phi_edges_deg())
        s = (np.arange(n) + 0.5) / n
        s2 = np.sin(te[:-1, None]) ** 2 + s[None, :] * (np.sin(te[1:, None]) ** 2 - np.sin(te[:-1, None]) ** 2)
        st = np.sqrt(s2)[:, None, :, None]                                  # (n_theta, 1, n, 1)
        ph = (pe[:-1, None] + s[None, :] * np.radians(self.dphi_deg))[None, :, None, :]   # (1, n_phi, 1, n)
        ct = np.sqrt(np.maximum(0.0, 1 - st * st))
        x, y, z = np.broadcast_arrays(st * np.cos(ph), st * np.sin(ph), ct)
        return np.stack([x, y, z], axis=-1).reshape(self.n_theta, self.n_phi, n * n, 3)

    def directions(self):
        """(n_theta, n_phi, 3) unit vectors at the bins' centres, reflection side (z > 0); negate z for T."""
        t = np.radians(self.theta_centres_deg())[:, None]
        p = np.radians(self.phi_centres_deg())[None, :]
        return np.stack(np.broadcast_arrays(np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)), axis=-1)
