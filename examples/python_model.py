#!/usr/bin/env python3
"""A model in Python, scored by gonio through files (gonio nodes / gonio score).

    gonio simulate stacks/plastic.toml --theta-i 0,45 --dtheta 5 --dphi 10 --out out/ref
    gonio nodes stacks/plastic.toml --theta-i 0,45 --dtheta 5 --dphi 10 --out out/nodes
    python3 examples/python_model.py out/nodes out/nodes/values.csv
    gonio score out/nodes --values out/nodes/values.csv --id lambert-under-fresnel --reference out/ref --out out/mine

The model: the plastic's Lambertian base (albedo [0.2, 0.6, 0.3]) seen through a smooth coat of index 1.5 without
absorption or inter-reflections, f = albedo / pi (1 - F(l)) (1 - F(v)), plus nothing for the coat's own specular
reflection (a delta the bins would hold at the mirror direction): a deliberately simple model, to see how far off
it is. Conventions (gonio's): directions away from the surface, z the normal, f in 1/sr without the cosine; one
row r,g,b per node, in their order. The files are read and written by python/gonio (read_nodes, write_values);
the values file is CSV, or .npy where its name ends in .npy.
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import gonio  # noqa: E402  (python/gonio: gonio's files as arrays)

ALBEDO = np.array([0.2, 0.6, 0.3])
ETA = 1.5


def fresnel_dielectric(cos_i, eta):
    """Unpolarised Fresnel reflectance from outside (index 1) into index eta, for an array of cosines."""
    sin_t2 = (1.0 - cos_i * cos_i) / (eta * eta)
    cos_t = np.sqrt(np.maximum(1.0 - sin_t2, 0.0))
    rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
    rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
    return np.where(sin_t2 >= 1.0, 1.0, 0.5 * (rs * rs + rp * rp))


def lambert_under_fresnel(nodes):
    """(n, 3) f: the base's albedo / pi through the coat's two Fresnel transmissions; 0 on the transmission side."""
    lz, vz = nodes.l[:, 2], nodes.v[:, 2]
    lit = (nodes.side == "R") & (vz > 0.0)
    t = (1.0 - fresnel_dielectric(lz, ETA)) * (1.0 - fresnel_dielectric(np.where(lit, vz, 1.0), ETA))
    return np.where(lit[:, None], ALBEDO[None, :] / np.pi * t[:, None], 0.0)


def main(nodes_dir, values_path):
    nodes = gonio.read_nodes(nodes_dir)
    gonio.write_values(values_path, lambert_under_fresnel(nodes), nodes)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: python_model.py NODES_DIR VALUES.csv|VALUES.npy")
    main(sys.argv[1], sys.argv[2])
