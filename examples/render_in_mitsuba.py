#!/usr/bin/env python3
"""Render gonio's reference in a real renderer: a table (gonio simulate over incident angles 0 to 88 degrees)
exported as an RGL .bsdf file (python/gonio/rgl.py) on a unit sphere in Mitsuba 3 (scalar_rgb, the `measured`
plugin), seen by an orthographic camera along the z axis, under an environment, and put beside gonio's own render.

usage: render_in_mitsuba.py TABLE_DIR --out DIR [--env NAME|FILE.exr] [--beside GONIO_RENDER_DIR]
                            [--size N] [--spp S] [--seed K]

  --env      the light, named as `gonio render --env` names it (docs/RENDER.md):
             furnace   uniform radiance 1: every pixel is the directional albedo at its view angle
             studio    gonio's procedural studio (three disc lights over a dim gradient), rebuilt here
             city, courtyard, forest, interior, night, sunrise, sunset
                       Debian blender-data's /usr/share/blender/datafiles/studiolights/world/NAME.exr
             FILE.exr  an equirectangular map in gonio's convention (z up, u = phi / 2pi, row 0 the zenith)
             Negative and non-finite texels are set to 0, as gonio does, before Mitsuba sees the map.
  --beside   the output directory of `gonio render STACK --env ENV --reference TABLE_DIR ...`: the Mitsuba
             render is made at its size under its environment (read from its render.json; a different --env is
             refused, exit 2) and written beside its reference.exr: DIR/mitsuba.exr, DIR/beside.png (gonio |
             Mitsuba | their signed difference) and DIR/beside.json (relative L1 and HDR-FLIP between the two over the sphere,
             beside gonio's floor between its halves and Mitsuba's between two halves of its samples).
Without --beside: writes DIR/reference.bsdf, DIR/reference.exr (RGB float), DIR/reference.png (clipped sRGB) and
DIR/render.json.
Needs numpy and mitsuba (pip install mitsuba); --beside's FLIP needs flip-evaluator, its PNG matplotlib.
"""
import argparse
import json
import math
import os
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import gonio  # noqa: E402
from gonio import rgl  # noqa: E402

BLENDER_WORLD_DIR = "/usr/share/blender/datafiles/studiolights/world"
BLENDER_NAMES = ["city", "courtyard", "forest", "interior", "night", "sunrise", "sunset"]

# gonio's environment is z up, u = phi / 2pi with phi = atan2(y, x), v = theta / pi from +z. Mitsuba's envmap
# looks a direction d up in its local frame l = to_world^-1 d as u = atan2(l.x, -l.z) / 2pi, v = acos(l.y) / pi
# (y up, u = 0 towards -z). Both agree when l = (d.y, d.z, -d.x): then acos(l.y) = theta and
# atan2(l.x, -l.z) = atan2(d.y, d.x) = phi. to_world maps l back to d = (-l.z, l.x, l.y).
GONIO_TO_MITSUBA_ENV = [[0, 0, -1, 0],
                        [1, 0, 0, 0],
                        [0, 1, 0, 0],
                        [0, 0, 0, 1]]


class EnvError(ValueError):
    """An --env that cannot be used (unknown name, missing file, a mismatch with --beside's): exit 2."""


def studio_map():
    """gonio's procedural studio (host/render/environment.cpp, studio_environment), 512 x 256: 0.05 + 0.10 z
    above the horizon, 0.02 below, and three discs (key, fill, rim) of constant radiance."""
    W, H = 512, 256
    th = np.pi * (np.arange(H) + 0.5) / H
    ph = 2 * np.pi * (np.arange(W) + 0.5) / W
    th, ph = np.meshgrid(th, ph, indexing="ij")
    w = np.stack([np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)], axis=-1)
    L = np.where(w[..., 2:] > 0, 0.05 + 0.10 * w[..., 2:], 0.02) * np.ones(3)
    for theta, phi, radius, rad in [(35, 30, 12, (6.0, 5.7, 5.2)), (55, 200, 20, (1.2, 1.3, 1.5)),
                                    (78, 110, 8, (4.0, 4.0, 4.0))]:
        t, p = math.radians(theta), math.radians(phi)
        c = np.array([math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)])
        L[w @ c > math.cos(math.radians(radius))] = rad
    return L.astype(np.float32)


