"""Readers for what gonio writes: summary.json, slices.csv, sweep.csv and the multi-part EXR."""
import csv
import json
import math
import os
from dataclasses import dataclass, field

import numpy as np

from .bins import Bins

SLICES_HEADER = ["source", "theta_i", "side", "theta_lo", "theta_hi", "phi_lo", "phi_hi",
                 "r", "g", "b", "se_r", "se_g", "se_b"]
# a run at an incident azimuth other than 0 (simulate --phi-i): a phi_i column after theta_i, one value in the file
SLICES_HEADER_AZIMUTH = SLICES_HEADER[:2] + ["phi_i"] + SLICES_HEADER[2:]


class FormatError(ValueError):
    """A file that is not what gonio writes: the message names the file and the line."""


def read_summary(path):
    """summary.json (a file or an output directory) as a dict; null numbers (non-finite) become nan."""
    if os.path.isdir(path):
        path = os.path.join(path, "summary.json")
    with open(path) as fh:
        try:
            summary = json.load(fh, parse_constant=lambda c: math.nan)
        except json.JSONDecodeError as e:   # a truncated or edited file: its place, not a traceback
            raise FormatError(f"{path}:{e.lineno}: not a summary.json gonio wrote: {e.msg} (column {e.colno})")
    if not isinstance(summary, dict):
        raise FormatError(f"{path}:1: not a summary.json gonio wrote: a JSON object expected")
    return summary


@dataclass
class Run:
    """A simulate / compare output: the summary, and each slice's f and se as (n_theta, n_phi, 3) arrays."""
    summary: dict
    bins: Bins
    values: dict = field(default_factory=dict)   # (source, theta_i, side) -> (n_theta, n_phi, 6): r g b se_r se_g se_b
    core: object = field(default=None, repr=False, compare=False)   # a run made in this process (gonio.simulate)

    def save(self, directory):
        """A run made in this process (gonio.simulate, gonio.compare): its files written to directory, the bytes
        `gonio simulate` / `gonio compare --out DIRECTORY` write (the EXR, slices.csv, summary.json, state.gonio)."""
        if self.core is None:
            raise ValueError("this run was read from files: it has them already")
        self.core.save(str(directory))

    @property
    def theta_i(self):
        """The run's incident angles in degrees, in its order."""
        return [float(a["theta_i"]) for a in self.summary.get("angles", [])]

    @property
    def phi_i(self):
        """The run's incident azimuth in degrees (summary.json's phi_i per angle; 0, the plane of incidence, where
        it has none)."""
        return float(self.summary.get("angles", [{}])[0].get("phi_i", 0.0)) if self.summary.get("angles") else 0.0

    def keys(self):
        return list(self.values)

    def sources(self):
        return list(dict.fromkeys(k[0] for k in self.values))

    def f(self, source, theta_i, side="R"):
        return self.values[(source, float(theta_i), side)][..., :3]

    def se(self, source, theta_i, side="R"):
        return self.values[(source, float(theta_i), side)][..., 3:]

    def albedo(self, source, theta_i, side="R"):
        """RGB directional albedo of one side: the sum of f times the bins' projected solid angles."""
        return (self.f(source, theta_i, side) * self.bins.projected_solid_angle()[..., None]).sum(axis=(0, 1))


def read_slices(path, bins):
    """slices.csv (a file or an output directory) -> {(source, theta_i, side): (n_theta, n_phi, 6)}."""
    if os.path.isdir(path):
        path = os.path.join(path, "slices.csv")
    with open(path, newline="") as fh:
        return parse_slices(fh, bins, path)


def parse_slices(lines, bins, name="slices.csv"):
    """slices.csv's text (an iterable of its lines: a file, io.StringIO) -> {(source, theta_i, side): (n_theta,
    n_phi, 6)}; `name` is the file the messages name."""
    rows = {}
    reader = csv.reader(lines)
    header = next(reader, None)
    if header not in (SLICES_HEADER, SLICES_HEADER_AZIMUTH):
        raise FormatError(f"{name}:1: expected the header {','.join(SLICES_HEADER)} (or with phi_i after "
                          f"theta_i), got {header}")
    azimuth = header == SLICES_HEADER_AZIMUTH
    phi_i = None
    for line, row in enumerate(reader, start=2):
        if len(row) != len(header):
            raise FormatError(f"{name}:{line}: expected {len(header)} fields, got {len(row)}")
        if azimuth:   # one azimuth in the file: the keys stay (source, theta_i, side)
            if phi_i is not None and row[2] != phi_i:
                raise FormatError(f"{name}:{line}: phi_i {row[2]}, the file's earlier rows {phi_i}")
            phi_i = row[2]
            row = row[:2] + row[3:]
        try:
            key = (row[0], float(row[1]), row[2])
            rows.setdefault(key, []).append([float(x) for x in row[7:13]])
        except ValueError as e:
            raise FormatError(f"{name}:{line}: expected numbers in theta_i and r to se_b: {e}")
    out = {}
    for key, vals in rows.items():
        if len(vals) != bins.n_theta * bins.n_phi:
            raise FormatError(f"{name}: {key} has {len(vals)} bins, expected {bins.n_theta} x {bins.n_phi}")
        out[key] = np.asarray(vals, dtype=np.float64).reshape(bins.n_theta, bins.n_phi, 6)
    return out


def read_run(directory):
    """summary.json and slices.csv of one output directory; of a spectral run (simulate --spectral), its bins' linear
    sRGB from its EXR (SpectralRun.as_rgb_run)."""
    summary = read_summary(directory)
    if "spectral" in summary:
        from .spectral import read_spectral_run   # spectral.py reads through this module
        return read_spectral_run(directory).as_rgb_run()
    try:
        bins = Bins.from_summary(summary)
    except (KeyError, TypeError, ValueError) as e:
        raise FormatError(f"{directory}: summary.json has no usable bins (dtheta_deg, dphi_deg, n_theta, n_phi): "
                          f"{e!r}")
    return Run(summary, bins, read_slices(directory, bins))


def read_sweep(path):
    """sweep.csv (a file or a sweep output directory) -> (header, rows as a list of dicts, numbers as float)."""
    if os.path.isdir(path):
        path = os.path.join(path, "sweep.csv")
    with open(path, newline="") as fh:
        reader = csv.reader(fh)
        header = next(reader)
        rows = []
        for row in reader:
            d = {}
            for h, v in zip(header, row):
                try:
                    d[h] = float(v)
                except ValueError:
                    d[h] = v
            rows.append(d)
    return header, rows


def read_exr(path):
    """The multi-part EXR -> {part name: {channel: (n_theta, n_phi) float32}}, plus each part's gonio_* header
    attributes under the key "header". Needs OpenEXR >= 3.2 (pip install OpenEXR)."""
    try:
        import OpenEXR
    except ImportError as e:
        raise ImportError("gonio.read_exr needs the OpenEXR package (pip install 'OpenEXR>=3.2')") from e
    out = {}
    with OpenEXR.File(path, separate_channels=True) as f:
        for part in f.parts:
            chans = {name: np.asarray(c.pixels) for name, c in part.channels.items()}
            chans["header"] = {k: v for k, v in part.header.items() if str(k).startswith("gonio_")}
            out[part.name()] = chans
    return out
