#!/usr/bin/env python3
"""What multiple scattering on the microsurface changes on the seed's four materials and the shipped coats
(docs/STUDIES.md, "The seed's materials and the shipped coats with multiple scattering"): for each stack, at its own
roughness and with its roughest interface set to GGX alpha 0.3, 0.6 and 1.0, it runs `gonio compare` on the stack
with `microfacets = "single"` and with `microfacets = "multiple"` on every rough interface (the walk on the
microsurface, Heitz et al. 2016) and writes

  DATA.csv   per stack, alpha, incident angle and model applicable to the stack: the single- and the
             multiple-scattering reference's albedo (reflected + transmitted, the mean of R, G, B), the single's light
             lost on the microfacets, and the model's albedo and relative error against each reference (a stack no
             model represents: one row, model "-"); its first line: the gonio version, the commit and the command
  stdout     the tables docs/STUDIES.md quotes: each reference's albedo and the single-scattering walk's loss (what
             pbrt-v4's LayeredBxDF, single-scattering at its interfaces as the seed's walk, loses), and each production
             model's albedo error against the multiple-scattering reference

usage: study_microfacets_stacks.py WORK_DIR DATA.csv [--paths N] [--gonio build/gonio] [--stacks A.toml,B.toml]
                                   [--alphas own,0.3,0.6,1.0]

Every run: incident angles 0, 45, 75 degrees, the default 1 x 2 degree bins, seed 1, every model and its variants
(--models all). A run whose summary.json is in WORK_DIR already is read, not run again.
"""
import json
import os
import subprocess
import sys
import tomllib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from study_common import ROOT, runs_arguments, write_runs_data  # noqa: E402

# the seed's four materials (Bati et al. 2019, stacks/README.md) and the shipped coats with a rough interface
STACKS = ["stacks/plastic.toml", "stacks/metallic-paint.toml", "stacks/frosted-metal.toml",
          "stacks/transparent-slab.toml", "stacks/coats/clear-over-grey-1.5.toml",
          "stacks/coats/clear-metallic-paint.toml", "stacks/coats/coated-gold.toml",
          "stacks/coats/tinted-coat-copper.toml", "stacks/coats/clear-over-glossy-dielectric.toml"]
ALPHAS = ["own", "0.3", "0.6", "1.0"]
SCATTERING = ["single", "multiple"]
ANGLES = "0,45,75"
PRODUCTION = ["openpbr", "openpbr+single", "openpbr-adobe", "standard-surface", "materialx-layer",
              "cycles-principled", "gltf-clearcoat", "enterprise-pbr"]
ROUGH_KINDS = ("dielectric", "conductor")


def roughest_layer(stack):
    """the index (0-based) of the stack's roughest dielectric or conductor interface (the first of equals)"""
    rough = [(layer.get("roughness", 0.0), -i) for i, layer in enumerate(stack["layer"])
             if layer.get("interface") in ROUGH_KINDS]
    return -max(rough)[1]


def toml_value(v):
    """a stack key's value in TOML: strings, numbers and (nested) arrays of numbers are written as JSON writes them"""
    return json.dumps(v)


def variant_text(stack, name, alpha, scattering):
    """the stack with its roughest interface at alpha ("own": as it is) and every rough interface's microfacets set"""
    lines = [f"name = {toml_value(name)}"]
    for key, value in stack.items():
        if key not in ("name", "layer"):
            lines.append(f"{key} = {toml_value(value)}")
    varied = roughest_layer(stack)
    for i, layer in enumerate(stack["layer"]):
        layer = dict(layer)
        if i == varied and alpha != "own":
            layer["roughness"] = float(alpha)
        if layer.get("interface") in ROUGH_KINDS and layer.get("roughness", 0.0) > 0:
            layer["microfacets"] = scattering
        lines.append("\n[[layer]]")
        lines += [f"{k} = {toml_value(v)}" for k, v in layer.items()]
    return "\n".join(lines) + "\n"


def run_name(stack_name, alpha, scattering):
    return f"{stack_name}-{alpha}-{scattering}"