def environment_source(env):
    """The file an --env name stands for (None for the procedural furnace and studio); EnvError if unusable."""
    if env in ("furnace", "studio"):
        return None
    if env in BLENDER_NAMES:
        path = os.path.join(BLENDER_WORLD_DIR, env + ".exr")
        if not os.path.exists(path):
            raise EnvError(f"--env {env}: {path} is missing (Debian: apt-get install blender-data)")
        return path
    if "/" not in env and "." not in env:
        raise EnvError(f"--env {env}: no such environment; valid: furnace, studio, {', '.join(BLENDER_NAMES)}, "
                       "or an EXR file")
    if not os.path.isfile(env):
        raise EnvError(f"--env {env}: no such file")
    return env


def environment_map(env):
    """The map gonio renders under for --env (H x W x 3 float32, negative and non-finite texels set to 0, as
    gonio does), or None for the furnace."""
    import mitsuba as mi
    source = environment_source(env)
    if env == "furnace":
        return None
    if env == "studio":
        return studio_map()
    texels = np.array(mi.Bitmap(source), dtype=np.float32)[..., :3]
    return np.where(np.isfinite(texels), np.maximum(texels, 0), 0).astype(np.float32)


def emitter(env, tmp):
    """Mitsuba's emitter for --env: a constant for the furnace, else the clamped map written to tmp as an EXR and
    turned from gonio's z-up frame into Mitsuba's y-up one."""
    import mitsuba as mi
    texels = environment_map(env)
    if texels is None:
        return {"type": "constant", "radiance": {"type": "rgb", "value": 1.0}}
    path = os.path.join(tmp, "environment.exr")
    mi.Bitmap(np.ascontiguousarray(texels)).write(path)
    return {"type": "envmap", "filename": path, "to_world": mi.ScalarTransform4f(GONIO_TO_MITSUBA_ENV)}


def mitsuba_image(bsdf_path, env, size, spp, seed):
    """The sphere in Mitsuba: orthographic camera from +z (row 0 at +y, the left column at -x, as gonio's),
    the measured BSDF, the environment seen through one reflection (path tracer, depth 2, MIS) and hidden behind
    the sphere (gonio's background is 0). A pixel is the mean over its samples that hit the sphere (RGB / alpha):
    the radiance of the sphere's part of the pixel, not darkened at the rim by the pixel's coverage."""
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    with tempfile.TemporaryDirectory() as tmp:
        scene = mi.load_dict({
            "type": "scene",
            "integrator": {"type": "path", "max_depth": 2, "hide_emitters": True},
            "sensor": {
                "type": "orthographic",
                "to_world": mi.ScalarTransform4f().look_at(origin=[0, 0, 3], target=[0, 0, 0], up=[0, 1, 0]),
                "film": {"type": "hdrfilm", "width": size, "height": size, "rfilter": {"type": "box"},
                         "pixel_format": "rgba"},
                "sampler": {"type": "independent", "sample_count": spp, "seed": seed},
            },
            "sphere": {"type": "sphere", "bsdf": {"type": "measured", "filename": bsdf_path}},
            "light": emitter(env, tmp),
        })
        rgba = np.array(mi.render(scene, seed=seed), dtype=np.float32)
    alpha = rgba[..., 3:]
    return np.where(alpha > 0, rgba[..., :3] / np.maximum(alpha, 1e-12), 0).astype(np.float32)


def sphere_pixels(size):
    """The view angle (degrees) at each pixel centre and the sphere's mask (docs/RENDER.md's camera)."""
    c = (np.arange(size) + 0.5) / size * 2 - 1
    x, y = np.meshgrid(c, -c)
    r2 = x * x + y * y
    return np.degrees(np.arcsin(np.sqrt(np.minimum(r2, 1.0)))), r2 < 1


