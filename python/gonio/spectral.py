"""Readers for gonio's spectral outputs (docs/SPECTRAL.md): `gonio simulate --spectral` and
`gonio compare --rgb-vs-spectral`."""
import csv
import os
from dataclasses import dataclass

import numpy as np

from .bins import Bins
from .outputs import FormatError, Run, read_exr, read_summary

# IEC 61966-2-1's XYZ (D65) to linear sRGB, as host/spectral/spectral_bands.cpp applies it
XYZ_TO_LINEAR_SRGB = np.array([[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]])

COLOUR_ERROR_HEADER = ["theta_i", "side", "theta_lo", "theta_hi", "phi_lo", "phi_hi", "X_spectral", "Y_spectral",
                       "Z_spectral", "X_rgb", "Y_rgb", "Z_rgb", "de2000", "de_itp", "de2000_noise", "lit"]


@dataclass
class SpectralRun:
    """A `simulate --spectral` output: its summary.json and its EXR's parts ({"theta_i=30 R": {channel: array}})."""
    summary: dict
    parts: dict

    @property
    def wavelength_nm(self):
        return np.asarray(self.summary["angles"][0]["spectral"]["wavelength_nm"], dtype=np.float64)

    def _part(self, theta_i, side):
        name = f"theta_i={float(theta_i):g} {side}"
        if name not in self.parts:
            raise KeyError(f"no part '{name}'; parts: {', '.join(self.parts)}")
        return self.parts[name]

    def bands(self, theta_i, side="R"):
        """(n_theta, n_phi, n_bands): each band's bin average of f (1/sr), bands in wavelength order."""
        p = self._part(theta_i, side)
        return np.stack([p[f"band.{nm:g}"] for nm in self.wavelength_nm], axis=-1)

    def bands_se(self, theta_i, side="R"):
        p = self._part(theta_i, side)
        return np.stack([p[f"se.band.{nm:g}"] for nm in self.wavelength_nm], axis=-1)

    def xyz(self, theta_i, side="R"):
        """(n_theta, n_phi, 3): the bins in CIE 1931 XYZ under D65 (1/sr; a white diffuser's pi f has Y = 1)."""
        p = self._part(theta_i, side)
        return np.stack([p["X"], p["Y"], p["Z"]], axis=-1)

    def srgb(self, theta_i, side="R"):
        p = self._part(theta_i, side)
        return np.stack([p["R"], p["G"], p["B"]], axis=-1)

    def as_rgb_run(self):
        """The run's RGB table, as `read_run` gives a simulate output: source "reference", each slice's linear sRGB
        (D65) and its se bounded by |M| se_XYZ (M: IEC 61966-2-1's XYZ to linear sRGB; the XYZ se are upper bounds
        already). What `gonio export` writes for a spectral run."""
        values = {}
        for name, p in self.parts.items():
            theta, side = name[len("theta_i="):].split(" ")
            se_xyz = np.stack([p["se.X"], p["se.Y"], p["se.Z"]], axis=-1)
            se = se_xyz @ np.abs(XYZ_TO_LINEAR_SRGB).T
            values[("reference", float(theta), side)] = np.concatenate([self.srgb(float(theta), side), se], axis=-1)
        return Run(self.summary, Bins.from_summary(self.summary), values)


def read_spectral_run(directory):
    """summary.json and the EXR of a `simulate --spectral` output directory (needs OpenEXR)."""
    summary = read_summary(directory)
    if "spectral" not in summary:
        raise FormatError(f"{directory}/summary.json: not a spectral run (no 'spectral' key)")
    exrs = [f for f in os.listdir(directory) if f.endswith(".exr")]
    if len(exrs) != 1:
        raise FormatError(f"{directory}: expected one .exr, found {exrs}")
    return SpectralRun(summary, read_exr(os.path.join(directory, exrs[0])))


def read_colour_error(directory):
    """A `compare --rgb-vs-spectral` output: (rgb-vs-spectral.json as a dict, rgb-vs-spectral.csv as a dict of numpy
    columns; side as strings 'R' / 'T', lit as bool)."""
    summary = read_summary(os.path.join(directory, "rgb-vs-spectral.json"))
    path = os.path.join(directory, "rgb-vs-spectral.csv")
    with open(path, newline="") as fh:
        reader = csv.reader(fh)
        header = next(reader, None)
        if header != COLOUR_ERROR_HEADER:
            raise FormatError(f"{path}:1: expected the header {','.join(COLOUR_ERROR_HEADER)}, got {header}")
        rows = list(reader)
    cols = {}
    for i, name in enumerate(COLOUR_ERROR_HEADER):
        vals = [r[i] for r in rows]
        if name == "side":
            cols[name] = np.asarray(vals)
        elif name == "lit":
            cols[name] = np.asarray([v == "1" for v in vals])
        else:
            cols[name] = np.asarray(vals, dtype=np.float64)
    return summary, cols