def summary(work, stack_file, alpha, scattering, gonio, paths):
    """the compare run's summary.json, run now where WORK_DIR lacks it"""
    with open(os.path.join(ROOT, stack_file), "rb") as fh:
        stack = tomllib.load(fh)
    name = run_name(stack["name"], alpha, scattering)
    out = os.path.join(work, name)
    path = os.path.join(out, "summary.json")
    if not os.path.exists(path):
        os.makedirs(work, exist_ok=True)
        variant = os.path.join(work, name + ".toml")
        with open(variant, "w") as fh:
            fh.write(variant_text(stack, name, alpha, scattering))
        subprocess.run([gonio, "compare", variant, "--theta-i", ANGLES, "--paths", str(paths), "--seed", "1",
                        "--models", "all", "--no-report", "--quiet", "--out", out], check=True,
                       stdout=subprocess.DEVNULL)
    with open(path) as fh:
        return stack["name"], roughest_layer(stack) + 1, json.load(fh)


def mean3(v):
    return sum(v) / len(v)


def reference_albedos(run):
    """per incident angle: the reference's albedo (reflected + transmitted) and its light lost on the microfacets,
    each the mean of R, G, B"""
    out = []
    for a in run["angles"]:
        e = a["energy"]
        out.append((mean3([e[c]["reflected"] + e[c]["transmitted"] for c in "RGB"]),
                    mean3([e[c]["microfacet_loss"] for c in "RGB"])))
    return out


def rows_of(name, layer, alpha, single, multiple):
    """one row per incident angle and model applicable to the multiple-scattering run (one row, model "-", where none
    is)"""
    ss, ms = reference_albedos(single), reference_albedos(multiple)
    rows = []
    for i, a in enumerate(multiple["angles"]):
        base = {"stack": name, "layer": layer, "alpha": alpha, "theta_i": a["theta_i"],
                "albedo_single": f"{ss[i][0]:.5f}", "albedo_multiple": f"{ms[i][0]:.5f}",
                "microfacet_loss_single": f"{ss[i][1]:.5f}", "single_vs_multiple": f"{ss[i][0] / ms[i][0] - 1:.5f}"}
        models = [m for m in multiple["models"] if m["applicable"]]
        for m in models:
            model = mean3(m["angles"][i]["albedo_model_total"] if "albedo_model_total" in m["angles"][i]
                          else m["angles"][i]["albedo_model"])
            rows.append(dict(base, model=m["id"], albedo_model=f"{model:.5f}",
                             error_vs_single=f"{model / ss[i][0] - 1:.5f}",
                             error_vs_multiple=f"{model / ms[i][0] - 1:.5f}"))
        if not models:
            rows.append(dict(base, model="-", albedo_model="", error_vs_single="", error_vs_multiple=""))
    return rows


def print_tables(rows):
    """the single-scattering reference's albedo against the walk's, and each production model's error against the
    walk, in percent"""
    keys = []
    for r in rows:
        k = (r["stack"], r["alpha"], r["theta_i"])
        if k not in keys:
            keys.append(k)
    by = {(r["stack"], r["alpha"], r["theta_i"], r["model"]): r for r in rows}
    shown = [m for m in PRODUCTION if any(k[3] == m for k in by)]
    print("| stack | alpha | theta_i | albedo, multiple | single's loss | " + " | ".join(shown) + " |")
    print("|---|---|---|---|---|" + "---|" * len(shown))
    for stack, alpha, th in keys:
        r0 = next(r for r in rows if (r["stack"], r["alpha"], r["theta_i"]) == (stack, alpha, th))
        cells = [f"{100 * float(by[(stack, alpha, th, m)]['error_vs_multiple']):+.1f}%"
                 if (stack, alpha, th, m) in by else "-" for m in shown]
        print(f"| {stack} | {alpha} | {th:g} | {float(r0['albedo_multiple']):.4f} | "
              f"{100 * float(r0['single_vs_multiple']):+.1f}% | " + " | ".join(cells) + " |")


def main():
    p = runs_arguments(__doc__)
    p.add_argument("--stacks", default=",".join(STACKS))
    p.add_argument("--alphas", default=",".join(ALPHAS))
    a = p.parse_args()
    rows = []
    for stack_file in a.stacks.split(","):
        for alpha in a.alphas.split(","):
            (name, layer, single), (_, _, multiple) = [summary(a.work, stack_file, alpha, s, a.gonio, a.paths)
                                                        for s in SCATTERING]
            rows += rows_of(name, layer, alpha, single, multiple)
    write_runs_data(a.gonio, a.data, rows,
                    f"python3 tools/study_microfacets_stacks.py {a.work} {a.data} --paths {a.paths}")
    print_tables(rows)


if __name__ == "__main__":
    main()