def render(table_dir, out, env="furnace", size=128, spp=64, seed=0):
    """The table's sphere in Mitsuba under env; writes OUT/reference.{bsdf,exr,png}, render.json. Returns the
    image (size x size x 3), the view angle per pixel and the sphere's mask."""
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    os.makedirs(out, exist_ok=True)
    environment_source(env)              # refuse a bad --env before exporting anything
    bsdf_path = os.path.join(out, "reference.bsdf")
    rgl.export_rgl(gonio.read_run(table_dir), bsdf_path)
    start = time.time()
    image = mitsuba_image(bsdf_path, env, size, spp, seed)
    seconds = time.time() - start
    mi.util.write_bitmap(os.path.join(out, "reference.exr"), image, write_async=False)
    mi.util.write_bitmap(os.path.join(out, "reference.png"), np.clip(image, 0, 1), write_async=False)
    view, on = sphere_pixels(size)
    info = {"table": os.path.abspath(table_dir), "env": env, "size": size, "spp": spp, "seed": seed,
            "render_seconds": seconds, "mean_on_sphere": image[on].mean(axis=0).tolist()}
    with open(os.path.join(out, "render.json"), "w") as fh:
        json.dump(info, fh, indent=1)
    return image, view, on


def relative_l1(a, b, mask):
    """sum |a - b| / sum |b| over the mask's pixels and the three channels (gonio's relative_l1, image.cpp)."""
    return float(np.abs(a[mask, :3] - b[mask, :3]).sum() / np.abs(b[mask, :3]).sum())


def flip_mean(ref, test, mask):
    """HDR-FLIP's mean over the mask (flip_evaluator, as tools/render_report.py), or a note without it."""
    try:
        import flip_evaluator as flip
    except ImportError as e:
        return f"not computed: {e} (pip install flip-evaluator)"
    r = np.ascontiguousarray(np.clip(ref[..., :3], 0, None), dtype=np.float32)
    t = np.ascontiguousarray(np.clip(test[..., :3], 0, None), dtype=np.float32)
    err = np.asarray(flip.evaluate(r, t, "HDR")[0], dtype=np.float64)
    return float((err[..., 0] if err.ndim == 3 else err)[mask].mean())


def read_exr(path):
    """An EXR's pixels as float32 (H x W x channels), through Mitsuba's reader."""
    import mitsuba as mi
    return np.array(mi.Bitmap(path), dtype=np.float32)


def tone_map(img, exposure):
    """gonio render's PNG curve: exposure x, x / (1 + x), sRGB, 8 bits."""
    x = np.clip(img[..., :3] * exposure, 0, None)
    x = x / (1 + x)
    s = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    return (np.clip(s, 0, 1) * 255 + 0.5).astype(np.uint8)


def difference_png(diff, scale):
    """The luminance of a signed difference: red above, blue below, full at scale (as gonio's diff-MODEL.png)."""
    y = np.clip((diff[..., :3] @ rgl.LUMA) / scale, -1, 1)
    out = np.zeros(diff.shape[:2] + (3,))
    out[..., 0] = np.maximum(y, 0)
    out[..., 2] = np.maximum(-y, 0)
    return (out * 255 + 0.5).astype(np.uint8)


def write_beside_png(path, ref, mine, tone):
    """gonio's reference | Mitsuba's | Mitsuba - gonio, side by side with a 2-pixel gap."""
    import matplotlib.image
    gap = np.full((ref.shape[0], 2, 3), 255, np.uint8)
    strip = np.concatenate([tone_map(ref, tone["exposure"]), gap, tone_map(mine, tone["exposure"]), gap,
                            difference_png(mine - ref[..., :3], tone["difference_png_scale"])], axis=1)
    matplotlib.image.imsave(path, strip)


def env_of(environment):
    """The --env that names a gonio render's environment here (render.json's `environment`): its name for the
    furnace, the studio and Blender's maps, else the file it read."""
    name = environment["name"]
    return name if name in ["furnace", "studio"] + BLENDER_NAMES else environment["source"]


