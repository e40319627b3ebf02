"""A model in any language, through files: the nodes `gonio nodes` writes, and the values `gonio score` reads.

    nodes = gonio.read_nodes("out/nodes")        # nodes.npy (or nodes.csv) and nodes.json of `gonio nodes`
    f = my_model(nodes.l, nodes.v)               # (n, 3): f in 1/sr, cosine excluded, one row per node
    gonio.write_values("out/values.npy", f)      # what `gonio score out/nodes --values out/values.npy` reads

Conventions (docs/PHYSICS.md): l and v point away from the surface, z is the stack normal, v.z < 0 on the
transmission side (side "T"); a bin's average of f over projected solid angle is the sum over its nodes of
weight x f, so the weights of one bin sum to 1.
"""
import csv
import json
import os
from dataclasses import dataclass

import numpy as np

from .outputs import FormatError

NODES_HEADER = ["theta_i", "side", "bin", "lx", "ly", "lz", "vx", "vy", "vz", "weight"]
NODES_FORMAT = 1   # nodes.json's gonio_nodes (kNodesFormat in host/cli/cmd_nodes.cpp)
SIDES = np.array(["R", "T"])   # nodes.npy's side column: 0 = R, 1 = T


@dataclass
class Nodes:
    """The nodes of one `gonio nodes` directory, one entry per row of nodes.csv, in its order."""
    theta_i: np.ndarray   # (n,) incident angle in degrees
    side: np.ndarray      # (n,) "R" or "T"
    bin: np.ndarray       # (n,) the bin's index within its side's grid (row-major: theta row, phi column)
    l: np.ndarray         # (n, 3) towards the light
    v: np.ndarray         # (n, 3) towards the viewer
    weight: np.ndarray    # (n,) quadrature weight; the nodes of one bin sum to 1
    meta: dict            # nodes.json: stack (TOML text), theta_i, dtheta, dphi, k, sides, nodes

    def __len__(self):
        return len(self.weight)

    def stack(self):
        """The stack the nodes were written for, nodes.json's TOML parsed (tomllib: Python >= 3.11)."""
        try:
            import tomllib
        except ImportError as e:
            raise ImportError("Nodes.stack() needs tomllib (Python >= 3.11)") from e
        return tomllib.loads(self.meta["stack"])


def _nodes_json(directory):
    path = os.path.join(directory, "nodes.json")
    with open(path) as fh:
        meta = json.load(fh)
    if meta.get("gonio_nodes") != NODES_FORMAT:
        raise FormatError(f"{path}: not a nodes.json of this gonio (gonio_nodes {NODES_FORMAT} expected)")
    return meta


def _table_from_npy(path):
    """nodes.npy: float64 (n, 10), the side as 0 / 1."""
    a = np.load(path)
    if a.ndim != 2 or a.shape[1] != len(NODES_HEADER):
        raise FormatError(f"{path}: shape {a.shape}, expected (nodes, {len(NODES_HEADER)})")
    return a[:, 0], SIDES[a[:, 1].astype(int)], a[:, 2].astype(np.int64), a[:, 3:10]


def _table_from_csv(path):
    """nodes.csv: the header, then one node a line, the side as R / T."""
    with open(path, newline="") as fh:
        reader = csv.reader(fh)
        header = next(reader, None)
        if header != NODES_HEADER:
            raise FormatError(f"{path}:1: expected the header {','.join(NODES_HEADER)}, got {header}")
        rows = list(reader)
    for line, row in enumerate(rows, start=2):
        if len(row) != len(NODES_HEADER) or row[1] not in ("R", "T"):
            raise FormatError(f"{path}:{line}: expected {len(NODES_HEADER)} fields with side R or T, got {row}")
    theta_i = np.array([float(r[0]) for r in rows])
    side = np.array([r[1] for r in rows])
    bins = np.array([int(r[2]) for r in rows], dtype=np.int64)
    return theta_i, side, bins, np.array([[float(x) for x in r[3:10]] for r in rows]).reshape(-1, 7)


def read_nodes(directory):
    """The nodes of a `gonio nodes --out DIR` directory: nodes.npy where it is there (exact float64), else
    nodes.csv; checked against nodes.json's node count."""
    meta = _nodes_json(directory)
    npy = os.path.join(directory, "nodes.npy")
    if os.path.exists(npy):
        theta_i, side, bins, lvw = _table_from_npy(npy)
    else:
        theta_i, side, bins, lvw = _table_from_csv(os.path.join(directory, "nodes.csv"))
    if len(theta_i) != meta["nodes"]:
        raise FormatError(f"{directory}: {len(theta_i)} nodes, nodes.json says {meta['nodes']}")
    return Nodes(theta_i, side, bins, lvw[:, 0:3], lvw[:, 3:6], lvw[:, 6], meta)


def _checked_values(rgb, nodes):
    """rgb as a float64 (n, 3) array, refused as `gonio score` refuses it: another shape, another row count than
    the nodes, or a value negative, NaN or infinite (nothing is clamped)."""
    rgb = np.asarray(rgb, dtype=np.float64)
    if rgb.ndim != 2 or rgb.shape[1] != 3:
        raise ValueError(f"values of shape {rgb.shape}: expected (nodes, 3), r, g, b per node")
    if nodes is not None and len(rgb) != len(nodes):
        raise ValueError(f"{len(rgb)} values for {len(nodes)} nodes (one row r, g, b per node, in their order)")
    bad = ~(np.isfinite(rgb) & (rgb >= 0)).all(axis=1)
    if bad.any():
        first = int(np.flatnonzero(bad)[0])
        raise ValueError(f"{int(bad.sum())} rows hold negative, NaN or infinite values, the first row {first} "
                         f"(from 0): {rgb[first]}; a BRDF is finite and non-negative")
    return rgb


def write_values(path, rgb, nodes=None):
    """f at each node, (n, 3) r, g, b, as `gonio score --values` reads it: .npy (numpy.save, float64) where path
    ends in .npy, else CSV with the header r,g,b and 17 significant digits (the same doubles). With nodes, the row
    count is checked against them."""
    rgb = _checked_values(rgb, nodes)
    if path.endswith(".npy"):
        np.save(path, np.ascontiguousarray(rgb))   # np.save would add .npy to any other name
        return
    with open(path, "w", newline="") as fh:
        fh.write("r,g,b\n")
        for r, g, b in rgb:
            fh.write(f"{r:.17g},{g:.17g},{b:.17g}\n")
