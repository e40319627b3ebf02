#!/usr/bin/env python3
"""tools/study_microfacets_stacks.py on synthetic runs (no Vulkan device, no gonio binary): the runs' summary.json
written here with chosen energies and albedos, the script reads them (it runs gonio only where a summary is missing)
and its DATA.csv holds each reference's albedo (reflected + transmitted), the single-scattering walk's loss, and each
model's relative error against both references, worked by hand; a stack no model represents keeps one row per angle;
the stack it would run is the shipped one with its roughest interface at alpha and every rough interface's microfacets
set, read back as TOML.

usage: study_microfacets_stacks_test.py    (Python 3.11: /usr/bin/python3 on Debian 12)
"""
import csv
import json
import os
import subprocess
import sys
import tempfile
import tomllib

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
sys.path.insert(0, os.path.join(ROOT, "tools"))
import study_microfacets_stacks as study  # noqa: E402


def run(reflected, transmitted, loss, models):
    """a compare run's summary.json: per angle (0, 45, 75) the reference's energy (R = G = B), per model (id,
    applicable, its albedo per angle)"""
    angles = [{"theta_i": th, "energy": {c: {"reflected": r, "transmitted": t, "microfacet_loss": m} for c in "RGB"}}
              for th, r, t, m in zip((0, 45, 75), reflected, transmitted, loss)]
    out = []
    for mid, applicable, albedos in models:
        out.append({"id": mid, "applicable": applicable,
                    "angles": [] if not applicable else [{"theta_i": th, "albedo_model": [a] * 3}
                                                         for th, a in zip((0, 45, 75), albedos)]})
    return {"angles": angles, "models": out}


def check_variant():
    """metallic-paint at alpha 0.6: its conductor (the roughest, 0.2) at 0.6, both rough interfaces walked"""
    with open(os.path.join(ROOT, "stacks", "metallic-paint.toml"), "rb") as fh:
        stack = tomllib.load(fh)
    assert study.roughest_layer(stack) == 1
    text = study.variant_text(stack, "metallic-paint-0.6-multiple", "0.6", "multiple")
    v = tomllib.loads(text)
    assert v["name"] == "metallic-paint-0.6-multiple" and v["exterior_ior"] == stack["exterior_ior"], text
    assert [L["roughness"] for L in v["layer"]] == [stack["layer"][0]["roughness"], 0.6], text
    assert [L.get("microfacets") for L in v["layer"]] == ["multiple", "multiple"], text
    assert v["layer"][1]["k"] == stack["layer"][1]["k"], text
    own = tomllib.loads(study.variant_text(stack, "x", "own", "single"))
    assert [L["roughness"] for L in own["layer"]] == [L["roughness"] for L in stack["layer"]]


def main():
    check_variant()
    models = [("cannot", False, None), ("openpbr", True, [0.5, 0.4, 0.3]), ("openpbr-adobe", True, [0.6, 0.5, 0.45])]
    single = run([0.4, 0.35, 0.3], [0.1, 0.05, 0.0], [0.1, 0.2, 0.3], models)
    multiple = run([0.5, 0.45, 0.4], [0.1, 0.05, 0.0], [0.0, 0.0, 0.0], models)
    nobody = [("cannot", False, None)]
    with tempfile.TemporaryDirectory() as d:
        work = os.path.join(d, "work")
        for name, r in (("plastic-own-single", single), ("plastic-own-multiple", multiple),
                        ("transparent-slab-own-single", run([0.3] * 3, [0.5] * 3, [0.2] * 3, nobody)),
                        ("transparent-slab-own-multiple", run([0.4] * 3, [0.6] * 3, [0.0] * 3, nobody))):
            os.makedirs(os.path.join(work, name))
            with open(os.path.join(work, name, "summary.json"), "w") as fh:
                json.dump(r, fh)
        data = os.path.join(d, "data.csv")
        text = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "study_microfacets_stacks.py"), work, data,
                               "--stacks", "stacks/plastic.toml,stacks/transparent-slab.toml", "--alphas", "own",
                               "--gonio", "/nonexistent/gonio"], capture_output=True, text=True, check=True).stdout
        with open(data) as fh:
            first = fh.readline()
            rows = list(csv.DictReader(fh))
    assert first.startswith("# ") and "regenerate: python3 tools/study_microfacets_stacks.py" in first, first
    plastic = [r for r in rows if r["stack"] == "plastic"]
    assert sorted({r["model"] for r in plastic}) == ["openpbr", "openpbr-adobe"], rows
    assert len(plastic) == 6 and all(r["layer"] == "1" for r in plastic), plastic
    for r in plastic:
        i = (0, 45, 75).index(int(float(r["theta_i"])))
        ss = single["angles"][i]["energy"]["R"]
        ms = multiple["angles"][i]["energy"]["R"]
        e_ss, e_ms = ss["reflected"] + ss["transmitted"], ms["reflected"] + ms["transmitted"]
        model = dict((m, a) for m, _, a in models[1:])[r["model"]][i]
        assert abs(float(r["albedo_single"]) - e_ss) < 1e-9 and abs(float(r["albedo_multiple"]) - e_ms) < 1e-9, r
        assert abs(float(r["microfacet_loss_single"]) - ss["microfacet_loss"]) < 1e-9, r
        assert abs(float(r["single_vs_multiple"]) - (e_ss / e_ms - 1)) < 1e-5, r
        assert abs(float(r["error_vs_single"]) - (model / e_ss - 1)) < 1e-5, r
        assert abs(float(r["error_vs_multiple"]) - (model / e_ms - 1)) < 1e-5, r
    slab = [r for r in rows if r["stack"] == "transparent-slab"]
    assert [r["model"] for r in slab] == ["-"] * 3 and slab[0]["layer"] == "2", slab
    assert abs(float(slab[0]["single_vs_multiple"]) - (0.8 / 1.0 - 1)) < 1e-5, slab
    # the walk keeps 0.6 at 0 degrees where the single-scattering one reflects and transmits 0.5: -16.7%; openpbr's
    # 0.5 is -16.7% from the walk
    assert "| plastic | own | 0 | 0.6000 | -16.7% | -16.7% | +0.0% |" in text, text
    assert "| transparent-slab | own | 0 | 1.0000 | -20.0% | - | - |" in text, text
    print("study_microfacets_stacks_test: ok")


if __name__ == "__main__":
    main()
