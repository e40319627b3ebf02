#!/usr/bin/env bash
# builtin_model_test.sh GLSLANG: a built-in model is one file (docs/MODELS.md "Adding a model"). A copy of
# shaders/ with tests/builtin_models/99-test-coat-rewrite.glsl added to lib/models/builtin/ goes through the build's
# own steps: cmake/builtin_models.cmake generates the dispatch, which must list the new file after the shipped ones
# (its code their count) with its entry, and models.comp and render.comp compile for it (GONIO_MODEL_ONLY=its code)
# and for a shipped model, as
# CMakeLists.txt compiles them; the registry side is tests/test_model_registry.cpp.
set -euo pipefail
glslang="$1"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cp -r "$here/shaders" "$tmp/shaders"
code=$(ls "$here/shaders/lib/models/builtin/"*.glsl | wc -l)   # the shipped files' count: the new file's code
cp "$here/tests/builtin_models/99-test-coat-rewrite.glsl" "$tmp/shaders/lib/models/builtin/"
mkdir -p "$tmp/glsl"
cmake -DMODEL_DIR="$tmp/shaders/lib/models/builtin" -DINCLUDE_PREFIX=models/builtin/ \
      -DOUT="$tmp/glsl/builtin_models.glsl" -P "$here/cmake/builtin_models.cmake"
gen="$tmp/glsl/builtin_models.glsl"
fail() { echo "FAIL: $*" >&2; exit 1; }
n=$(ls "$tmp/shaders/lib/models/builtin/"*.glsl | wc -l)
[ "$(grep -c '^#include "models/builtin/' "$gen")" = "$n" ] || fail "the dispatch does not include every file ($n)"
grep -q '^#include "models/builtin/99-test-coat-rewrite.glsl"' "$gen" || fail "no #include of the new file"
grep -q "if (model == ${code}u) return model_test_coat_rewrite(p, terms, l, v);" "$gen" || fail "no dispatch to code $code"
grep -q 'if (model == 0u) return model_ww09(p, terms, l, v);' "$gen" || fail "ww09 is no longer code 0"
for c in "$code" 0 5; do
    for comp in models render; do
        "$glslang" --quiet --target-env vulkan1.2 -V -DGONIO_MODEL_ONLY=$c -I"$tmp/shaders/lib" -I"$tmp/glsl" \
            -o "$tmp/${comp}_$c.spv" "$tmp/shaders/$comp.comp" >"$tmp/log" 2>&1 || { cat "$tmp/log"; fail "$comp.comp does not compile for code $c"; }
    done
done
echo "builtin_model_test: the new file is code $code, and models.comp and render.comp compile for it"
