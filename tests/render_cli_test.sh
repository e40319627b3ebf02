#!/usr/bin/env bash
# gonio render as a user meets it: a small render end to end (files, render.json), the same bytes for the same seed,
# a reused table, and the refusals (exit 2 with the reason). Usage: render_cli_test.sh path/to/gonio
set -u
gonio=${1:?usage: render_cli_test.sh GONIO}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
check() {   # check NAME COMMAND...: the command must succeed
    local name=$1
    shift
    if "$@"; then echo "ok: $name"; else echo "FAIL: $name"; fail=1; fi
}
refused() {   # refused NAME PATTERN ARGS...: exit 2 and PATTERN in stderr
    local name=$1 pattern=$2
    shift 2
    "$gonio" render "$@" >"$tmp/out" 2>"$tmp/err"
    local rc=$?
    if [ $rc = 2 ] && grep -q -- "$pattern" "$tmp/err"; then echo "ok: refused: $name"; else
        echo "FAIL: refused: $name (exit $rc)"; cat "$tmp/err"; fail=1; fi
}

small=(--env studio --size 24 --theta-i 0:88:8 --paths 4e4 --spp 16 --quiet)
check "render runs" "$gonio" render stacks/plastic.toml "${small[@]}" --out "$tmp/a" >/dev/null
for f in reference.exr reference.png reference-half-a.exr reference-half-b.exr ww09.exr ww09.png diff-ww09.exr \
    diff-ww09.png render.json table-a/state.gonio table-b/state.gonio; do
    check "writes $f" test -s "$tmp/a/$f"
done
check "render.json has the models' relative L1" grep -q '"relative_l1"' "$tmp/a/render.json"
check "render.json says why a model is not rendered" grep -q '"not_rendered"' "$tmp/a/render.json"
check "render.json says where FLIP stands" grep -q '"flip"' "$tmp/a/render.json"
check "same seed" "$gonio" render stacks/plastic.toml "${small[@]}" --out "$tmp/b" --no-report >/dev/null
for f in reference.exr ww09.exr ww-corrected.exr; do check "same seed, same bytes: $f" cmp -s "$tmp/a/$f" "$tmp/b/$f"; done
check "a reused table (--reference)" "$gonio" render stacks/plastic.toml "${small[@]}" --reference "$tmp/a" \
    --out "$tmp/c" --no-report --models ww09 >/dev/null
check "the reused table gives the same reference" cmp -s "$tmp/a/reference.exr" "$tmp/c/reference.exr"
check "render --help" bash -c "'$gonio' render --help | grep -q -- '--env'"

# compare --render: the render in OUT/render with compare's models, its figure and numbers in report.html
check "compare --render" "$gonio" compare stacks/plastic.toml --theta-i 0,60 --paths 2e4 --render studio \
    --render-size 16 --render-paths 2e4 --models ww09,ww-corrected --quiet --out "$tmp/cmp" >/dev/null
check "compare --render writes render/render.json" test -s "$tmp/cmp/render/render.json"
check "compare --render renders the selected models only" bash -c "test -s '$tmp/cmp/render/ww-corrected.exr' &&
    ! test -e '$tmp/cmp/render/elek10.exr'"
check "compare --render: its own 0:88:2 table" python3 -c "import json, sys
t = json.load(open(sys.argv[1]))['reference']['theta_i_deg']
sys.exit(t != [2.0 * k for k in range(45)])" "$tmp/cmp/render/render.json"
if [ -s "$tmp/cmp/report.html" ]; then
    check "report.html shows the renderings" grep -q "Renderings (under studio)" "$tmp/cmp/report.html"
fi
check "compare --render --model: the user's model rendered too" bash -c "'$gonio' compare stacks/plastic.toml \
    --theta-i 0 --paths 1e4 --render furnace --render-size 16 --render-paths 1e4 --models ww09,schlick-coat \
    --model examples/user_model.glsl --quiet --no-report --out '$tmp/cmpu' >/dev/null &&
    test -s '$tmp/cmpu/render/schlick-coat.exr'"
