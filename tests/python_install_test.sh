#!/usr/bin/env bash
# pip install ./python on this machine (the README's fresh one, with ./run's packages): in a new venv, the package and
# its compiled module gonio._core built by CMake through scikit-build-core; then the installed gonio runs a stack in
# memory and gives the bytes of `gonio simulate` (GONIO, built beside) for the same options.
# usage: python_install_test.sh GONIO   (from the repository root)
set -euo pipefail
gonio="$(realpath "$1")"
here="$(pwd)"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
/usr/bin/python3 -m venv "$tmp/venv"
"$tmp/venv/bin/pip" install -q --disable-pip-version-check "$here/python" ||
    { echo "python_install_test: FAIL: pip install ./python"; exit 1; }
"$gonio" simulate stacks/plastic.toml --theta-i 0,45 --paths 2e5 --dtheta 5 --dphi 10 --seed 3 --quiet \
    --out "$tmp/cli" > /dev/null
cd "$tmp"   # the installed package, not the repository's python/
"$tmp/venv/bin/python" - "$here/stacks/plastic.toml" "$tmp/cli/slices.csv" <<'PY'
import sys
import gonio
assert "site-packages" in gonio.__file__, gonio.__file__
run = gonio.simulate(gonio.Stack.from_toml(sys.argv[1]), theta_i=[0, 45], paths=2e5, dtheta=5, dphi=10, seed=3,
                     progress=False)
same = run.core.slices_csv() == open(sys.argv[2]).read()
print("python_install_test:", "ok: the installed gonio gives gonio simulate's slices.csv" if same else
      "FAIL: the installed gonio's slices.csv differs from gonio simulate's")
# the rest of the module as this build of it (PyPI's pybind11) runs it: a progress callback, models, a fit
import numpy as np
calls = []
gonio.simulate(sys.argv[1], theta_i=[30], paths=1e5, dtheta=5, dphi=10, progress=lambda d, t: calls.append(d))
cmp = gonio.compare(sys.argv[1], run, models=["ww-corrected", gonio.Model(lambda l, v, p: np.full((len(l), 3), 0.1),
                                                                          "flat")])
fit = gonio.fit(run, "ww-corrected", free=["layer.1.roughness"])
works = len(calls) > 0 and {"ww-corrected", "flat"} <= set(cmp.sources()) and fit.se("layer.1.roughness") > 0
print("python_install_test:", "ok: progress, compare and fit run" if works else "FAIL: progress, compare or fit")
sys.exit(0 if same and works else 1)
PY
