#!/usr/bin/env python3
"""A model in Python, scored by gonio through files (gonio nodes / gonio score).

    gonio simulate stacks/plastic.toml --theta-i 0,45 --dtheta 5 --dphi 10 --out out/ref
    gonio nodes stacks/plastic.toml --theta-i 0,45 --dtheta 5 --dphi 10 --out out/nodes
    python3 examples/python_model.py out/nodes/nodes.csv > out/nodes/values.csv
    gonio score out/nodes --values out/nodes/values.csv --id lambert-under-fresnel --reference out/ref --out out/mine

The model: the plastic's Lambertian base (albedo [0.2, 0.6, 0.3]) seen through a smooth coat of index 1.5 without
absorption or inter-reflections, f = albedo / pi (1 - F(l)) (1 - F(v)), plus nothing for the coat's own specular
reflection (a delta the bins would hold at the mirror direction): a deliberately simple model, to see how far off
it is. Conventions (gonio's): directions away from the surface, z the normal, f in 1/sr without the cosine; one
output row r,g,b per row of nodes.csv, in its order. Only the standard library.
"""
import csv
import math
import sys

ALBEDO = (0.2, 0.6, 0.3)
ETA = 1.5


def fresnel_dielectric(cos_i, eta):
    """Unpolarised Fresnel reflectance from outside (index 1) into index eta."""
    sin_t2 = (1.0 - cos_i * cos_i) / (eta * eta)
    if sin_t2 >= 1.0:
        return 1.0
    cos_t = math.sqrt(1.0 - sin_t2)
    rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
    rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
    return 0.5 * (rs * rs + rp * rp)


def main(nodes_csv):
    out = csv.writer(sys.stdout, lineterminator="\n")
    out.writerow(["r", "g", "b"])
    with open(nodes_csv, newline="") as fh:
        for row in csv.DictReader(fh):
            lz, vz = float(row["lz"]), float(row["vz"])
            if row["side"] != "R" or vz <= 0.0:
                out.writerow([0, 0, 0])
                continue
            t = (1.0 - fresnel_dielectric(lz, ETA)) * (1.0 - fresnel_dielectric(vz, ETA))
            out.writerow([f"{a / math.pi * t:.9g}" for a in ALBEDO])


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: python_model.py NODES.csv > values.csv")
    main(sys.argv[1])
