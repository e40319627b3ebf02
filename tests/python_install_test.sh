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
sys.exit(0 if same else 1)
PY
