#!/usr/bin/env bash
# builtin_model_test.sh GLSLANG CXX: a built-in model is one file (docs/MODELS.md "Adding a model"). A copy of
# shaders/ with tests/builtin_models/99-test-coat-rewrite.glsl added to lib/models/builtin/ goes through the build's
# own steps: cmake/builtin_models.cmake generates the dispatch, which must list the new file after the shipped ones
# (its code their count) with its entry, and models.comp and render.comp compile for it (GONIO_MODEL_ONLY=its code)
# and for a shipped model, as CMakeLists.txt compiles them; its table set (`table:`) is laid out after the shipped
# ones, and its GONIO_MODEL_TABLES hook dispatched and compiled as the CPU twin compiles it (CXX, with model_twin.h's
# environment); the registry side is tests/test_model_registry.cpp.
set -euo pipefail
glslang="$1"
cxx="$2"
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
# its table set: after the shipped files' sets, its bit the next, its hook dispatched; the twin compiles with it
shipped_sets=$(grep -c '^// table:' "$here"/shaders/lib/models/builtin/*.glsl | awk -F: '{ n += $2 } END { print n }')
grep -q "^const uint STACK_TABLES_TEST_COAT_REWRITE_ALBEDO = $((1 << shipped_sets))u;" "$gen" ||
    fail "the new file's table set is not bit $shipped_sets"
grep -q '{"test-coat-rewrite-albedo", '"$((1 << shipped_sets))u"', STACK_TABLE_SETS + [0-9]*u, 65u, '"${code}"'u}' "$gen" ||
    fail "the new file's table set is not in STACK_TABLE_SET_LIST"
grep -q '^    model_test_coat_rewrite_tables(s, sets);' "$gen" || fail "the new file's GONIO_MODEL_TABLES is not dispatched"
printf '#include "model_twin.h"\nvoid fill(const StackGpu& s) { eval_stack_table_sets(s, STACK_TABLES_TEST_COAT_REWRITE_ALBEDO); }\n' \
    >"$tmp/twin.cpp"
"$cxx" -std=c++20 -fsyntax-only -DGLM_FORCE_XYZW_ONLY -I"$tmp/glsl" -I"$tmp/shaders/lib" -I"$here/host/models" \
    -I"$here/host/core" -I"$here/host/spectral" "$tmp/twin.cpp" >"$tmp/log" 2>&1 ||
    { cat "$tmp/log"; fail "the CPU twin does not compile with the new file"; }
echo "builtin_model_test: the new file is code $code, models.comp and render.comp compile for it, its table set is" \
    "bit $shipped_sets and the CPU twin compiles its fill"