# a --model whose f is NaN where the render samples it: said, its images not written, render.json says why, exit 1
"$gonio" render stacks/plastic.toml "${small[@]}" --model tests/user_models/nan_near_normal.glsl \
    --models ww09,nan-near-normal --no-report --out "$tmp/nan" >/dev/null 2>"$tmp/err"
nan_rc=$?
check "a model whose f is not finite: exit 1, said" bash -c "[ $nan_rc = 1 ] &&
    grep -q 'nan-near-normal: [0-9]* pixels are NaN or infinite' '$tmp/err'"
check "a model whose f is not finite: its images not written, the others' are" bash -c "
    ! test -e '$tmp/nan/nan-near-normal.exr' && test -s '$tmp/nan/ww09.exr'"
check "a model whose f is not finite: render.json says why" grep -q '"non_finite_pixels"' "$tmp/nan/render.json"
# compare --render keeps the render's exit status: the model is finite at compare's 30 degrees (scored there), not
# everywhere the render samples it, so only the render fails
"$gonio" compare stacks/plastic.toml --theta-i 30 --paths 1e4 --render furnace --render-size 16 --render-paths 1e4 \
    --model tests/user_models/nan_near_normal.glsl --models ww09,nan-near-normal --quiet --no-report \
    --out "$tmp/cmpnan" >/dev/null 2>"$tmp/err"
cmp_nan_rc=$?
check "compare --render: the render's failure is compare's exit 1" bash -c "[ $cmp_nan_rc = 1 ] &&
    grep -q 'nan-near-normal: [0-9]* pixels are NaN or infinite' '$tmp/err'"
check "compare --render: the model scored on compare's own bins" python3 -c "import json, sys
m = {e['id']: e for e in json.load(open(sys.argv[1]))['models']}['nan-near-normal']
sys.exit(not m['scored'])" "$tmp/cmpnan/summary.json"
refused "a --model file that does not compile, with its line" "broken.glsl:[0-9]" stacks/plastic.toml \
    --model tests/user_models/broken.glsl --out "$tmp/x"
compare_refused() {   # compare_refused NAME PATTERN ARGS...: exit 2 and PATTERN in stderr, before any simulation
    local name=$1 pattern=$2
    shift 2
    "$gonio" compare stacks/plastic.toml --theta-i 0 --paths 1e9 --out "$tmp/y" "$@" >"$tmp/out" 2>"$tmp/err"
    local rc=$?
    if [ $rc = 2 ] && grep -q -- "$pattern" "$tmp/err" && ! test -e "$tmp/y/state.gonio"; then
        echo "ok: refused: compare $name"; else echo "FAIL: refused: compare $name (exit $rc)"; cat "$tmp/err"; fail=1; fi
}
compare_refused "--render with an unknown environment" "forest" --render nowhere
compare_refused "--render-size without --render" "--render ENV" --render-size 64
compare_refused "--render-size out of range" "--render-size" --render studio --render-size 4

# render --spectral (docs/RENDER.md): the table traced band by band, the RGB run rendered beside it, their colour
# difference per pixel. A grey stack's two runs differ by their noise alone: the median CIEDE2000 over the lit pixels
# is the noise floor's order (between 0.6 and 1.8 of it); coated gold with n and k at the dominant wavelengths is off by
# several units (the bins' study: 5.6 to 6.8), far above its floor, and the f0 reduction, which matches F0's colour,
# by less
printf 'name = "grey"\n[[layer]]\ninterface = "dielectric"\nroughness = 0.1\nior = 1.5\n[[layer]]\ninterface = "lambertian"\nalbedo = 0.5\n' >"$tmp/grey.toml"
spectral=(--spectral --env studio --size 32 --theta-i 0:80:20 --paths 2e5 --spp 8 --models tm21,ww09 --no-report --quiet)
check "render --spectral runs (grey)" "$gonio" render "$tmp/grey.toml" "${spectral[@]}" --out "$tmp/sg" >/dev/null
for f in reference.exr reference-rgb.exr rgb-vs-spectral-de2000.exr rgb-vs-spectral-de-itp.exr \
    rgb-vs-spectral-noise.exr rgb-vs-spectral-de2000.png spectral-a/summary.json spectral-b/grey.exr \
    rgb-table-a/state.gonio rgb-table-b/state.gonio ww09.exr; do
    check "render --spectral writes $f" test -s "$tmp/sg/$f"
