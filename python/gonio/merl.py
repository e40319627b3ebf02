"""The MERL BRDF format (Matusik et al. 2003, "A data-driven reflectance model"): an isotropic BRDF tabulated in
Rusinkiewicz's half/difference angles, read by BRDF Explorer, libbsdf, Mitsuba plugins and many renderers.

File layout: three int32 (n_theta_h = 90, n_theta_d = 90, n_phi_d = 180), then 3 n float64, n = 90 x 90 x 180,
red block, green block, blue block; entry (i_h, i_d, i_p) at i_p + 180 (i_d + 90 i_h). A value is f / scale with
scale = 1/1500, 1.15/1500, 1.66/1500 for R, G, B; negative values mean "no data".
Cells: the readers' index functions put (theta_h, theta_d, phi_d) in cell (floor(90 sqrt(theta_h / (pi/2))),
floor(90 theta_d / (pi/2)), floor(180 phi_d / pi)) (the grid is dense near the specular peak; phi_d and
phi_d + pi are one pair for a reciprocal BRDF); a cell holds the value at its centre in these index coordinates.
"""
import struct

import numpy as np

N_THETA_H, N_THETA_D, N_PHI_D = 90, 90, 180
SCALE = np.array([1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0])


def cell_angles():
    """(theta_h, theta_d, phi_d) in radians of every cell's centre, each (90, 90, 180)."""
    th = ((np.arange(N_THETA_H) + 0.5) / N_THETA_H) ** 2 * (np.pi / 2)
    td = (np.arange(N_THETA_D) + 0.5) * (np.pi / 2) / N_THETA_D
    pd = (np.arange(N_PHI_D) + 0.5) * np.pi / N_PHI_D
    return np.meshgrid(th, td, pd, indexing="ij")


def half_diff_to_directions(theta_h, theta_d, phi_d):
    """Rusinkiewicz 1998: the half vector at (theta_h, phi_h = 0), the difference vector at (theta_d, phi_d) in
    the half vector's frame; returns (wi, wo), both (..., 3), z the normal, pointing away from the surface."""
    d = np.stack([np.sin(theta_d) * np.cos(phi_d), np.sin(theta_d) * np.sin(phi_d), np.cos(theta_d)], axis=-1)
    # rotate d by theta_h about y (phi_h = 0: no rotation about z)
    c, s = np.cos(theta_h), np.sin(theta_h)
    wi = np.stack([c * d[..., 0] + s * d[..., 2], d[..., 1], -s * d[..., 0] + c * d[..., 2]], axis=-1)
    h = np.stack([s, np.zeros_like(s), c], axis=-1)
    wo = 2 * np.sum(wi * h, axis=-1, keepdims=True) * h - wi
    return wi, wo


def write(path, values):
    """values: (3, 90, 90, 180) f in 1/sr, nan where there is no data (written as -1)."""
    v = np.asarray(values, dtype=np.float64)
    if v.shape != (3, N_THETA_H, N_THETA_D, N_PHI_D):
        raise ValueError(f"MERL values must be (3, 90, 90, 180), got {v.shape}")
    out = np.where(np.isfinite(v), v / SCALE[:, None, None, None], -1.0)
    with open(path, "wb") as fh:
        fh.write(struct.pack("<3i", N_THETA_H, N_THETA_D, N_PHI_D))
        fh.write(out.astype("<f8").tobytes())


def read(path):
    """(3, 90, 90, 180) f in 1/sr, nan where the file says "no data"."""
    with open(path, "rb") as fh:
        dims = struct.unpack("<3i", fh.read(12))
        if dims != (N_THETA_H, N_THETA_D, N_PHI_D):
            raise ValueError(f"{path}: MERL dimensions {dims}, expected (90, 90, 180)")
        raw = np.frombuffer(fh.read(), dtype="<f8")
    if raw.size != 3 * N_THETA_H * N_THETA_D * N_PHI_D:
        raise ValueError(f"{path}: {raw.size} values, expected {3 * N_THETA_H * N_THETA_D * N_PHI_D}")
    v = raw.reshape(3, N_THETA_H, N_THETA_D, N_PHI_D) * SCALE[:, None, None, None]
    return np.where(v < 0, np.nan, v)
