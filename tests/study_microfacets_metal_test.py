#!/usr/bin/env python3
"""tools/study_microfacets_metal.py on synthetic runs (no Vulkan device, no gonio binary): the runs' summary.json
written here with chosen albedos, the script reads them (it runs gonio only where a summary is missing) and its
DATA.csv holds each model's albedo and its relative errors against the single- and the multiple-scattering
reference, worked by hand; a model that cannot represent the stack is left out; the stack it would run sets the
microfacets key it names, under an index-matched smooth coat.

usage: study_microfacets_metal_test.py    (Python 3: /usr/bin/python3 on Debian)
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
sys.path.insert(0, os.path.join(ROOT, "tools"))
import study_microfacets_metal as study  # noqa: E402


def run(reference, models):
    """a compare run's summary.json: per model (id, applicable, its albedo per angle), the reference's albedo per
    angle (R = G = B, angles 0, 45, 75)"""
    out = []
    for mid, applicable, albedos in models:
        angles = [] if not applicable else [{"theta_i": th, "albedo_model": [a] * 3, "albedo_reference": [r] * 3, "rmse_remapped": 0.01 * i}
                  for i, (th, a, r) in enumerate(zip((0, 45, 75), albedos, reference))]
        out.append({"id": mid, "applicable": applicable, "angles": angles})
    return {"models": out}


def main():
    single, multiple = [0.6, 0.5, 0.4], [0.8, 0.75, 0.7]
    models = [("cannot", False, None), ("openpbr", True, [0.6, 0.5, 0.4]), ("openpbr-adobe", True, [0.8, 0.78, 0.63])]
    with tempfile.TemporaryDirectory() as d:
        work = os.path.join(d, "work")
        for name, ref in (("single", single), ("multiple", multiple)):
            path = os.path.join(work, study.run_name("Au", "0.3", name))
            os.makedirs(path)
            with open(os.path.join(path, "summary.json"), "w") as fh:
                json.dump(run(ref, models), fh)
        data = os.path.join(d, "data.csv")
        text = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "study_microfacets_metal.py"), work, data,
                               "--metals", "Au", "--alphas", "0.3", "--gonio", "/nonexistent/gonio"],
                              capture_output=True, text=True, check=True).stdout
        with open(data) as fh:
            first = fh.readline()
            rows = list(csv.DictReader(fh))
    assert first.startswith("# ") and "regenerate: python3 tools/study_microfacets_metal.py" in first, first
    assert sorted({r["model"] for r in rows}) == ["openpbr", "openpbr-adobe"], rows
    assert len(rows) == 6, rows
    for r in rows:
        i = (0, 45, 75).index(int(float(r["theta_i"])))
        model = dict((m, a) for m, _, a in models[1:])[r["model"]][i]
        assert abs(float(r["albedo_single"]) - single[i]) < 1e-9 and abs(float(r["albedo_multiple"]) - multiple[i]) < 1e-9
        assert abs(float(r["error_vs_single"]) - (model / single[i] - 1)) < 1e-5, r
        assert abs(float(r["error_vs_multiple"]) - (model / multiple[i] - 1)) < 1e-5, r
    # the single-scattering model sits on the single reference: 0 against it, -25% against the walk at 0 degrees
    assert "| Au | 0.3 | 0 | 0.8000 | -25.0% | -25.0% | +0.0% |" in text, text
    s = study.stack_text("Ag", "0.6", "multiple")
    assert 'microfacets = "multiple"' in s and 'material = "Ag"' in s and "roughness = 0.6" in s, s
    assert 'interface = "dielectric"\nior = 1.0\nroughness = 0\n' in s, s
    print("study_microfacets_metal: 6 rows as worked by hand, the table's cells, the stack's keys")


if __name__ == "__main__":
    main()
