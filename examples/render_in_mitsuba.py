#!/usr/bin/env python3
"""Render gonio's reference in a real renderer: a table (gonio simulate over incident angles 0 to 88 degrees)
exported as an RGL .bsdf file (python/gonio/rgl.py) on a unit sphere in Mitsuba 3 (scalar_rgb, the `measured`
plugin), seen by an orthographic camera along the z axis, under an environment.

usage: render_in_mitsuba.py TABLE_DIR --out DIR [--env furnace|FILE.exr] [--size N] [--spp S] [--seed K]

  furnace   uniform white light of radiance 1: every pixel is the directional albedo at its view angle
            (the cosine between the sphere's normal and the camera), a check of the whole chain
  FILE.exr  an equirectangular environment map (for example Debian's blender-data:
            /usr/share/blender/datafiles/studiolights/world/forest.exr)
Writes DIR/reference.bsdf, DIR/reference.exr (RGB float), DIR/reference.png (clipped sRGB) and DIR/render.json.
Needs numpy and mitsuba (pip install mitsuba).
"""
import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import gonio  # noqa: E402
from gonio import rgl  # noqa: E402


def render(table_dir, out, env="furnace", size=128, spp=64, seed=0):
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    os.makedirs(out, exist_ok=True)
    run = gonio.read_run(table_dir)
    bsdf_path = os.path.join(out, "reference.bsdf")
    rgl.export_rgl(run, bsdf_path)
    emitter = {"type": "constant", "radiance": {"type": "rgb", "value": 1.0}} if env == "furnace" else \
        {"type": "envmap", "filename": env}
    scene = mi.load_dict({
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 2},   # the environment seen through one reflection
        "sensor": {
            "type": "orthographic",
            "to_world": mi.ScalarTransform4f().look_at(origin=[0, 0, 3], target=[0, 0, 0], up=[0, 1, 0]),
            "film": {"type": "hdrfilm", "width": size, "height": size, "rfilter": {"type": "box"},
                     "pixel_format": "rgb"},
            "sampler": {"type": "independent", "sample_count": spp, "seed": seed},
        },
        "sphere": {"type": "sphere", "bsdf": {"type": "measured", "filename": bsdf_path}},
        "light": emitter,
    })
    image = np.array(mi.render(scene, seed=seed))
    mi.util.write_bitmap(os.path.join(out, "reference.exr"), image, write_async=False)
    mi.util.write_bitmap(os.path.join(out, "reference.png"), np.clip(image, 0, 1), write_async=False)
    # pixel centres: the sphere's normal there and the view angle (the camera looks along -z)
    c = (np.arange(size) + 0.5) / size * 2 - 1
    x, y = np.meshgrid(c, -c)
    r2 = x * x + y * y
    info = {"table": os.path.abspath(table_dir), "env": env, "size": size, "spp": spp, "seed": seed,
            "mean_on_sphere": image[r2 < 1].mean(axis=0).tolist()}
    with open(os.path.join(out, "render.json"), "w") as fh:
        json.dump(info, fh, indent=1)
    return image, np.degrees(np.arcsin(np.sqrt(np.minimum(r2, 1.0)))), r2 < 1


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("table_dir")
    ap.add_argument("--out", required=True)
    ap.add_argument("--env", default="furnace")
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args()
    render(a.table_dir, a.out, a.env, a.size, a.spp, a.seed)
    print(f"wrote {a.out}/reference.exr, reference.png, render.json")


if __name__ == "__main__":
    main()