def beside(table_dir, gonio_dir, out, env=None, spp=64, seed=0, bsdf_path=None):
    """Mitsuba's render of the table under gonio_dir's environment at its size, beside gonio's reference.exr:
    writes OUT/beside.png, OUT/mitsuba.exr and OUT/beside.json and returns the latter's dict. env, when given,
    must be the one gonio_dir was rendered under (EnvError otherwise); bsdf_path, an RGL file already exported
    from table_dir, saves the export (reading a table of 45 angles and exporting it take about 10 s)."""
    with open(os.path.join(gonio_dir, "render.json")) as fh:
        rj = json.load(fh)
    used, source = env_of(rj["environment"]), rj["environment"]["source"]
    same_file = source != "procedural" and os.path.abspath(env or "") == os.path.abspath(source)
    if env is not None and env != used and not same_file:
        raise EnvError(f"--env {env}, but {gonio_dir} was rendered under {used} ({rj['environment']['source']}); "
                       "drop --env or render gonio under the same one")
    ref = read_exr(os.path.join(gonio_dir, "reference.exr"))
    size = ref.shape[0]
    on = ref[..., 3] > 0
    below_80 = on & (sphere_pixels(size)[0] < 80)
    os.makedirs(out, exist_ok=True)
    if bsdf_path is None:
        bsdf_path = os.path.join(out, "reference.bsdf")
        rgl.export_rgl(gonio.read_run(table_dir), bsdf_path)
    # Mitsuba's own floor: two halves of its samples, other seeds; its image is their mean
    half_spp = max(spp // 2, 1)
    start = time.time()
    halves = [mitsuba_image(bsdf_path, used, size, half_spp, seed + k) for k in range(2)]
    seconds = time.time() - start
    mine = np.where(on[..., None], 0.5 * (halves[0] + halves[1]), 0)   # gonio's sphere: coverage at the centre
    halves = [np.where(on[..., None], h, 0) for h in halves]
    import mitsuba as mi
    mi.util.write_bitmap(os.path.join(out, "mitsuba.exr"), mine, write_async=False)
    floor = rj["reference"]["floor"]
    if "flip_mean_between_halves" not in floor:    # render ran without its report (--no-report, no FLIP there)
        gonio_halves = [read_exr(os.path.join(gonio_dir, f"reference-half-{h}.exr")) for h in "ab"]
        floor["flip_mean_between_halves"] = flip_mean(gonio_halves[0], gonio_halves[1], on)
    info = {
        "table": os.path.abspath(table_dir), "gonio_render": os.path.abspath(gonio_dir),
        "environment": used, "size": size, "mitsuba_spp": 2 * half_spp,
        "mitsuba_seconds": seconds, "over": "the sphere's pixels (gonio's A > 0), R, G, B",
        "relative_l1": relative_l1(mine, ref, on),
        "relative_l1_view_below_80": relative_l1(mine, ref, below_80),
        "flip_mean": flip_mean(ref, mine, on),
        "gonio_floor": {"relative_l1_between_halves": floor["relative_l1_between_halves"],
                        "relative_l1_estimate_of_full": floor["relative_l1_estimate_of_full"],
                        "flip_mean_between_halves": floor["flip_mean_between_halves"]},
        "mitsuba_floor": {"relative_l1_between_halves": relative_l1(halves[0], halves[1], on),
                          "relative_l1_estimate_of_full": 0.5 * relative_l1(halves[0], halves[1], on),
                          "flip_mean_between_halves": flip_mean(halves[0], halves[1], on)},
    }
    write_beside_png(os.path.join(out, "beside.png"), ref, mine, rj["tone_map"])
    with open(os.path.join(out, "beside.json"), "w") as fh:
        json.dump(info, fh, indent=1)
        fh.write("\n")
    return info


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("table_dir")
    ap.add_argument("--out", required=True)
    ap.add_argument("--env", default=None, help="default: --beside's environment, else furnace")
    ap.add_argument("--beside", metavar="GONIO_RENDER_DIR")
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args()
    try:
        if a.beside:
            info = beside(a.table_dir, a.beside, a.out, a.env, a.spp, a.seed)
            print(f"relative L1 {info['relative_l1']:.4f}, FLIP {info['flip_mean']} (gonio's floor: L1 "
                  f"{info['gonio_floor']['relative_l1_between_halves']:.4f} between halves; Mitsuba's "
                  f"{info['mitsuba_floor']['relative_l1_between_halves']:.4f})")
            print(f"wrote {a.out}/beside.png, beside.json")
        else:
            render(a.table_dir, a.out, a.env or "furnace", a.size, a.spp, a.seed)
            print(f"wrote {a.out}/reference.exr, reference.png, render.json")
    except EnvError as e:
        print(f"render_in_mitsuba.py: {e}", file=sys.stderr)
        sys.exit(2)


if __name__ == "__main__":
    main()