done
check "render --spectral, grey stack: RGB and spectral differ by their noise" python3 -c "import json, sys
e = json.load(open(sys.argv[1]))['rgb_vs_spectral']
r = e['de2000']['median'] / e['noise_de2000_median']
print('grey: median dE2000', e['de2000']['median'], 'noise', e['noise_de2000_median'], 'ratio', r)
sys.exit(not (e['lit_pixels'] > 300 and 0.6 < r < 1.8))" "$tmp/sg/render.json"
check "render --spectral: coated gold" "$gonio" render stacks/coats/coated-gold.toml "${spectral[@]}" \
    --out "$tmp/sa" >/dev/null
check "render --spectral --reduction f0: coated gold" "$gonio" render stacks/coats/coated-gold.toml \
    "${spectral[@]}" --reduction f0 --out "$tmp/sf" >/dev/null 2>&1
check "render --spectral, coated gold: the dominant reduction far off, f0 less" python3 -c "import json, sys
d = json.load(open(sys.argv[1]))['rgb_vs_spectral']
f = json.load(open(sys.argv[2]))['rgb_vs_spectral']
print('gold: dominant', d['de2000']['median'], 'f0', f['de2000']['median'], 'noise', d['noise_de2000_median'])
sys.exit(not (d['de2000']['median'] > 4 and d['de2000']['median'] > 10 * d['noise_de2000_median'] and
              f['de2000']['median'] < 0.5 * d['de2000']['median'] and f['reduction'] == 'f0'))" \
    "$tmp/sa/render.json" "$tmp/sf/render.json"
check "render --spectral: the reference's pixels are the spectral table's colour (not the RGB run's)" \
    bash -c "! cmp -s '$tmp/sa/reference.exr' '$tmp/sa/reference-rgb.exr'"
check "compare --spectral --render: render --spectral into OUT/render" bash -c "'$gonio' compare '$tmp/grey.toml' \
    --spectral --bands 40 --theta-i 0 --paths 2e4 --render studio --render-size 16 --render-paths 2e4 --models ww09 \
    --quiet --no-report --out '$tmp/cs' >/dev/null && grep -q '\"rgb_vs_spectral\"' '$tmp/cs/render/render.json' &&
    test -s '$tmp/cs/render/spectral-a/summary.json' && test -s '$tmp/cs/models-spectral.json'"
refused "--spectral with --reference" "--reference is not taken" "$tmp/grey.toml" --spectral --reference "$tmp/a" \
    --out "$tmp/x"
refused "--bands without --spectral" "go with --spectral" "$tmp/grey.toml" --bands 20 --out "$tmp/x"
refused "--spectral on an RGB conductor" "per RGB channel" stacks/metallic-paint.toml --spectral --out "$tmp/x"

refused "unknown environment, the valid ones listed" "forest" stacks/plastic.toml --env nowhere --out "$tmp/x"
refused "missing environment file" "no such file" stacks/plastic.toml --env /no/such/map.exr --out "$tmp/x"
refused "bad size" "--size" stacks/plastic.toml --size 4 --out "$tmp/x"
refused "reference of another stack" "another stack" stacks/metallic-paint.toml --reference "$tmp/a" --env furnace \
    --size 16 --out "$tmp/x"
refused "reference directory missing" "no such directory" stacks/plastic.toml --reference "$tmp/none" --out "$tmp/x"
refused "unknown model" "no model" stacks/plastic.toml --models nope --out "$tmp/x"
refused "no --out" "--out" stacks/plastic.toml
exit $fail
