#!/usr/bin/env bash
# The command line as a user meets it: help, clear refusals of bad input, a validated simulate run.
# usage: cli_test.sh path/to/gonio   (run from the repository root)
set -u
gonio="$(realpath "$1")"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
export GONIO_CACHE_DIR="$out/cache"   # Belcour's tables: keep the user's cache out of the test
pass=0 fail=0
ok()   { pass=$((pass + 1)); }
bad()  { fail=$((fail + 1)); echo "FAIL: $*"; }
expect() {   # expect RC PATTERN -- command...
    local want_rc="$1" pattern="$2"; shift 3
    local text rc
    text="$("$@" 2>&1)"; rc=$?
    if [ "$rc" != "$want_rc" ]; then bad "$* exited $rc, expected $want_rc: $text"; return; fi
    if ! grep -qE -- "$pattern" <<<"$text"; then bad "$*: output lacks /$pattern/: $text"; return; fi
    ok
}
expect 0 "usage:" -- "$gonio" --help
for c in simulate compare fit sweep merge export nodes score bench check models random-stack devices; do expect 0 "usage:" -- "$gonio" $c --help; done
[ -x "$(dirname "$gonio")/gonio-view" ] && { expect 0 "usage: gonio-view" -- "$gonio" view --help; }
expect 2 "unknown command" -- "$gonio" frobnicate
# each command takes its own options only, and has its own --help
expect 2 "option --paths does not apply to .gonio check. \(it takes no options\)" -- "$gonio" check stacks/plastic.toml --paths 5
expect 2 "option --atlas does not apply to .gonio simulate." -- "$gonio" simulate stacks/plastic.toml --atlas 3
expect 2 "option --cpu-twin does not apply to .gonio compare." -- "$gonio" compare stacks/plastic.toml --cpu-twin
expect 2 "option --paths does not apply to .gonio devices. \(it takes no options\)" -- "$gonio" devices --paths 5
expect 2 "unknown option --bogus for .gonio models. \(it takes no options\)" -- "$gonio" models --bogus
# gonio models STACK: each production model's parameters for the stack (sqrt(0.05) = 0.2236), or why not
expect 0 "openpbr +coat_weight 1, coat_darkening 1, coat_ior 1.5, coat_roughness 0.2236" -- "$gonio" models stacks/coats/clear-over-grey-1.5.toml
expect 0 "gltf-clearcoat +cannot represent it: .*colourless" -- "$gonio" models stacks/metallic-paint.toml
# a dielectric base (three layers): OpenPBR's glossy-diffuse base, its IOR relative to the exterior
expect 0 "openpbr +coat_weight 1, .*base_metalness 0, base_color \(0.7, 0.2, 0.1\), specular_weight 1, specular_ior 1.59, specular_roughness 0.3873" -- "$gonio" models stacks/coated-plastic.toml
expect 0 "cycles-principled +cannot represent it: cycles-principled is one coat over one base here; this stack has 3 layers" -- "$gonio" models stacks/coated-plastic.toml
# a sheen model's parameters are its fibres' (read through the stack's layers)
expect 0 "zeltner22-sheen +fuzz_roughness 0.5, fuzz_color \(0.9, 0.6, 0.55\), base_color \(0.35, 0.05, 0.05\)" -- "$gonio" models stacks/velvet.toml
expect 0 "gltf-sheen +sheenRoughnessFactor 0.5, sheenColorFactor \(0.9, 0.6, 0.55\)" -- "$gonio" models stacks/velvet.toml
expect 0 "openpbr +cannot represent it: openpbr takes Henyey-Greenstein media" -- "$gonio" models stacks/velvet.toml
expect 2 "models takes at most one stack file, got 2" -- "$gonio" models stacks/plastic.toml stacks/plastic.toml
expect 2 "nope.toml.*cannot open" -- "$gonio" models nope.toml
expect 2 "option --rse does not apply to .gonio random-stack. \(its options: --seed --count --out\)" -- "$gonio" random-stack --rse 0.1
expect 2 "option --rse does not apply to .gonio bench." -- "$gonio" bench stacks/plastic.toml --rse 0.1
expect 2 "option --paths does not apply to .gonio sweep. \(its options: --out --shard " -- "$gonio" sweep tests/sweeps/tiny.toml --paths 5
expect 2 "unknown option --bogus for .gonio merge. \(it takes no options\)" -- "$gonio" merge --bogus
"$gonio" sweep --help | grep -q "gonio sweep SWEEP.toml" && ! "$gonio" sweep --help | grep -q "simulate options" && ok || bad "gonio sweep --help is not the sweep's own"
"$gonio" simulate --help | grep -q -- "--rse-quantile" && ! "$gonio" simulate --help | grep -q "bench options" && ok || bad "gonio simulate --help is not simulate's own"
"$gonio" --help | grep -q "bench options" && "$gonio" --help | grep -q "Exit codes" && ok || bad "gonio --help lacks a section"
expect 2 "unknown option --bogus" -- "$gonio" simulate stacks/plastic.toml --bogus
# every command's options, as its table lists them, read from the table's own dump (its --help: one line "  --NAME"
# per option, in table order): the refusal of an unknown option lists exactly these (both are made from the table),
# gonio --help names each; an unknown option and an option of another command are refused with exit 2, naming the
# option and the command. The few options below each command must keep (a table that lost one would still agree
# with its own help).
declare -A opts
for c in devices check models merge simulate compare fit bench random-stack sweep export nodes score render; do
    opts[$c]="$("$gonio" "$c" --help | sed -nE 's/^  (--[a-z0-9-]+)( .*)?$/\1/p' | tr '\n' ' ' | sed 's/ $//')"
done
for need in "simulate --rse --resume --spectral" "compare --models --model --render --rgb-vs-spectral" \
            "fit --free --start --loss --reference" "bench --atlas --cpu-paths" "sweep --shard --resume --keep-results" \
            "render --env --reference --spp" "export --format" "nodes --nodes-per-bin" "score --values --id" \
            "random-stack --count"; do
    set -- $need; c=$1; shift
    for o in "$@"; do [[ " ${opts[$c]} " == *" $o "* ]] && ok || bad "gonio $c no longer takes $o (its options: ${opts[$c]})"; done
done
full_help="$("$gonio" --help)"
for c in "${!opts[@]}"; do
    text="$("$gonio" "$c" --no-such-option 2>&1)"; rc=$?
    if [ -z "${opts[$c]}" ]; then listed="(it takes no options)"; else listed="(its options: ${opts[$c]})"; fi
    [ "$rc" = 2 ] && grep -qF -- "unknown option --no-such-option for \`gonio $c\` $listed" <<<"$text" && ok ||
        bad "gonio $c --no-such-option: exit $rc, expected 2 and its options $listed: $text"
    help="$("$gonio" "$c" --help)" || bad "gonio $c --help failed"
    grep -q "^  gonio $c" <<<"$help" && ok || bad "gonio $c --help lacks its usage line"
    [ -n "${opts[$c]}" ] || { grep -q "^$c takes no options" <<<"$help" && ok || bad "gonio $c --help does not say it takes no options"; }
    for o in ${opts[$c]}; do
        grep -qE -- "^  $o( |$)" <<<"$help" && ok || bad "gonio $c --help does not list $o"
        grep -qE -- "(^| )$o( |$)" <<<"$full_help" && ok || bad "gonio --help does not name $c's $o"
    done
    other=""   # an option of another command that this one does not take
    for d in "${!opts[@]}"; do
        for o in ${opts[$d]}; do [[ " ${opts[$c]} " == *" $o "* ]] || { other=$o; break 2; }; done
    done
    text="$("$gonio" "$c" "$other" 1 2>&1)"; rc=$?
    [ "$rc" = 2 ] && grep -qF -- "option $other does not apply to \`gonio $c\`" <<<"$text" && ok ||
        bad "gonio $c $other: exit $rc, expected 2 and a refusal naming both: $text"
done
expect 0 "ok: stacks/plastic.toml is a valid stack" -- "$gonio" check stacks/plastic.toml
expect 0 "walk: the Lambertian series" -- "$gonio" check stacks/plastic.toml
expect 0 "walk: every trip traced \(no Lambertian series: not a dielectric coat" -- "$gonio" check stacks/metallic-paint.toml
expect 2 "tests/bad_stacks/negative-roughness.toml:[0-9]+: .*roughness" -- "$gonio" check tests/bad_stacks/negative-roughness.toml
expect 2 "no-such-file.toml" -- "$gonio" check no-such-file.toml
expect 2 "incident angles must be in \[0, 90\)" -- "$gonio" simulate stacks/plastic.toml --theta-i 90 --paths 10 --out "$out/x"
expect 2 "--paths: expected a number" -- "$gonio" simulate stacks/plastic.toml --paths lots
expect 2 "--dphi must divide 180" -- "$gonio" simulate stacks/plastic.toml --dphi 7 --paths 10 --out "$out/x"
expect 2 "max-events .* too large" -- "$gonio" simulate stacks/plastic.toml --max-events 5000 --paths 10 --out "$out/x"
# options are checked before any work, each refusal exits 2 and says what was expected
expect 2 "incident angle 30 is given twice" -- "$gonio" simulate stacks/plastic.toml --theta-i 30,30 --paths 10 --out "$out/x"
expect 2 "needs a histogram buffer of .* MiB; the device allows .* use wider --dtheta" -- "$gonio" simulate stacks/plastic.toml --dtheta 0.005 --paths 10 --out "$out/x"
expect 2 "at most .* paths per incident angle" -- "$gonio" simulate stacks/plastic.toml --paths 1e15 --out "$out/x"
expect 2 "rse-quantile must be in" -- "$gonio" simulate stacks/plastic.toml --rse 0.1 --rse-quantile 0 --out "$out/x"
expect 2 "ior-huge.toml:6: layer 1: ior must be in \[1, 10\]" -- "$gonio" check tests/bad_stacks/ior-huge.toml
# nothing that comes from an input file leaves --out: a stack named "../../x" writes inside out/
printf 'name = "../../escaped"\n[[layer]]\ninterface = "dielectric"\nior = 1.5\n[[layer]]\ninterface = "lambertian"\nalbedo = 0.5\n' > "$out/evil.toml"
(mkdir -p "$out/cwd/a/b" && cd "$out/cwd/a/b" && "$gonio" simulate "$out/evil.toml" --paths 1000 --quiet > /dev/null 2>&1)
[ -z "$(find "$out/cwd" -name '*escaped*' -not -path "$out/cwd/a/b/out/*" | grep -v "^$out/cwd/a/b/out$")" ] && [ -d "$out/cwd/a/b/out" ] && ok || bad "a stack's name wrote outside the output directory: $(find "$out/cwd")"
# a sweep's [[vary]] goes through the stack file's rules: albedo is no parameter of a conductor
printf 'name = "bad"\nstack = "%s/stacks/frosted-metal.toml"\ntheta_i = [30]\n[[vary]]\nlayer = 2\nkey = "albedo"\nvalues = [0.1]\n' "$PWD" > "$out/bad-vary.toml"
expect 2 "bad-vary.toml:4: .*key 'albedo' does not apply to layer 2, a conductor interface" -- "$gonio" sweep "$out/bad-vary.toml" --quiet --out "$out/swv"
# a word key (the microsurface's) is set in the stack file: a sweep varies numbers, and says so
printf 'name = "bad"\nstack = "%s/stacks/frosted-metal.toml"\ntheta_i = [30]\n[[vary]]\nlayer = 1\nkey = "microfacets"\nvalues = ["single", "multiple"]\n' "$PWD" > "$out/bad-vary-word.toml"
expect 2 "bad-vary-word.toml:4: .*'microfacets' takes a word \\(\"single\" or \"multiple\"\\), and a sweep varies numbers" -- "$gonio" sweep "$out/bad-vary-word.toml" --quiet --out "$out/swv"
expect 0 "wrote" -- "$gonio" simulate stacks/transparent-slab.toml --theta-i 0,45 --paths 2e5 --seed 7 --validate --quiet --out "$out/slab"
for f in transparent-slab.exr slices.csv summary.json; do
    [ -s "$out/slab/$f" ] && ok || bad "simulate did not write $f"
done
# same seed, same bytes; the CPU twin writes the same kind of files
expect 0 "wrote" -- "$gonio" simulate stacks/transparent-slab.toml --theta-i 0,45 --paths 2e5 --seed 7 --quiet --out "$out/slab2"
cmp -s "$out/slab/slices.csv" "$out/slab2/slices.csv" && ok || bad "same seed gave different slices.csv"
expect 0 "wrote" -- "$gonio" simulate stacks/plastic.toml --paths 1e4 --cpu-twin --quiet --out "$out/twin"
expect 0 "\* 0: " -- "$gonio" devices
# --phi-i: the incident azimuth, carried by every file of the run (and by its state, which --resume continues), the
# models' rows included; what takes the plane of incidence only refuses it; out of [0, 360) refused
expect 0 "wrote" -- "$gonio" simulate stacks/plastic.toml --theta-i 30,60 --phi-i 45 --paths 2e4 --quiet --out "$out/az"
head -1 "$out/az/slices.csv" | grep -q "^source,theta_i,phi_i,side," && sed -n 2p "$out/az/slices.csv" | grep -q "^reference,30,45,R," &&
    ok || bad "simulate --phi-i 45: slices.csv has no phi_i column: $(head -2 "$out/az/slices.csv")"
PYTHONPATH="$PWD/python" /usr/bin/python3 - "$out/az" <<'PY' && ok || bad "simulate --phi-i 45: summary.json or the Python reader lost the azimuth"
import sys, gonio
run = gonio.read_run(sys.argv[1])
assert [a["phi_i"] for a in run.summary["angles"]] == [45, 45] and run.phi_i == 45.0
assert run.f("reference", 60).shape == (90, 180, 3)
PY
head -1 "$out/slab/slices.csv" | grep -q "^source,theta_i,side," && ! grep -q '"phi_i"' "$out/slab/summary.json" && ok ||
    bad "a run in the plane of incidence writes a phi_i"
cp -r "$out/az" "$out/az-cmp"
expect 0 "wrote" -- "$gonio" compare stacks/plastic.toml --resume "$out/az-cmp" --paths 3e4 --quiet --no-report
grep -q "^ww09,60,45,R," "$out/az-cmp/slices.csv" && ok || bad "compare at phi_i 45: no ww09 rows with the phi_i column"
expect 0 "wrote" -- "$gonio" compare stacks/plastic.toml --theta-i 30 --phi-i 45 --dtheta 5 --dphi 10 --paths 2e4 --quiet \
    --no-report --out "$out/az-cmp2"
expect 2 "--spectral traces the plane of incidence .phi_i 0.; --phi-i goes with the RGB walk" -- "$gonio" compare \
    stacks/plastic.toml --phi-i 45 --spectral
expect 0 "fit" -- "$gonio" fit --reference "$out/az-cmp2" --model ww09 --free layer.1.roughness --out "$out/az-fit" \
    --no-report
grep -q '"phi_i": 45' "$out/az-fit/fit.json" && ok || bad "fit at phi_i 45: fit.json does not carry the azimuth"
# gonio nodes at an azimuth: l turned, the bins the surface's; score takes a reference of the nodes' azimuth only
expect 0 "wrote" -- "$gonio" nodes stacks/plastic.toml --theta-i 30 --phi-i 45 --dtheta 5 --dphi 10 --nodes-per-bin 1 \
    --out "$out/az-nodes"
grep -q '"phi_i": 45' "$out/az-nodes/nodes.json" && sed -n 2p "$out/az-nodes/nodes.csv" |
    grep -q "^30,R,0,0.35355339059327\(3\|4\)[0-9]*,0.35355339059327\(3\|4\)[0-9]*,0.866025403784438" && ok ||
    bad "nodes --phi-i 45: nodes.json or the nodes' l: $(sed -n 2p "$out/az-nodes/nodes.csv")"
expect 0 "wrote" -- "$gonio" nodes stacks/plastic.toml --theta-i 30 --dtheta 5 --dphi 10 --nodes-per-bin 1 \
    --out "$out/az-nodes0"
awk -F, 'NR > 1 {print "0.1,0.1,0.1"}' "$out/az-nodes0/nodes.csv" > "$out/az-values.csv"
expect 2 "not a run of the nodes' stack, angles and bins .incident azimuth 45, the nodes' 0." -- "$gonio" score \
    "$out/az-nodes0" --values "$out/az-values.csv" --id flat --reference "$out/az-cmp2" --out "$out/az-score"
expect 2 "an isotropic table takes phi_i = 0" -- "$gonio" export "$out/az" --format merl --out "$out/az.binary"
expect 0 "40000 paths" -- "$gonio" simulate stacks/plastic.toml --resume "$out/az" --paths 4e4 --quiet
expect 2 "--phi-i: the incident azimuth must be in \[0, 360\) degrees, got 360" -- "$gonio" simulate stacks/plastic.toml --phi-i 360
expect 2 "--phi-i goes with the RGB walk" -- "$gonio" simulate stacks/plastic.toml --phi-i 10 --spectral
# --resume continues a run exactly, with the options it recorded, as the README writes it (STACK --resume DIR --paths
# N): 3e5 then on to 7e5 paths gives the bytes of one 7e5-path run
expect 0 "wrote" -- "$gonio" simulate stacks/plastic.toml --theta-i 30,70 --paths 3e5 --seed 4 --quiet --out "$out/r1"
expect 0 "700000 paths" -- "$gonio" simulate stacks/plastic.toml --resume "$out/r1" --paths 7e5 --quiet
expect 0 "wrote" -- "$gonio" simulate stacks/plastic.toml --theta-i 30,70 --paths 7e5 --seed 4 --quiet --out "$out/r2"
cmp -s "$out/r1/slices.csv" "$out/r2/slices.csv" && ok || bad "resumed run differs from one longer run"
# and its energy book, paths and errors: summary.json the same but for the fields that measure time
/usr/bin/python3 - "$out/r1/summary.json" "$out/r2/summary.json" <<'PY' && ok || bad "resumed run's summary.json differs from one longer run's"
import json, re, sys
timing = re.compile(r"(seconds|paths_per_second|^date)")
def strip(o):
    if isinstance(o, dict):
        return {k: strip(v) for k, v in o.items() if not timing.search(k)}
    return [strip(v) for v in o] if isinstance(o, list) else o
a, b = (strip(json.load(open(f))) for f in sys.argv[1:])
sys.exit(0 if a == b else 1)
PY
# options given again must agree with the recorded ones (the refusal names both); those that agree are accepted
expect 2 "--no-series given differs from the earlier run's not given" -- "$gonio" simulate stacks/plastic.toml --paths 9e5 --no-series --quiet --resume "$out/r1"
expect 2 "--no-baked-stack given differs from the earlier run's not given" -- "$gonio" simulate stacks/plastic.toml --paths 9e5 --no-baked-stack --quiet --resume "$out/r1"
expect 2 "--seed 5 differs from the earlier run's 4" -- "$gonio" simulate stacks/plastic.toml --paths 9e5 --seed 5 --quiet --resume "$out/r1"
expect 2 "--theta-i 30 differs from the earlier run's 30,70" -- "$gonio" simulate stacks/plastic.toml --theta-i 30 --paths 9e5 --quiet --resume "$out/r1"
expect 2 "--dtheta 2 differs from the earlier run's 1" -- "$gonio" simulate stacks/plastic.toml --dtheta 2 --paths 9e5 --quiet --resume "$out/r1"
expect 2 "the stack differs" -- "$gonio" simulate stacks/frosted-metal.toml --paths 9e5 --quiet --resume "$out/r1"
expect 2 "already has 700000 paths" -- "$gonio" simulate stacks/plastic.toml --theta-i 30,70 --paths 5e5 --seed 4 --quiet --resume "$out/r1"
expect 2 "nothing-here/state.gonio: cannot open the state file for reading .no such file. .is it the output directory of a simulate run" -- "$gonio" simulate stacks/plastic.toml --paths 5e5 --quiet --resume "$out/nothing-here"
# a path whose weight stops being finite is booked as invalid (not absorbed), said, and the run exits 1; the energy
# sum is still 1 and summary.json holds no NaN
expect 1 "theta_i 30: 1 paths booked a number that is not finite" -- "$gonio" simulate stacks/frosted-metal.toml --theta-i 30 --paths 1e5 --invalid-path-for-tests 77 --quiet --out "$out/inv"
/usr/bin/python3 - "$out/inv/summary.json" <<'PY' && ok || bad "the invalid path is not booked in its own class"
import json, sys
def refuse(c): raise ValueError("summary.json holds " + c)
e = json.load(open(sys.argv[1]), parse_constant=refuse)["angles"][0]["energy"]
for c in "RGB":
    assert e[c]["invalid"] == 1e-05, e[c]
    assert abs(e[c]["sum"] - 1) < 1e-5, e[c]
PY
# a stack that names a measured material runs end to end: a smooth coat over smooth gold reflects, per channel, the
# series F + (1 - F)^2 R_b / (1 - F R_b) with gold's n and k read here from data/spectra at the sRGB primaries'
# dominant wavelengths (611.3, 549.1, 464.3 nm, docs/SPECTRAL.md)
mkdir -p "$out/gold"
printf 'name = "smooth-gold"\n[[layer]]\ninterface = "dielectric"\nior = 1.5\n[[layer]]\ninterface = "conductor"\nmaterial = "Au"\n' > "$out/gold/gold.toml"
expect 0 "wrote" -- "$gonio" simulate "$out/gold/gold.toml" --theta-i 0 --paths 1e6 --quiet --out "$out/gold/run"
/usr/bin/python3 - "$out/gold/run/summary.json" data/spectra/au-johnson-christy-1972.csv <<'PY' && ok || bad "a coat over smooth gold does not reflect the Fresnel series of gold's measured n and k"
import csv, json, sys
rows = [[float(x) for x in r] for r in csv.reader(l for l in open(sys.argv[2]) if not l.startswith("#") and not l.startswith("wave"))]
def at(nm, c):
    for a, b in zip(rows, rows[1:]):
        if a[0] <= nm <= b[0]:
            return a[c] + (nm - a[0]) / (b[0] - a[0]) * (b[c] - a[c])
e = json.load(open(sys.argv[1]))["angles"][0]["energy"]
f = 0.04
for ch, nm in zip("RGB", (611.3, 549.1, 464.3)):
    n, k = at(nm, 1), at(nm, 2)
    r_b = ((n - 1.5) ** 2 + k * k) / ((n + 1.5) ** 2 + k * k)
    want = f + (1 - f) ** 2 * r_b / (1 - f * r_b)
    assert abs(e[ch]["reflected"] - want) < 2e-3, (ch, e[ch]["reflected"], want)   # 4 binomial se at 1e6 paths
PY
# --spectral (docs/SPECTRAL.md): a grey stack's first band is the RGB run's red channel (the same walk and seed), every
# band agrees with it within the noise; a perfect white reflector is D65's white with Y = 1; the coat over smooth gold
# is the Fresnel series of gold's n and k at each band's centre; what it cannot take is refused
printf 'name = "grey"\n[[layer]]\ninterface = "dielectric"\nroughness = 0.1\nior = 1.5\n[[layer]]\ninterface = "lambertian"\nalbedo = 0.5\n' > "$out/gold/grey.toml"
expect 0 "wrote" -- "$gonio" simulate "$out/gold/grey.toml" --theta-i 30 --paths 2e5 --quiet --out "$out/gold/grey-rgb"
expect 0 "40 bands of 10 nm" -- "$gonio" simulate "$out/gold/grey.toml" --spectral --band-paths even --theta-i 30 --paths 2e5 --quiet --out "$out/gold/grey-spectral"
/usr/bin/python3 - "$out/gold/grey-rgb/summary.json" "$out/gold/grey-spectral/summary.json" <<'PY' && ok || bad "--spectral on a grey stack is not the RGB run band by band"
import json, math, sys
rgb = json.load(open(sys.argv[1]))["angles"][0]["energy"]["R"]["reflected"]
s = json.load(open(sys.argv[2]))["angles"][0]
bands = s["spectral"]["reflected"]
assert len(bands) == 40 and s["spectral"]["wavelength_nm"][0] == 385, s["spectral"]
assert bands[0] == rgb, (bands[0], rgb)   # pass 1, channel 1: the RGB run's walk and seed
se = math.sqrt(rgb * (1 - rgb) / 2e5)
assert all(abs(b - rgb) < 5 * se for b in bands), (rgb, se, bands)
assert abs(s["xyz"]["reflected"][1] - sum(bands) / 40) < 5 * se, s["xyz"]   # a flat spectrum's Y is its value
PY
# a seed gives the same bytes: two spectral runs of the gold with seed 7 (paths by weight, two points per band) write
# the same EXR
for r in a b; do "$gonio" simulate "$out/gold/gold.toml" --spectral --bands 40 --band-points 2 --theta-i 0,60 --paths 5e4 --seed 7 --quiet --out "$out/gold/det-$r" > /dev/null 2>&1; done
cmp -s "$out/gold/det-a/smooth-gold.exr" "$out/gold/det-b/smooth-gold.exr" && ok || bad "--spectral: a seed does not give the same bytes"
printf 'name = "white"\n[[layer]]\ninterface = "lambertian"\nalbedo = 1\n' > "$out/gold/white.toml"
expect 0 "wrote" -- "$gonio" simulate "$out/gold/white.toml" --spectral --bands 20 --theta-i 0 --paths 1e5 --quiet --out "$out/gold/white"
/usr/bin/python3 - "$out/gold/white/summary.json" <<'PY' && ok || bad "--spectral: a perfect white reflector is not D65's white with Y = 1"
import json, sys
s = json.load(open(sys.argv[1]))["angles"][0]
X, Y, Z = s["xyz"]["reflected"]
assert abs(Y - 1) < 1e-6 and abs(X - 0.9505) < 2e-3 and abs(Z - 1.089) < 3e-3, (X, Y, Z)
assert len(s["spectral"]["reflected"]) == 20 and all(abs(b - 1) < 1e-6 for b in s["spectral"]["reflected"])
PY
expect 0 "wrote" -- "$gonio" simulate "$out/gold/gold.toml" --spectral --theta-i 0 --paths 1e6 --quiet --out "$out/gold/spectral"
/usr/bin/python3 - "$out/gold/spectral/summary.json" data/spectra/au-johnson-christy-1972.csv <<'PY' && ok || bad "--spectral: a coat over smooth gold is not the Fresnel series of gold's n and k at each band"
import csv, json, math, sys
rows = [[float(x) for x in r] for r in csv.reader(l for l in open(sys.argv[2]) if not l.startswith("#") and not l.startswith("wave"))]
def at(nm, c):
    for a, b in zip(rows, rows[1:]):
        if a[0] <= nm <= b[0]:
            return a[c] + (nm - a[0]) / (b[0] - a[0]) * (b[c] - a[c])
a = json.load(open(sys.argv[1]))["angles"][0]
s = a["spectral"]
for b, (nm, got) in enumerate(zip(s["wavelength_nm"], s["reflected"])):
    n, k, f = at(nm, 1), at(nm, 2), 0.04
    r_b = ((n - 1.5) ** 2 + k * k) / ((n + 1.5) ** 2 + k * k)
    want = f + (1 - f) ** 2 * r_b / (1 - f * r_b)
    paths = a["paths"][b // 3]   # the pass's share of the paths (--band-paths weight)
    assert abs(got - want) < 5 * math.sqrt(want * (1 - want) / paths) + 1e-6, (nm, got, want, paths)
PY
# a key given as a spectrum: a smooth slab of index 1.5 whose optical depth is pairs of nm and value transmits, band by
# band, the closed form (1 - F)^2 a / (1 - F^2 a^2), a = exp(-tau(lambda)), at normal incidence
printf 'name = "dyed-slab"\n[[layer]]\ninterface = "dielectric"\nior = 1.5\noptical_depth = [[380, 1.2], [500, 0.4], [600, 0.1], [780, 0.05]]\n[[layer]]\ninterface = "dielectric"\nior = 1.0\n' > "$out/gold/dyed.toml"
expect 0 "wrote" -- "$gonio" simulate "$out/gold/dyed.toml" --spectral --bands 20 --theta-i 0 --paths 2e5 --quiet --out "$out/gold/dyed"
/usr/bin/python3 - "$out/gold/dyed/summary.json" <<'PY' && ok || bad "--spectral: a slab's spectral optical depth is not the closed form band by band"
import json, math, sys
pairs = [(380, 1.2), (500, 0.4), (600, 0.1), (780, 0.05)]
def tau(nm):
    for (a, ta), (b, tb) in zip(pairs, pairs[1:]):
        if a <= nm <= b:
            return ta + (nm - a) / (b - a) * (tb - ta)
angle = json.load(open(sys.argv[1]))["angles"][0]
s = angle["spectral"]
f = 0.04
for b, (nm, got) in enumerate(zip(s["wavelength_nm"], s["transmitted"])):
    a = math.exp(-tau(nm))
    want = (1 - f) ** 2 * a / (1 - f * f * a * a)
    paths = angle["paths"][b // 3]
    assert abs(got - want) < 5 * math.sqrt(want * (1 - want) / paths), (nm, got, want, paths)
PY
# --band-points 4: a band's value is the mean over the midpoints of its four parts; a dye that steps from clear to
# optical depth 3 inside the first 20 nm band transmits there the mean of the clear and the dark slab, not the slab
# at the band's centre (where the step is halfway)
sed 's/\[\[380, 1.2\], \[500, 0.4\], \[600, 0.1\], \[780, 0.05\]\]/[[380, 0], [389, 0], [391, 3], [780, 3]]/' "$out/gold/dyed.toml" > "$out/gold/step.toml"
expect 0 "wrote" -- "$gonio" simulate "$out/gold/step.toml" --spectral --bands 20 --band-points 4 --band-paths even --theta-i 0 --paths 2e5 --quiet --out "$out/gold/step"
/usr/bin/python3 - "$out/gold/step/summary.json" <<'PY' && ok || bad "--band-points: a band's value is not the mean over its points"
import json, math, sys
s = json.load(open(sys.argv[1]))
assert s["spectral"]["points_per_band"] == 4, s["spectral"]
a = s["angles"][0]
f = 0.04
def slab(tau):
    x = math.exp(-tau)
    return (1 - f) ** 2 * x / (1 - f * f * x * x)
def tau(nm):
    return 0.0 if nm <= 389 else (3.0 if nm >= 391 else 1.5 * (nm - 389))
got, paths = a["spectral"]["transmitted"][0], a["paths"][0]
want = sum(slab(tau(380 + (j + 0.5) * 5)) for j in range(4)) / 4   # 382.5, 387.5, 392.5, 397.5 nm
centre = slab(tau(390))
se = math.sqrt(want * (1 - want) / paths)
assert abs(got - want) < 5 * se and abs(got - centre) > 20 * se, (got, want, centre, se)
PY
# a dispersive IOR (a spectrum of n): a smooth slab reflects, band by band, 2F/(1 + F) with F of n at the band's centre
# (one wavelength per pass); the RGB run takes n at the d line, 587.56 nm, in every channel
printf 'name = "prism-glass"\n[[layer]]\ninterface = "dielectric"\nior = [[380, 1.55], [780, 1.5]]\n[[layer]]\ninterface = "dielectric"\nior = 1.0\n' > "$out/gold/disp.toml"
expect 0 "ior 1.524055" -- "$gonio" check "$out/gold/disp.toml"
expect 0 "wrote" -- "$gonio" simulate "$out/gold/disp.toml" --spectral --bands 40 --band-paths even --theta-i 0 --paths 2e5 --quiet --out "$out/gold/disp"
/usr/bin/python3 - "$out/gold/disp/summary.json" <<'PY' && ok || bad "--spectral: a dispersive slab is not the Fresnel series of n at each band"
import json, math, sys
a = json.load(open(sys.argv[1]))["angles"][0]
got = a["spectral"]["reflected"]
for b, nm in enumerate(a["spectral"]["wavelength_nm"]):
    n = 1.55 + (nm - 380) / 400 * (1.5 - 1.55)
    f = ((n - 1) / (n + 1)) ** 2
    want = 2 * f / (1 + f)
    se = math.sqrt(want * (1 - want) / a["paths"][b // 3])
    assert abs(got[b] - want) < 5 * se, (nm, got[b], want, se)
se = math.sqrt(0.08 * 0.92 / 2e5)
assert got[0] - got[-1] > 10 * se, (got[0], got[-1])   # the blue band reflects more: n is larger there
PY
# a named glass: N-BK7's Sellmeier formula (its data sheet's coefficients, written out here) band by band
printf 'name = "bk7"\n[[layer]]\ninterface = "dielectric"\nior = "N-BK7"\n[[layer]]\ninterface = "dielectric"\nior = 1.0\n' > "$out/gold/bk7.toml"
expect 0 "wrote" -- "$gonio" simulate "$out/gold/bk7.toml" --spectral --bands 40 --band-paths even --theta-i 0 --paths 2e5 --quiet --out "$out/gold/bk7"
/usr/bin/python3 - "$out/gold/bk7/summary.json" <<'PY' && ok || bad "--spectral: an N-BK7 slab is not the Fresnel series of its Sellmeier index"
import json, math, sys
B, C = (1.03961212, 0.231792344, 1.01046945), (0.00600069867, 0.0200179144, 103.560653)
a = json.load(open(sys.argv[1]))["angles"][0]
for b, nm in enumerate(a["spectral"]["wavelength_nm"]):
    l2 = (nm / 1000) ** 2
    n = math.sqrt(1 + sum(bi * l2 / (l2 - ci) for bi, ci in zip(B, C)))
    f = ((n - 1) / (n + 1)) ** 2
    want = 2 * f / (1 + f)
    se = math.sqrt(want * (1 - want) / a["paths"][b // 3])
    assert abs(a["spectral"]["reflected"][b] - want) < 5 * se, (nm, a["spectral"]["reflected"][b], want, se)
PY
expect 0 "models-spectral.json" -- "$gonio" compare "$out/gold/disp.toml" --spectral --bands 40 --band-points 2 --theta-i 30 --paths 2e4 --dtheta 5 --dphi 10 --quiet --out "$out/gold/disp-models"
sed 's/\[\[380, 1.2\], \[500, 0.4\], \[600, 0.1\], \[780, 0.05\]\]/[[420, 1], [700, 0.1]]/' "$out/gold/dyed.toml" > "$out/gold/dyed-narrow.toml"
expect 2 "optical_depth spectrum covers 420 to 700 nm; the run reads it from 385 to 775 nm" -- "$gonio" simulate "$out/gold/dyed-narrow.toml" --spectral --paths 1e4 --quiet --out "$out/gold/no"
printf 'name = "tinted"\n[[layer]]\ninterface = "dielectric"\nior = 1.5\noptical_depth = [0.1, 0.2, 0.3]\n[[layer]]\ninterface = "lambertian"\nalbedo = 0.5\n' > "$out/gold/tinted.toml"
# a key given per RGB channel: an albedo or an optical depth is uplifted (Jakob & Hanika 2019, docs/SPECTRAL.md), the
# run says how in summary.json and gonio check prints it; a conductor's RGB k has no physical uplift: refused
expect 0 "wrote" -- "$gonio" simulate "$out/gold/tinted.toml" --spectral --bands 40 --theta-i 0 --paths 1e4 --quiet --out "$out/gold/tinted"
/usr/bin/python3 - "$out/gold/tinted/summary.json" <<'PY' && ok || bad "--spectral: an RGB optical depth's uplift is not in summary.json"
import json, sys
u = json.load(open(sys.argv[1]))["uplifted"]
assert len(u) == 1 and u[0]["layer"] == 1 and u[0]["key"] == "optical_depth", u
assert u[0]["method"].startswith("Jakob & Hanika 2019") and u[0]["delta_e76"] < 1e-3 and len(u[0]["coefficients_per_nm"]) == 3, u
PY
printf 'name = "rgb-k"\n[[layer]]\ninterface = "conductor"\nior = 0.2\nk = [3, 2.5, 2]\n' > "$out/gold/rgb-k.toml"
expect 2 "--spectral: layer 1's k is given per RGB channel \(\[3, 2.5, 2\]\).*it is not uplifted from RGB" -- "$gonio" simulate "$out/gold/rgb-k.toml" --spectral --paths 1e4 --quiet --out "$out/gold/no"
# a bare Lambertian base reflects its albedo (no noise: every path leaves with the albedo's weight); its RGB albedo's
# spectral run has that colour: its linear sRGB divided by a white base's (the 10 nm bands' white is (1, 1, 1) within
# 5e-4) is the RGB albedo within 2e-4 (the bands' midpoint rule, tests/test_spectral.cpp RgbUplift.ColoursRoundTrip);
# the RGB run takes the albedo as given
printf 'name = "bare"\n[[layer]]\ninterface = "lambertian"\nalbedo = [0.8, 0.5, 0.2]\n' > "$out/gold/bare.toml"
printf 'name = "bare-white"\n[[layer]]\ninterface = "lambertian"\nalbedo = 1\n' > "$out/gold/bare-white.toml"
expect 0 "spectral run: layer 1's albedo \[0.8, 0.5, 0.2\] uplifted to the spectrum: s\(nm\) = S\(" -- "$gonio" check "$out/gold/bare.toml"
for b in bare bare-white; do
    expect 0 "wrote" -- "$gonio" simulate "$out/gold/$b.toml" --spectral --theta-i 0 --paths 1e4 --quiet --out "$out/gold/$b-spectral"
done
expect 0 "wrote" -- "$gonio" simulate "$out/gold/bare.toml" --theta-i 0 --paths 1e4 --quiet --out "$out/gold/bare-rgb"
/usr/bin/python3 - "$out/gold" <<'PY' && ok || bad "--spectral: a bare Lambertian's RGB albedo is not its uplifted spectrum's colour"
import json, sys
d = sys.argv[1]
def srgb(run): return json.load(open(d + "/" + run + "/summary.json"))["angles"][0]["srgb"]["reflected"]
albedo, white = srgb("bare-spectral"), srgb("bare-white-spectral")
assert all(abs(w - 1) < 5e-4 for w in white), white
for got, w, want in zip(albedo, white, (0.8, 0.5, 0.2)):
    assert abs(got / w - want) < 2e-4, (albedo, white)
e = json.load(open(d + "/bare-rgb/summary.json"))["angles"][0]["energy"]
assert all(abs(e[c]["reflected"] - v) < 1e-6 for c, v in zip("RGB", (0.8, 0.5, 0.2))), e
PY
expect 2 "--bands and --band-paths go with --spectral" -- "$gonio" simulate "$out/gold/grey.toml" --bands 20 --paths 1e4 --quiet --out "$out/gold/no"
expect 2 "--bands: the band width \(7 nm\) must divide" -- "$gonio" simulate "$out/gold/grey.toml" --spectral --bands 7 --paths 1e4 --quiet --out "$out/gold/no"
expect 2 "--band-points: 17 wavelengths per band: from 1 to 16" -- "$gonio" simulate "$out/gold/grey.toml" --spectral --band-points 17 --paths 1e4 --quiet --out "$out/gold/no"
# --band-paths measured: a pilot of --paths / 8 in every pass, then the shares it measures; every pass keeps at least
# its pilot, the passes add up to at least passes x --paths, the blue passes (Z's) get more than the red ones on gold
# (whose red reflects most, so its red bins are the least noisy); the same seed gives the same bytes; --rse refused
for k in 1 2; do
    expect 0 "wrote" -- "$gonio" simulate stacks/coats/coated-gold.toml --spectral --band-paths measured --bands 20 --theta-i 30 --paths 8e4 --quiet --out "$out/gold/measured$k"
done
cmp -s "$out/gold/measured1/coated-gold.exr" "$out/gold/measured2/coated-gold.exr" && ok || bad "--band-paths measured: the same seed gave other bytes"
/usr/bin/python3 - "$out/gold/measured1/summary.json" <<'PY' && ok || bad "--band-paths measured: the passes' paths are not the pilot's shares"
import json, sys
j = json.load(open(sys.argv[1]))
paths = j["angles"][0]["paths"]
assert j["spectral"]["pass_paths"].startswith("measured"), j["spectral"]["pass_paths"]
assert len(paths) == 7 and min(paths) >= 10000 and sum(paths) >= 7 * 80000, paths
assert paths[1] > paths[5] and paths[2] > paths[6], paths   # 420-500 nm (Z) above 600-700 nm (gold's red)
PY
expect 2 "--band-paths measured shares --paths" -- "$gonio" simulate stacks/coats/coated-gold.toml --spectral --band-paths measured --rse 0.1 --theta-i 30 --quiet --out "$out/gold/no"
# with --rse and no --band-paths the passes share by weight (each runs to its own error), and summary.json says so
expect 0 "wrote" -- "$gonio" simulate stacks/coats/coated-gold.toml --spectral --bands 40 --rse 0.5 --theta-i 30 --paths 4e4 --quiet --out "$out/gold/rse-default"
grep -q '"pass_paths": "by the pass.s weight in X + Y + Z' "$out/gold/rse-default/summary.json" && ok || bad "--spectral --rse without --band-paths: not shared by weight"
# white furnaces band by band: a smooth N-BK7 slab (dispersive: a run per band) and a smooth coat over a white
# Lambertian (the passes side by side; every trip traced, --no-series, so that no path's weight is an estimate) absorb
# nothing, so every band's reflected and transmitted sum to 1
printf 'name = "coat-white"\n[[layer]]\ninterface = "dielectric"\nior = 1.5\n[[layer]]\ninterface = "lambertian"\nalbedo = 1\n' > "$out/gold/coat-white.toml"
expect 0 "wrote" -- "$gonio" simulate "$out/gold/coat-white.toml" --spectral --no-series --bands 20 --theta-i 0,70 --paths 2e4 --quiet --out "$out/gold/furnace"
for f in furnace bk7; do
    /usr/bin/python3 - "$out/gold/$f/summary.json" <<'PY' && ok || bad "--spectral: $f loses or gains energy in some band (white furnace)"
import json, sys
for a in json.load(open(sys.argv[1]))["angles"]:
    s = a["spectral"]
    for nm, r, t in zip(s["wavelength_nm"], s["reflected"], s.get("transmitted") or [0] * len(s["reflected"])):
        assert abs(r + t - 1) < 1e-6, (a["theta_i"], nm, r, t)
PY
done
expect 2 "--band-paths: expected even, weight or measured" -- "$gonio" simulate stacks/coats/coated-gold.toml --spectral --band-paths neyman --quiet --out "$out/gold/no"
# compare --rgb-vs-spectral (docs/SPECTRAL.md): on a grey stack the two runs differ by their noise alone (the albedo's
# colour to a hundredth of a CIEDE2000 unit per se; the bins' median difference is the noise floor the run reports);
# its files are the two runs' own numbers; the f0 reduction says where it leaves the sRGB gamut; misuse refused
expect 0 "lit bins" -- "$gonio" compare "$out/gold/grey.toml" --rgb-vs-spectral --theta-i 30 --paths 4e5 --dtheta 5 --dphi 10 --quiet --out "$out/gold/rvs-grey"
/usr/bin/python3 - "$out/gold/rvs-grey/rgb-vs-spectral.json" <<'PY' && ok || bad "--rgb-vs-spectral: a grey stack's runs differ by more than their noise"
import json, sys
a = json.load(open(sys.argv[1]))["angles"][0]
assert a["albedo"]["de2000"] < 0.3 and a["albedo"]["de_itp"] < 1, a["albedo"]   # 5 se of the albedo's lightness
ratio = a["de2000"]["median"] / a["median_de2000_noise"]
assert a["lit_bins"] > 100 and 0.8 < ratio < 1.5, (a, ratio)
PY
expect 0 "lit bins" -- "$gonio" compare "$out/gold/gold.toml" --rgb-vs-spectral --reduction f0 --theta-i 0 --paths 2e5 --quiet --out "$out/gold/rvs-gold"
/usr/bin/python3 - "$out/gold/rvs-gold" <<'PY' && ok || bad "--rgb-vs-spectral: its colours are not the two runs' numbers"
import csv, json, sys
d = sys.argv[1]
j = json.load(open(d + "/rgb-vs-spectral.json"))
assert j["reduction"] == "f0" and "Au red F0 1.03" in j["reduction_clipped"], j["reduction_clipped"]
a = j["angles"][0]["albedo"]
spectral = json.load(open(d + "/spectral/summary.json"))["angles"][0]["xyz"]["reflected"]
e = json.load(open(d + "/rgb/summary.json"))["angles"][0]["energy"]
rgb = [e[c]["reflected"] for c in "RGB"]
m = [[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]]   # IEC 61966-2-1
xyz = [sum(m[r][c] * rgb[c] for c in range(3)) for r in range(3)]
assert all(abs(x - y) < 1e-6 for x, y in zip(a["xyz_spectral"], spectral)), (a, spectral)
assert all(abs(x - y) < 1e-6 for x, y in zip(a["xyz_rgb"], xyz)), (a, xyz)
rows = list(csv.DictReader(open(d + "/rgb-vs-spectral.csv")))
assert rows and set(rows[0]) >= {"theta_i", "side", "de2000", "de_itp", "de2000_noise", "lit"}, rows[:1]
PY
# compare --spectral: the research models band by band, the production models in RGB; on a grey stack either way a
# model's albedo Y is the RGB compare's and its X and Z are D65's white times it; a model that cannot represent the
# stack says why
expect 0 "wrote" -- "$gonio" compare "$out/gold/grey.toml" --theta-i 30 --paths 1e5 --dtheta 5 --dphi 10 --models ww09,openpbr --no-report --quiet --out "$out/gold/sc-rgb"
expect 0 "belcour18-forward +not evaluated: .*forward propagation" -- "$gonio" compare "$out/gold/grey.toml" --spectral --bands 40 --theta-i 30 --paths 1e5 --dtheta 5 --dphi 10 --models ww09,openpbr,belcour18-forward --quiet --out "$out/gold/sc"
/usr/bin/python3 - "$out/gold/sc-rgb/summary.json" "$out/gold/sc/models-spectral.json" <<'PY' && ok || bad "compare --spectral: a grey stack's models are not their RGB values in every band"
import json, sys
rgb = {m["id"]: m for m in json.load(open(sys.argv[1]))["models"]}
models = json.load(open(sys.argv[2]))["models"]
assert sorted(m["id"] for m in models) == ["belcour18-forward", "openpbr", "ww09"], models
assert "forward propagation" in [m for m in models if m["id"] == "belcour18-forward"][0]["not_evaluated"]
for m in (m for m in models if m["id"] != "belcour18-forward"):
    X, Y, Z = m["angles"][0]["albedo"]["xyz_model"]
    want = rgb[m["id"]]["angles"][0]["albedo_model"][0]
    assert abs(Y - want) < 1e-6 * want, (m["id"], Y, want)
    assert abs(X / Y - 0.9505) < 2e-3 and abs(Z / Y - 1.089) < 3e-3, (m["id"], X, Y, Z)
    assert m["angles"][0]["lit_bins"] > 100 and m["angles"][0]["median_de2000_noise"] > 0, m["angles"][0]
    # a production model (an artist's colours as inputs) in RGB as defined, a research model band by band
    assert m["evaluated"].startswith("in RGB" if m["id"] == "openpbr" else "band by band"), m["evaluated"]
PY
expect 2 "give --spectral or --rgb-vs-spectral, not both" -- "$gonio" compare "$out/gold/grey.toml" --spectral --rgb-vs-spectral --paths 1e4 --quiet --out "$out/gold/no"
expect 2 "forest" -- "$gonio" compare "$out/gold/grey.toml" --spectral --render nowhere --paths 1e4 --quiet --out "$out/gold/no"
expect 0 "coated-gold +[0-9.]+ +[0-9.]+ +[0-9.]+/[0-9.]+/[0-9.]+ " -- "$gonio" bench --spectral stacks/coats/coated-gold.toml --theta-i 30 --paths 1e5 --bands 40
expect 2 "bench --spectral prints its table only" -- "$gonio" bench --spectral --out "$out/gold/no"
expect 2 "--reduction goes with --spectral or --rgb-vs-spectral" -- "$gonio" compare "$out/gold/grey.toml" --reduction f0 --paths 1e4 --quiet --out "$out/gold/no"
expect 2 "unknown RGB reduction 'cmf'" -- "$gonio" compare "$out/gold/grey.toml" --rgb-vs-spectral --reduction cmf --paths 1e4 --quiet --out "$out/gold/no"
expect 2 "it evaluates no models" -- "$gonio" compare "$out/gold/grey.toml" --rgb-vs-spectral --models ww09 --paths 1e4 --quiet --out "$out/gold/no"
# a killed run keeps its checkpoint (--checkpoint-seconds), and --resume from it gives the bytes of one whole run
expect 0 "wrote" -- "$gonio" simulate stacks/frosted-metal.toml --theta-i 0,60 --paths 3e7 --seed 3 --quiet --out "$out/ck-whole"
"$gonio" simulate stacks/frosted-metal.toml --theta-i 0,60 --paths 3e7 --seed 3 --quiet --checkpoint-seconds 0.2 --out "$out/ck" > /dev/null 2>&1 &
ck_pid=$!
# the first checkpoint follows the device's start and the shaders' JIT: seconds on a loaded machine, so wait for it
for _ in $(seq 6000); do [ -s "$out/ck/state.gonio" ] && break; kill -0 "$ck_pid" 2> /dev/null || break; sleep 0.05; done
sleep 0.5
kill -9 "$ck_pid" 2> /dev/null; wait "$ck_pid" 2> /dev/null
[ -s "$out/ck/state.gonio" ] && [ ! -e "$out/ck/summary.json" ] && ok || bad "the killed run left no checkpoint (or finished before the kill)"
expect 0 "wrote" -- "$gonio" simulate stacks/frosted-metal.toml --quiet --resume "$out/ck"   # its angles, paths, seed: recorded
cmp -s "$out/ck/slices.csv" "$out/ck-whole/slices.csv" && ok || bad "a run resumed from its checkpoint differs from one uninterrupted run"
# --rse stops at the target and says so
expect 0 "paths \(rse\), median rse 0\.0[0-9]" -- "$gonio" simulate stacks/transparent-slab.toml --theta-i 30 --dtheta 10 --dphi 20 --rse 0.1 --quiet --out "$out/rse"
expect 0 "paths \(rse\), median rse [0-9.]+, worst 0\.0[0-9]" -- "$gonio" simulate stacks/transparent-slab.toml --theta-i 30 --dtheta 10 --dphi 20 --rse 0.1 --rse-quantile 1 --quiet --out "$out/rse1"
/usr/bin/python3 - "$out/rse/summary.json" "$out/rse1/summary.json" <<'PY' && ok || bad "summary.json's relative_se does not show the quantile --rse stopped on"
import json, sys
med, worst = (json.load(open(p))["angles"][0] for p in sys.argv[1:])
assert med["relative_se"]["median"] <= 0.1 < med["relative_se"]["worst"], med["relative_se"]
assert worst["relative_se"]["worst"] <= 0.1 and worst["paths"] > med["paths"], (worst["relative_se"], worst["paths"], med["paths"])
PY
grep -q '"stopped_by": "rse"' "$out/rse/summary.json" && ok || bad "summary.json lacks stopped_by rse"
expect 0 "paths \(max_seconds\)" -- "$gonio" simulate stacks/plastic.toml --theta-i 30 --rse 0.0001 --max-seconds 1 --quiet --out "$out/maxs"
# angles side by side (the default): each takes its share of the time, and --max-seconds stops each
expect 0 "theta_i +60: .*paths \(max_seconds\)" -- "$gonio" simulate stacks/plastic.toml --theta-i 0,60 --rse 0.0001 --max-seconds 0.5 --quiet --out "$out/maxs2"
[ "$(grep -c '"stopped_by": "max_seconds"' "$out/maxs2/summary.json")" = 2 ] && ok || bad "--max-seconds did not stop both angles side by side"
# angles side by side and one at a time (--angles-per-dispatch 1), a grazing one among them: the same bytes
expect 0 "wrote" -- "$gonio" simulate stacks/transparent-slab.toml --theta-i 0:88:8,89.9 --paths 2e4 --orders --quiet --out "$out/apd0"
expect 0 "wrote" -- "$gonio" simulate stacks/transparent-slab.toml --theta-i 0:88:8,89.9 --paths 2e4 --orders --angles-per-dispatch 1 --quiet --out "$out/apd1"
cmp -s "$out/apd0/slices.csv" "$out/apd1/slices.csv" && ok || bad "angles side by side differ from one angle at a time"
# the Lambertian series: on by default over a Lambertian base, reported in summary.json, off with --no-series
expect 0 "wrote" -- "$gonio" simulate stacks/plastic.toml --theta-i 30 --paths 1e5 --quiet --out "$out/ser"
series() {   # series SUMMARY.json: the walk's lambertian_series member, as Python prints it
    /usr/bin/python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["walk"]["lambertian_series"])' "$1"
}
series "$out/ser/summary.json" | grep -q "^{'applied': True, 'trip_escaped'" && ok || bad "summary.json lacks the applied series"
expect 0 "wrote" -- "$gonio" simulate stacks/plastic.toml --theta-i 30 --paths 1e5 --quiet --no-series --out "$out/noser"
[ "$(series "$out/noser/summary.json")" = "{'applied': False, 'reason': '--no-series'}" ] && ok || bad "summary.json lacks why the series is off"
expect 0 "wrote" -- "$gonio" simulate stacks/hard/ior-3.toml --theta-i 30 --paths 1e4 --quiet --out "$out/ser3"
series "$out/ser3/summary.json" | grep -q "^{'applied': False, 'reason': 'the quadrature" && ok || bad "summary.json lacks why the series does not apply to ior-3"
# the booking estimators: the entry's both branches and the exit estimate on a coat over a conductor, reported in
# summary.json, off with --no-branching (recorded: a resumed run continues with the walk it began with)
walk_flags() {   # walk_flags SUMMARY.json: entry_branch and exit_estimates, as Python prints them
    /usr/bin/python3 -c 'import json, sys; w = json.load(open(sys.argv[1]))["walk"]; print(w["entry_branch"], w["exit_estimates"])' "$1"
}
expect 0 "wrote" -- "$gonio" simulate stacks/metallic-paint.toml --theta-i 30 --paths 1e5 --quiet --out "$out/br"
[ "$(walk_flags "$out/br/summary.json")" = "True 1" ] && ok || bad "summary.json lacks the booking estimators on metallic paint"
expect 0 "wrote" -- "$gonio" simulate stacks/metallic-paint.toml --theta-i 30 --paths 1e5 --quiet --no-branching --out "$out/nobr"
[ "$(walk_flags "$out/nobr/summary.json")" = "False 0" ] && ok || bad "--no-branching left an estimator on"
[ "$(walk_flags "$out/ser/summary.json")" = "False 0" ] && ok || bad "the booking estimators ran beside the Lambertian series"
expect 0 "200000 paths" -- "$gonio" simulate stacks/metallic-paint.toml --resume "$out/nobr" --paths 2e5 --quiet
[ "$(walk_flags "$out/nobr/summary.json")" = "False 0" ] && ok || bad "a resumed --no-branching run turned the estimators on"
expect 2 "--no-branching given differs from the earlier run's not given" -- "$gonio" simulate stacks/metallic-paint.toml --paths 3e5 --quiet --resume "$out/br" --no-branching
# compare: the models on the reference's bins, their metrics, and the reasons of those that cannot apply
expect 0 "ww-corrected +[0-9]+\.[0-9]{4}" -- "$gonio" compare stacks/plastic.toml --theta-i 0,60 --paths 2e5 --quiet --out "$out/cmp"
grep -q '"rmse_remapped"' "$out/cmp/summary.json" && ok || bad "compare summary.json lacks model metrics"
[ "$(grep -c '^ww-corrected,' "$out/cmp/slices.csv")" = 32400 ] && ok || bad "compare slices.csv lacks the model rows (2 angles x 16200 bins)"
for f in slices.png albedo.png topview-0.png topview-1.png report.html; do
    [ -s "$out/cmp/$f" ] && ok || bad "compare did not make $f"
done
# by default the models as published run, not their variants (counted in one line); --models all runs them
expect 0 "[0-9]+ variants of these models not run \(--models all runs them" -- "$gonio" compare stacks/plastic.toml --theta-i 30 --paths 1e5 --no-report --quiet --out "$out/cmpdef"
! cut -d, -f1 "$out/cmpdef/slices.csv" | grep -q '+' && ok || bad "compare ran a variant without --models all"
/usr/bin/python3 -c 'import json, sys; sys.exit(not any(m["id"] == "openpbr+dev1.2" and not m["applicable"] and "a variant: --models all" in m["reason"] for m in json.load(open(sys.argv[1]))["models"]))' \
    "$out/cmpdef/summary.json" && ok || bad "compare summary.json does not say why the variants did not run"
# --models: only the selected models run (the others are counted in one line as not selected); an unknown id is refused
expect 0 "[0-9]+ more models not selected by --models" -- "$gonio" compare stacks/plastic.toml --theta-i 30 --paths 1e5 --no-report --models albedo-scaling --out "$out/cmpsel"
[ "$(cut -d, -f1 "$out/cmpsel/slices.csv" | sort -u | tr '\n' ' ')" = "albedo-scaling reference source " ] && ok || bad "compare --models wrote rows of other models"
expect 2 "no model 'ww10' \(the models: ww09, " -- "$gonio" compare stacks/plastic.toml --models ww09,ww10 --out "$out/cmpsel2"
expect 2 "option --models does not apply to .gonio simulate." -- "$gonio" simulate stacks/plastic.toml --models ww09 --out "$out/cmpsel3"
# a model as files: nodes, the user's values, score. f = 1 gives exactly 1 in every bin (the weights of a bin sum to
# 1); the Python example runs; broken values are refused with their line, a reference of other bins with why
expect 0 "wrote" -- "$gonio" simulate stacks/plastic.toml --theta-i 0,45 --dtheta 5 --dphi 10 --paths 1e5 --quiet --out "$out/nref"
expect 0 "20736 nodes" -- "$gonio" nodes stacks/plastic.toml --theta-i 0,45 --dtheta 5 --dphi 10 --out "$out/nodes"
head -1 "$out/nodes/nodes.csv" | grep -qx "theta_i,side,bin,lx,ly,lz,vx,vy,vz,weight" && ok || bad "nodes.csv header"
python3 -c "import sys; n = sum(1 for _ in open(sys.argv[1])) - 1; open(sys.argv[2], 'w').write('r,g,b\n' + '1,1,1\n' * n)" "$out/nodes/nodes.csv" "$out/nodes/ones.csv"
expect 0 "wrote" -- "$gonio" score "$out/nodes" --values "$out/nodes/ones.csv" --id ones --reference "$out/nref" --no-report --out "$out/ones"
python3 - "$out/ones/slices.csv" <<'PY' && ok || bad "score: f = 1 does not give 1 in every bin"
import csv, sys
v = [float(r[c]) for r in csv.DictReader(open(sys.argv[1])) if r["source"] == "ones" for c in "rgb"]
assert len(v) == 2 * 648 * 3 and max(abs(x - 1) for x in v) < 1e-12, (len(v), max(abs(x - 1) for x in v))
PY
# the same nodes as .npy, and values as .npy (numpy.save), give the same bytes as the CSVs
py="${GONIO_PYTHON:-$(dirname "$gonio")/venv/bin/python}"; [ -x "$py" ] || py=python3   # the Python gonio runs (numpy)
"$py" -c "import numpy as np, sys; n = np.load(sys.argv[1]); assert n.shape[1] == 10 and abs(n[:, 9].sum() - 2 * 648) < 1e-9; np.save(sys.argv[2], np.ones((len(n), 3)))" "$out/nodes/nodes.npy" "$out/nodes/ones.npy" && ok || bad "nodes.npy is not the nodes"
expect 0 "wrote" -- "$gonio" score "$out/nodes" --values "$out/nodes/ones.npy" --id ones --reference "$out/nref" --no-report --out "$out/ones-npy"
cmp -s "$out/ones/slices.csv" "$out/ones-npy/slices.csv" && ok || bad "score: .npy values differ from the same values as CSV"
"$py" examples/python_model.py "$out/nodes" "$out/nodes/values.csv" && ok || bad "examples/python_model.py failed"
expect 0 "lambert-under-fresnel +[0-9]+\.[0-9]{4}" -- "$gonio" score "$out/nodes" --values "$out/nodes/values.csv" --id lambert-under-fresnel --reference "$out/nref" --no-report --out "$out/mine"
grep -q '"id": "lambert-under-fresnel"' "$out/mine/summary.json" && ok || bad "score: summary.json lacks the model"
printf 'r,g,b\n1,1\n' > "$out/nodes/short.csv"
expect 2 "short.csv:2: expected three numbers" -- "$gonio" score "$out/nodes" --values "$out/nodes/short.csv" --id x --reference "$out/nref" --out "$out/x"
head -11 "$out/nodes/ones.csv" > "$out/nodes/ten.csv"
expect 2 "ten.csv:10: 10 values for 20736 nodes" -- "$gonio" score "$out/nodes" --values "$out/nodes/ten.csv" --id x --reference "$out/nref" --out "$out/x"
expect 2 "not a run of the nodes' stack, angles and bins \(other incident angles\)" -- "$gonio" score "$out/nodes" --values "$out/nodes/ones.csv" --id x --reference "$out/cmpsel" --out "$out/x"
# your own model as one GLSL file (--model): compiled at run time, integrated and scored as a built-in one is
expect 0 "schlick-coat: reciprocal as measured" -- "$gonio" compare stacks/plastic.toml --model examples/user_model.glsl --models ww-corrected,schlick-coat --theta-i 0,60 --dtheta 2 --dphi 4 --paths 2e5 --no-report --quiet --out "$out/user"
python3 - "$out/user/summary.json" <<'PY' && ok || bad "compare --model: summary.json lacks the user's model as scored"
import json, sys
s = json.load(open(sys.argv[1]))
m = {e["id"]: e for e in s["models"]}["schlick-coat"]
assert m["scored"] and m["integration"] == "black box" and m["file"] == "examples/user_model.glsl", m
assert len(m["angles"]) == 2 and m["angles"][0]["verdict"], m
assert s["model_stage"]["user_compile_seconds"] > 0
PY
grep -q "^schlick-coat," "$out/user/slices.csv" && ok || bad "compare --model: no rows in slices.csv"
# a model file of its id alone runs on any stack; gonio measures its reciprocity and energy and says what it claims
expect 0 "one-sided-fresnel: not reciprocal as measured" -- "$gonio" compare stacks/plastic.toml --model tests/user_models/id_only.glsl --models one-sided-fresnel --theta-i 30 --dtheta 3 --dphi 6 --paths 1e4 --no-report --quiet --out "$out/idonly"
/usr/bin/python3 - "$out/idonly/summary.json" "$out/user/summary.json" <<'PY' && ok || bad "summary.json lacks the claims and the measured reciprocity and albedo"
import json, sys
m = {e["id"]: e for e in json.load(open(sys.argv[1]))["models"]}["one-sided-fresnel"]
assert m["family"] == "your models" and m["claims"] == {"reciprocal": None, "energy_conserving": None}, m
assert m["measured"]["reciprocity"]["reciprocal"] is False and m["measured"]["reciprocity"]["pairs"] == 196, m
assert 0 < m["measured"]["largest_albedo"]["value"] < 1, m
s = {e["id"]: e for e in json.load(open(sys.argv[2]))["models"]}
assert s["schlick-coat"]["claims"]["reciprocal"] is True and s["schlick-coat"]["measured"]["reciprocity"]["reciprocal"], s
assert s["ww-corrected"]["family"] == "Weidlich-Wilkie" and "reciprocity" not in s["ww-corrected"]["measured"], s
PY
expect 2 "tests/user_models/broken.glsl:8: .*undeclared_thing" -- "$gonio" compare stacks/plastic.toml --model tests/user_models/broken.glsl --paths 10 --out "$out/x"
expect 2 "retro.glsl.*cannot open the model file" -- "$gonio" compare stacks/plastic.toml --model "$out/retro.glsl" --paths 10 --out "$out/x"
expect 2 "the id 'schlick-coat' is taken" -- "$gonio" compare stacks/plastic.toml --model examples/user_model.glsl --model examples/user_model.glsl --paths 10 --out "$out/x"
expect 2 "--models: no model 'nope' \(the models: .*schlick-coat" -- "$gonio" compare stacks/plastic.toml --model examples/user_model.glsl --models nope --paths 10 --out "$out/x"
# a model that returns NaN or negative values is reported (where), never scored, and the run exits 1
expect 1 "nan-test: its bins cannot be used: [0-9]+ quadrature nodes in [0-9]+ bins where f is NaN, infinite or negative \(theta_i 30 R" -- "$gonio" compare stacks/plastic.toml --model tests/user_models/nan_where_v_x_above_half.glsl --models nan-test --theta-i 30 --dtheta 3 --dphi 6 --paths 1e4 --no-report --quiet --out "$out/nan"
python3 -c "import json,sys; m={e['id']: e for e in json.load(open(sys.argv[1]))['models']}['nan-test']; assert not m['scored'] and m['invalid_values']['bins'] > 0 and m['invalid_values']['first_bins'][0]['theta_i'] == 30" "$out/nan/summary.json" && ok || bad "a NaN model is not reported in summary.json"
! grep -q "^nan-test," "$out/nan/slices.csv" && ok || bad "a NaN model's bins were written"
# a sweep file may list model files: their rows in sweep.csv beside the built-in models'
expect 0 "wrote .*sweep.csv" -- "$gonio" sweep tests/sweeps/tiny-user-model.toml --quiet --out "$out/swuser"
[ "$(grep -c ',schlick-coat,' "$out/swuser/sweep.csv")" = 2 ] && ok || bad "sweep: the model file's rows are not in sweep.csv"
printf 'name = "b"\nstack = "%s/stacks/plastic.toml"\nmodels = ["%s/tests/user_models/broken.glsl"]\ntheta_i = [30]\n[[vary]]\nlayer = 1\nkey = "roughness"\nvalues = [0.1]\n' "$PWD" "$PWD" > "$out/bad-model-sweep.toml"
expect 2 "broken.glsl:8: .*undeclared_thing" -- "$gonio" sweep "$out/bad-model-sweep.toml" --quiet --out "$out/swbad"
# the figures are not blank: their pixels vary
# the figures are not blank (their pixels vary) and have the size they are drawn at (at least 400 x 250 pixels)
figures_ok() {   # figures_ok DIR FILE...
    /usr/bin/python3 -c "
import matplotlib.image as m, sys
for f in sys.argv[2:]:
    a = m.imread(sys.argv[1] + '/' + f)
    if a.std() <= 0.05 or a.shape[0] < 250 or a.shape[1] < 400:
        sys.exit(f + ': blank or too small ' + str(a.shape))" "$@"
}
figures_ok "$out/cmp" slices.png albedo.png topview-0.png && ok || bad "a figure is blank or too small"
grep -q "rmse remapped" "$out/cmp/report.html" && ok || bad "report.html lacks the metric table"
grep -aq "theta_i=60 R model=ww-corrected" "$out/cmp/plastic.exr" && ok || bad "the EXR lacks the model parts"
"$gonio" compare stacks/transparent-slab.toml --paths 1e4 --quiet --models all --out "$out/cmp2" > "$out/cmp2.txt" 2> "$out/cmp2.err" \
    && grep -qE "not applicable: .*transmissive" "$out/cmp2.txt" && ok || bad "compare on the slab: $(cat "$out/cmp2.txt" "$out/cmp2.err")"
# a refusal names the stack's values as written: optical depth 0.1 and phase_g -0.3, not the floats' 0.100000001 and
# -0.300000
printf 'name = "as-written"\n[[layer]]\ninterface = "dielectric"\nior = 1.5\nroughness = 0.3\noptical_depth = 0.1\n[[layer]]\ninterface = "conductor"\nroughness = 0.2\nior = 0.27\nk = 3.6\n' > "$out/as-written.toml"
expect 0 "wrote" -- "$gonio" compare "$out/as-written.toml" --theta-i 0 --paths 1e3 --models gltf-clearcoat --no-report --quiet --out "$out/as-written"
grep -q "layer 1's medium absorbs: optical depth 0.1, 0.1, 0.1)" "$out/as-written/summary.json" && ok || bad "a refusal does not give the optical depth as written: $(grep -o 'optical depth [^)]*' "$out/as-written/summary.json")"
sed -e 's/^optical_depth = 0.1$/optical_depth = 0.1\nscattering_albedo = 0.7\nphase_g = -0.3/' "$out/as-written.toml" > "$out/as-written-g.toml"
expect 0 "wrote" -- "$gonio" compare "$out/as-written-g.toml" --theta-i 0 --paths 1e3 --models belcour18-forward --no-report --quiet --out "$out/as-written-g"
grep -q "scatters with phase_g -0.3)" "$out/as-written-g/summary.json" && ok || bad "a refusal does not give phase_g as written: $(grep -o 'phase_g [^)]*' "$out/as-written-g/summary.json")"
expect 0 "scattering optical depth 0.07, absorption 0.03," -- "$gonio" check "$out/as-written-g.toml"
# the console's table of every model, both sides of four angles, and the reasons fit 120 columns
awk 'length($0) > 120 { print "longer than 120: " $0; bad = 1 } END { exit bad }' "$out/cmp2.txt" && ok || bad "compare printed lines longer than 120 columns"
/usr/bin/python3 -c 'import json, sys; sys.exit(not any(not m["applicable"] and m["reason"] for m in json.load(open(sys.argv[1]))["models"]))' \
    "$out/cmp2/summary.json" && ok || bad "compare summary.json lacks the reason"
# a slab: Belcour's forward model on both sides, rows for T in the CSV, metrics under transmission_angles,
# and the transmission slice figure
grep -q '"transmission_angles"' "$out/cmp2/summary.json" && ok || bad "compare summary.json lacks transmission metrics"
[ "$(grep -c '^belcour18-forward,0,T,' "$out/cmp2/slices.csv")" = 16200 ] && ok || bad "compare slices.csv lacks belcour18-forward T rows"
# with --models all the convention variants run beside the defaults, with rows and metrics of their own
[ "$(grep -c '^belcour18-forward+g2+tir,0,R,' "$out/cmp2/slices.csv")" = 16200 ] && ok || bad "compare slices.csv lacks belcour18-forward+g2+tir rows"
grep -q '"id": "belcour18-toplobe+g2"' "$out/cmp2/summary.json" && ok || bad "compare summary.json lacks belcour18-toplobe+g2"
figures_ok "$out/cmp2" slices-T.png albedo.png topview-0-T.png && ok || bad "compare did not draw slices-T.png for a slab (or it is blank)"
expect 0 "belcour18-forward +[0-9]+\.[0-9]{4}" -- "$gonio" compare stacks/frosted-metal.toml --theta-i 30 --paths 1e5 --no-belcour-tables --no-report --quiet --out "$out/cmp3"
expect 0 "ww-corrected .*Bati" -- "$gonio" models
expect 0 "tm21 .*Randrianandrasana" -- "$gonio" models
expect 0 "tm21\+g2 .*gonio's variant of tm21" -- "$gonio" models
# the authors' own other readings are variants too, and a production model says what an artist would set for a stack
expect 0 "openpbr\+pr261 .*a variant of openpbr \(OpenPBR Surface" -- "$gonio" models
expect 0 "its parameters for a stack: clearcoat c = 1, clearcoat roughness r_c = sqrt\(alpha_coat\)" -- "$gonio" models
# bench: throughput table, and with --out the convergence report, the models' cost against error, the atlas
expect 0 "transparent-slab .*x" -- "$gonio" bench stacks/transparent-slab.toml --paths 1e5 --cpu-paths 1e4 --atlas 2 --atlas-paths 1e5 --out "$out/bench"
for key in '"relative_rmse"' '"seconds_to_rse_1pct"' '"specialised_over_general"' '"device_over_cpu_twin"' '"ns_per_evaluation"' '"device_seconds_per_grid"' '"atlas"' '"best"'; do
    grep -q "$key" "$out/bench/bench.json" && ok || bad "bench.json lacks $key"
done
figures_ok "$out/bench" convergence.png pareto.png atlas.png && ok || bad "bench figures missing, blank or too small"
grep -q "Error atlas" "$out/bench/bench.html" && grep -q "pareto.png" "$out/bench/bench.html" && ok || bad "bench.html lacks its sections"
# bench --render: gonio render's stages timed per stack (the table, the reference, each model)
expect 0 "plastic .*render 16x16 under studio .*8 models .*ww09 [0-9.]* .*openpbr [0-9.]*" -- "$gonio" bench stacks/plastic.toml --paths 2e5 --cpu-paths 1e4 --render studio --render-size 16
expect 2 "render-size and --render-paths set up --render ENV" -- "$gonio" bench stacks/plastic.toml --render-size 16
expect 2 "bench takes one --theta-i" -- "$gonio" bench stacks/plastic.toml --theta-i 0,30 --out "$out/bench2"
# random-stack: seeded, valid (gonio check accepts every file), the same bytes for the same seed
expect 0 "wrote .*random-5-2.toml" -- "$gonio" random-stack --seed 5 --count 3 --out "$out/rs"
for i in 0 1 2; do
    expect 0 "is a valid stack" -- "$gonio" check "$out/rs/random-5-$i.toml"
done
expect 0 'name = "random-5-1"' -- "$gonio" random-stack --seed 5 --count 2
"$gonio" random-stack --seed 5 --count 3 > "$out/rs1.txt"; "$gonio" random-stack --seed 5 --count 3 > "$out/rs2.txt"
cmp -s "$out/rs1.txt" "$out/rs2.txt" && ok || bad "random-stack: same seed gave different stacks"
"$gonio" random-stack --seed 6 > "$out/rs3.txt"
cmp -s "$out/rs1.txt" "$out/rs3.txt" && bad "random-stack: different seeds gave the same stacks" || ok
expect 2 "--count must be in" -- "$gonio" random-stack --count 0
# sweep: shards merged give the bytes of the unsplit run; a killed run resumes; damaged shards are refused
sw=tests/sweeps/tiny.toml
expect 0 "wrote .*sweep.csv" -- "$gonio" sweep "$sw" --quiet --out "$out/sw1"
[ "$(wc -l < "$out/sw1/sweep.csv")" -gt 1 ] && ok || bad "sweep.csv has no rows"
expect 0 "2 configurations computed in shard 2/2" -- "$gonio" sweep "$sw" --shard 2/2 --quiet --out "$out/sw2"
expect 2 "cannot merge .*configuration 0: missing" -- "$gonio" merge "$out/sw2"
expect 0 "2 configurations computed in shard 1/2" -- "$gonio" sweep "$sw" --shard 1/2 --quiet --out "$out/sw2"
expect 0 "wrote .*sweep.csv" -- "$gonio" merge "$out/sw2"
cmp -s "$out/sw1/sweep.csv" "$out/sw2/sweep.csv" && ok || bad "merged shards differ from the unsplit sweep"
# a sweep at an incident azimuth: its column after theta_i, the rows of the plane's sweep; not with [spectral]
sed -e 's/^theta_i = \[30\]/theta_i = [30]\nphi_i = 90/' -e "s#\"\.\./\.\./stacks#\"$PWD/stacks#" "$sw" > "$out/sw-az.toml"
expect 0 "wrote .*sweep.csv" -- "$gonio" sweep "$out/sw-az.toml" --quiet --out "$out/sw-az"
head -1 "$out/sw-az/sweep.csv" | grep -q ",theta_i,phi_i,side,model," && grep -q "^0,0.05,0.01,30,90,R,ww09," "$out/sw-az/sweep.csv" &&
    [ "$(wc -l < "$out/sw-az/sweep.csv")" = "$(wc -l < "$out/sw1/sweep.csv")" ] && ok ||
    bad "sweep phi_i = 90: no phi_i column, or not the plane's rows: $(head -2 "$out/sw-az/sweep.csv")"
sed -e 's/^theta_i = \(.*\)/theta_i = \1\nphi_i = 10/' -e "s#\"\.\./\.\./stacks#\"$PWD/stacks#" tests/sweeps/tiny-spectral.toml > "$out/sw-az-spectral.toml"
expect 2 "sw-az-spectral.toml:[0-9]*: phi_i: a \[spectral\] sweep traces the plane of incidence" -- "$gonio" sweep \
    "$out/sw-az-spectral.toml" --quiet --out "$out/sw-az-spectral"
expect 2 "already has configuration 0 .*--resume" -- "$gonio" sweep "$sw" --quiet --out "$out/sw2"
# sweep.json is read as JSON: a damaged one is refused, saying which file
mkdir -p "$out/swj" && printf '{"hash": ' > "$out/swj/sweep.json"
expect 2 "swj/sweep.json: not valid JSON" -- "$gonio" merge "$out/swj"
# a sweep where the Lambertian series applies to some configurations only runs (general walk for all)
expect 0 "wrote .*sweep.csv" -- "$gonio" sweep tests/sweeps/tiny-lambertian.toml --quiet --out "$out/swl"
# kill a run once its first configuration is written, then resume it
"$gonio" sweep "$sw" --quiet --out "$out/sw3" >/dev/null 2>&1 &
pid=$!
for _ in $(seq 600); do [ -e "$out/sw3/configs/c-00000000.csv" ] && break; sleep 0.05; done
kill -9 "$pid" 2>/dev/null; wait "$pid" 2>/dev/null
ls "$out/sw3/configs/"*.tmp* >/dev/null 2>&1 && rm -f "$out/sw3/configs/"*.tmp*   # a write cut short is never renamed in
expect 0 "wrote .*sweep.csv" -- "$gonio" sweep "$sw" --resume --quiet --out "$out/sw3"
cmp -s "$out/sw1/sweep.csv" "$out/sw3/sweep.csv" && ok || bad "a killed and resumed sweep differs from the unsplit one"
sed -i '1s/^# gonio sweep ./# gonio sweep X/' "$out/sw3/configs/c-00000001.csv"
expect 2 "configuration 1: written by another sweep" -- "$gonio" merge "$out/sw3"
head -n 3 "$out/sw1/configs/c-00000002.csv" > "$out/sw3/configs/c-00000002.csv"
expect 2 "configuration 2: truncated" -- "$gonio" merge "$out/sw3"
printf 'name = "bad"\nstack = "%s/stacks/plastic.toml"\ntheta_i = [30]\n[[vary]]\nlayer = 5\nkey = "roughness"\nvalues = [0.1]\n' "$PWD" > "$out/bad-sweep.toml"
expect 2 "bad-sweep.toml:4: .*layer must be the number of one of the stack.s layers \(1 to 2" -- "$gonio" sweep "$out/bad-sweep.toml" --quiet --out "$out/sw4"
for f in atlas.png sweep.html; do [ -s "$out/sw1/$f" ] && ok || bad "sweep did not make $f"; done
# the batch size (configurations per dispatch) changes no byte of sweep.csv
expect 0 "wrote .*sweep.csv" -- "$gonio" sweep "$sw" --batch 3 --quiet --out "$out/sw5"
cmp -s "$out/sw1/sweep.csv" "$out/sw5/sweep.csv" && ok || bad "sweep.csv depends on --batch"
# a [spectral] sweep (docs/SWEEPS.md): per configuration and angle the models' colour errors, the RGB run's and the
# reference's albedo; shards merged give the unsplit bytes; gold's n and k at three wavelengths are off by 6 to 7
# CIEDE2000 (docs/SPECTRAL.md's finding), tm21 band by band by under 2
sws=tests/sweeps/tiny-spectral.toml
expect 0 "wrote .*sweep.csv" -- "$gonio" sweep "$sws" --quiet --keep-results --out "$out/sws1"
expect 0 "1 configurations computed in shard 2/2" -- "$gonio" sweep "$sws" --shard 2/2 --quiet --out "$out/sws2"
expect 0 "1 configurations computed in shard 1/2" -- "$gonio" sweep "$sws" --shard 1/2 --quiet --out "$out/sws2"
expect 0 "wrote .*sweep.csv" -- "$gonio" merge "$out/sws2"
cmp -s "$out/sws1/sweep.csv" "$out/sws2/sweep.csv" && ok || bad "a spectral sweep's merged shards differ from the unsplit run"
for f in configs/c-00000001/summary.json configs/c-00000001/coated-gold-1.exr error-vs-layer1.roughness.png; do
    [ -s "$out/sws1/$f" ] && ok || bad "the spectral sweep did not write $f"
done
/usr/bin/python3 - "$out/sws1/sweep.csv" <<'PY' && ok || bad "a spectral sweep's rows are not the colour errors expected"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
seen = {(r["config"], r["theta_i"], r["model"]): r for r in rows}
for c in ("0", "1"):
    for t in ("0", "45"):
        assert {m for (cc, tt, m) in seen if (cc, tt) == (c, t)} == {"tm21", "openpbr", "rgb-run", "reference"}, (c, t)
        rgb, tm, ref = seen[(c, t, "rgb-run")], seen[(c, t, "tm21")], seen[(c, t, "reference")]
        assert rgb["evaluated"] == "rgb-reduced-dominant" and tm["evaluated"] == "band-by-band", (rgb, tm)
        assert seen[(c, t, "openpbr")]["evaluated"] == "rgb-reduced-dominant"
        assert 4 < float(rgb["albedo_de2000"]) < 10, rgb
        assert float(tm["albedo_de2000"]) < 2, tm
        assert ref["albedo_de2000"] == "" and float(ref["albedo_y_reference"]) == float(tm["albedo_y_reference"]) > 0.4
PY
expect 2 "--batch: a \[spectral\] sweep" -- "$gonio" sweep "$sws" --batch 2 --quiet --out "$out/sws3"
expect 2 "--bench times the RGB sweep" -- "$gonio" sweep "$sws" --bench 2 --quiet --out "$out/sws3"
sed -e 's/^bands = 20/bands = 7/' -e "s|\.\./\.\./stacks|$PWD/stacks|" "$sws" > "$out/bad-spectral.toml"
expect 2 "bad-spectral.toml:11: \[spectral\] bands: the band width \(7 nm\) must divide" -- "$gonio" sweep "$out/bad-spectral.toml" --quiet --out "$out/sws3"
sed -e 's/^reduction = .*/colour = "yes"/' -e "s|\.\./\.\./stacks|$PWD/stacks|" "$sws" > "$out/bad-spectral.toml"
expect 2 "bad-spectral.toml:13: unknown key 'colour' in \[spectral\]" -- "$gonio" sweep "$out/bad-spectral.toml" --quiet --out "$out/sws3"
sed -e "s|\.\./\.\./stacks/coats/coated-gold.toml|$PWD/stacks/metallic-paint.toml|" "$sws" > "$out/bad-spectral.toml"
expect 2 "bad-spectral.toml:11: \[spectral\]: configuration 0 cannot be traced band by band: layer 2's k is given per RGB channel" -- "$gonio" sweep "$out/bad-spectral.toml" --quiet --out "$out/sws3"
{ sed -e "s|\.\./\.\./stacks|$PWD/stacks|" "$sws"; printf '[[fit]]\nmodel = "tm21"\nfree = ["layer.2.roughness"]\n'; } > "$out/bad-spectral.toml"
expect 2 "bad-spectral.toml:19: \[\[fit\]\] with \[spectral\]" -- "$gonio" sweep "$out/bad-spectral.toml" --quiet --out "$out/sws3"
# a model above the white-furnace bound is flagged in summary.json and warned about, not clamped (albedo-scaling on
# a coat of IOR 3 at 85 degrees: its base is scaled by 1 - E_coat(v), not by what the coat lets in from l)
expect 0 "albedo-scaling reflects 1\.[0-9]+ of the light it receives at theta_i 85 \(not clamped" -- \
    "$gonio" compare stacks/hard/ior-3-metal.toml --theta-i 85 --paths 1e5 --quiet --no-report --out "$out/e1"
/usr/bin/python3 - "$out/e1/summary.json" <<'PY' && ok || bad "summary.json does not flag the white-furnace bound as measured"
import json, sys
for m in json.load(open(sys.argv[1]))["models"]:
    if not m["applicable"]: continue
    for a in m["angles"]:
        over = max(a["albedo_model_total"]) > 1.001
        assert a["reflects_more_than_it_receives"] == over, (m["id"], a)
        assert not (over and m["id"] in ("ww-corrected", "belcour18-forward")), m["id"]
        if m["id"] == "albedo-scaling": assert over
PY
# rse = R in a sweep file: each configuration stops at its own checkpoint, whatever the batch; --keep-results
swr=tests/sweeps/tiny-rse.toml
expect 0 "wrote .*sweep.csv" -- "$gonio" sweep "$swr" --quiet --keep-results --out "$out/swr1"
expect 0 "wrote .*sweep.csv" -- "$gonio" sweep "$swr" --quiet --batch 1 --out "$out/swr2"
cmp -s "$out/swr1/sweep.csv" "$out/swr2/sweep.csv" && ok || bad "an rse sweep's sweep.csv depends on --batch"
paths_seen=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "reference_paths") c = i; next } { print $c }' "$out/swr1/sweep.csv" | sort -u | tr '\n' ' ')
[ "$paths_seen" = "1048576 2097152 " ] && ok || bad "rse sweep: expected configurations stopping at 2^20 and at the 2^21 cap, got '$paths_seen'"
for f in configs/c-00000000/slices.csv configs/c-00000001/summary.json configs/c-00000001/frosted-metal-1.exr; do
    [ -s "$out/swr1/$f" ] && ok || bad "--keep-results did not write $f"
done
grep -q '"stopped_by": "rse"' "$out/swr1/configs/c-00000000/summary.json" && ok || bad "kept summary.json does not say rse stopped the run"
sed -e 's/^rse = 0.3 .*/rse = 2/' -e "s|\.\./\.\./stacks|$PWD/stacks|" "$swr" > "$out/bad-rse.toml"
expect 2 "bad-rse.toml:5: rse: expected a relative standard error in \(0, 1\)" -- "$gonio" sweep "$out/bad-rse.toml" --quiet --out "$out/swr3"
expect 0 "speedup" -- "$gonio" sweep "$sw" --bench 4 --quiet --out "$out/sw6"
grep -q '"batched_configurations_per_second"' "$out/sw6/sweep-bench.json" && ok || bad "sweep --bench wrote no sweep-bench.json"
# --theta-i ranges: FROM:TO:STEP, mixed with single angles; malformed ones refused
expect 0 "wrote" -- "$gonio" simulate stacks/plastic.toml --theta-i 0:20:10,45 --paths 1000 --quiet --out "$out/range"
got=$(python3 -c "import json,sys; print(','.join('%g' % a['theta_i'] for a in json.load(open(sys.argv[1]))['angles']))" "$out/range/summary.json")
[ "$got" = "0,10,20,45" ] && ok || bad "--theta-i 0:20:10,45 ran the angles $got"
expect 2 "a range is FROM:TO:STEP, got '0:10'" -- "$gonio" simulate stacks/plastic.toml --theta-i 0:10 --quiet --out "$out/r2"
expect 2 "the range 10:0:1 needs TO >= FROM and STEP > 0" -- "$gonio" simulate stacks/plastic.toml --theta-i 10:0:1 --quiet --out "$out/r2"
expect 2 "the incident angle 20 is given twice" -- "$gonio" simulate stacks/plastic.toml --theta-i 0:40:20,20 --quiet --out "$out/r2"
# export: refusals before any work (the exports themselves: tests/python_package_test.py)
expect 2 "export: --format merl or --format rgl-bsdf" -- "$gonio" export "$out/range" --format png --out "$out/x"
expect 2 "holds no summary.json" -- "$gonio" export "$out/nothing-here" --format merl --out "$out/x"
expect 2 "option --paths does not apply to .gonio export. \(its options: --format --out --source\)" -- "$gonio" export "$out/range" --format merl --out "$out/x" --paths 4
expect 2 "needs incident angles from 0 to at least 80 degrees at most 5 degrees apart" -- "$gonio" export "$out/range" --format merl --out "$out/x.binary"
# gonio fit: a known parameter recovered. On an index-matched smooth coat over a rough conductor ww-corrected is the
# conductor's own microfacet BRDF, so the fit of the base roughness (0.3) from either side returns it within three
# of its standard errors, each se within a factor 2 of the 5e-5 these paths give (over many seeds, the se is the
# spread: tests/fit_calibration_test.py); the coat medium's Henyey-Greenstein asymmetry, which nothing scatters by (scattering albedo
# 0), is unconstrained
cp tests/stacks/matched-coat-conductor.toml "$out/matched.toml"
fit_value() {   # fit.json KEY -> "value se constrained"
    python3 -c "import json,sys; p=json.load(open(sys.argv[1]))['parameters'][sys.argv[2]]; print(p['value'], p['se'], p['constrained'])" "$1" "$2"
}
for start in 0.1 0.6; do
    expect 0 "layer.2.roughness = " -- "$gonio" fit "$out/matched.toml" --model ww-corrected --free layer.2.roughness --start layer.2.roughness=$start --theta-i 30,60 --paths 1e7 --quiet --no-report --out "$out/fit-$start"
    read -r v se c <<<"$(fit_value "$out/fit-$start/fit.json" layer.2.roughness)"
    python3 -c "import sys; v, se = float(sys.argv[1]), float(sys.argv[2]); sys.exit(0 if 2.5e-5 < se < 1e-4 and abs(v - 0.3) < 3 * se else 1)" "$v" "$se" && [ "$c" = True ] && ok ||
        bad "gonio fit from $start: layer.2.roughness = $v +- $se (constrained $c), expected 0.3 within 3 se"
done
expect 0 "layer.1.phase_g = 0.5: unconstrained" -- "$gonio" fit "$out/matched.toml" --model ww-corrected --free layer.2.roughness,layer.1.phase_g --start layer.1.phase_g=0.5 --theta-i 30 --paths 1e6 --quiet --no-report --out "$out/fit-two"
read -r v se c <<<"$(fit_value "$out/fit-two/fit.json" layer.1.phase_g)"
[ "$se" = None ] && [ "$c" = False ] && ok || bad "an unconstrained parameter has no se in fit.json: se $se, constrained $c"
# --reference DIR: the same fit on the earlier run's own bins, without simulating; the model at the start and at the
# fit written beside the reference, as compare writes models
expect 0 "layer.2.roughness = " -- "$gonio" fit --reference "$out/fit-0.1" --model ww-corrected --free layer.2.roughness --start layer.2.roughness=0.1 --quiet --no-report --out "$out/fit-again"
[ "$(fit_value "$out/fit-0.1/fit.json" layer.2.roughness)" = "$(fit_value "$out/fit-again/fit.json" layer.2.roughness)" ] && ok ||
    bad "fit --reference of the run gave another value: $(fit_value "$out/fit-again/fit.json" layer.2.roughness)"
[ "$(cut -d, -f1 "$out/fit-again/slices.csv" | sort -u | tr '\n' ' ')" = "reference source ww-corrected ww-corrected@fit " ] && ok ||
    bad "fit's slices.csv lacks the model at the start and at the fit: $(cut -d, -f1 "$out/fit-again/slices.csv" | sort -u | tr '\n' ' ')"
# several starts (--start repeated for a key): each descends and the lowest loss is kept; this loss has one minimum,
# which both starts reach
expect 0 "the best of 2 starts" -- "$gonio" fit --reference "$out/fit-0.1" --model ww-corrected --free layer.2.roughness --start layer.2.roughness=0.1 --start layer.2.roughness=0.6 --quiet --no-report --out "$out/fit-starts"
/usr/bin/python3 - "$out/fit-0.1/fit.json" "$out/fit-starts/fit.json" <<'PY' && ok || bad "fit from two starts: not the one minimum, or starts not reported"
import json, sys
one, two = (json.load(open(p)) for p in sys.argv[1:])
a, b = one["parameters"]["layer.2.roughness"], two["parameters"]["layer.2.roughness"]
assert two["starts"] == 2 and one["starts"] == 1, (one["starts"], two["starts"])
assert abs(a["value"] - b["value"]) < 1e-5, (a, b)
PY
# the cosine-weighted L2 loss recovers the same known roughness, within three of its own standard errors
expect 0 "loss cosine" -- "$gonio" fit --reference "$out/fit-0.1" --model ww-corrected --free layer.2.roughness --start layer.2.roughness=0.1 --loss cosine --quiet --no-report --out "$out/fit-cosine"
read -r v se c <<<"$(fit_value "$out/fit-cosine/fit.json" layer.2.roughness)"
python3 -c "import sys; v, se = float(sys.argv[1]), float(sys.argv[2]); sys.exit(0 if 3e-5 < se < 1.2e-4 and abs(v - 0.3) < 3 * se else 1)" "$v" "$se" && ok ||
    bad "gonio fit --loss cosine: layer.2.roughness = $v +- $se, expected 0.3 within 3 se"
# an RGB key one channel at a time (layer.N.KEY.r, .g, .b): the conductor's k, 3.6, 2.6 and 2.3, recovered channel by
# channel from 3 within three standard errors each, fit.json naming the channel; a number has no channels
expect 0 "layer.2.k.b = " -- "$gonio" fit --reference "$out/fit-0.1" --model ww-corrected --free layer.2.k.r,layer.2.k.g,layer.2.k.b --start layer.2.k.r=3 --start layer.2.k.g=3 --start layer.2.k.b=3 --quiet --no-report --out "$out/fit-k"
/usr/bin/python3 - "$out/fit-k/fit.json" <<'PY' && ok || bad "fit of an RGB key per channel: the conductor's k not recovered, or its channels not named"
import json, sys
p = json.load(open(sys.argv[1]))["parameters"]
for c, want in zip("rgb", (3.6, 2.6, 2.3)):
    q = p["layer.2.k." + c]
    assert q["channels"] == c and q["constrained"] and abs(q["value"] - want) < 3 * q["se"], (c, q)
PY
expect 0 "layer.2.k = .*one value in every channel" -- "$gonio" fit --reference "$out/fit-0.1" --model ww-corrected --free layer.2.k --quiet --no-report --out "$out/fit-k1"
expect 2 "free key layer.2.roughness.r: roughness is one number, not one per RGB channel" -- "$gonio" fit "$out/matched.toml" --model ww-corrected --free layer.2.roughness.r --out "$out/fit-x"
# a model file's own parameter (parameter: NAME default V range [A, B]), read as param_NAME, fitted as param.NAME: on
# a bare Lambertian of albedo 0.7 a model f = param_albedo / pi recovers it within three standard errors (the
# cosine-weighted loss: linear in f, so the reference's noise does not bias it)
printf 'name = "bare-lambertian"\n[[layer]]\ninterface = "lambertian"\nalbedo = 0.7\n' > "$out/bare.toml"
cat > "$out/scaled.glsl" <<'GLSL'
// gonio-model: scaled-lambert
// parameter: albedo default 0.5 range [0, 1] -- the reflectance
vec3 model_f(vec3 l, vec3 v) { return vec3(param_albedo / 3.14159265358979f); }
GLSL
expect 0 "param.albedo = " -- "$gonio" fit "$out/bare.toml" --model "$out/scaled.glsl" --free param.albedo --loss cosine --theta-i 0,30,60 --paths 1e6 --quiet --no-report --out "$out/fit-param"
read -r v se c <<<"$(fit_value "$out/fit-param/fit.json" param.albedo)"
python3 -c "import sys; v, se = float(sys.argv[1]), float(sys.argv[2]); sys.exit(0 if 2e-4 < se < 8e-4 and abs(v - 0.7) < 3 * se else 1)" "$v" "$se" && ok ||
    bad "gonio fit of a model file's parameter: param.albedo = $v +- $se, expected 0.7 within 3 se"
expect 2 "free key param.nope: model scaled-lambert has the parameters param.albedo" -- "$gonio" fit "$out/bare.toml" --model "$out/scaled.glsl" --free param.nope --out "$out/fit-x"
expect 2 "free key param.albedo: model ww-corrected has no parameters of its own" -- "$gonio" fit "$out/matched.toml" --model ww-corrected --free param.albedo --out "$out/fit-x"
sed 's/default 0.5 range \[0, 1\]/default 1.5 range [0, 1]/' "$out/scaled.glsl" > "$out/scaled-bad.glsl"
expect 2 "scaled-bad.glsl:2: parameter albedo: expected A < B and the default within \[A, B\]" -- "$gonio" fit "$out/bare.toml" --model "$out/scaled-bad.glsl" --free param.albedo --out "$out/fit-x"
starts=(); for r in 0.1 0.2 0.3 0.4 0.5 0.6 0.7 0.8 0.9; do starts+=(--start layer.2.roughness=$r); done
for k in 1 2 3 4 5 6 7 8; do starts+=(--start layer.2.k=$k); done
expect 2 "fit: start: 72 starting points .every combination of the keys. values.: at most 64" -- "$gonio" fit "$out/matched.toml" --model ww-corrected --free layer.2.roughness,layer.2.k "${starts[@]}" --out "$out/fit-x"
expect 2 "--paths does not apply with --reference" -- "$gonio" fit --reference "$out/fit-0.1" --model ww-corrected --free layer.2.roughness --paths 5 --out "$out/fit-x"
expect 2 "--reference DIR needs --out OUT" -- "$gonio" fit --reference "$out/fit-0.1" --model ww-corrected --free layer.2.roughness
expect 2 "--reference DIR takes no STACK" -- "$gonio" fit "$out/matched.toml" --reference "$out/fit-0.1" --model ww-corrected --free layer.2.roughness --out "$out/fit-x"
# refusals, before any simulation, exit 2 with the reason
expect 2 "layer 2 is a conductor interface, which takes roughness, ior, k" -- "$gonio" fit "$out/matched.toml" --model ww-corrected --free layer.2.albedo --out "$out/fit-x"
expect 2 "the stack has layers 1 to 2" -- "$gonio" fit "$out/matched.toml" --model ww-corrected --free layer.3.roughness --out "$out/fit-x"
expect 2 "expected layer.N.KEY" -- "$gonio" fit "$out/matched.toml" --model ww-corrected --free roughness --out "$out/fit-x"
expect 2 "fit: start layer.2.roughness=2: outside the key.s range .1e-04, 1. or 0" -- "$gonio" fit "$out/matched.toml" --model ww-corrected --free layer.2.roughness --start layer.2.roughness=2 --out "$out/fit-x"
expect 2 "fit: start layer.1.roughness: not one of the free keys" -- "$gonio" fit "$out/matched.toml" --model ww-corrected --free layer.2.roughness --start layer.1.roughness=0.1 --out "$out/fit-x"
expect 2 "fit: model no-such-model: no such model" -- "$gonio" fit "$out/matched.toml" --model no-such-model --free layer.2.roughness --out "$out/fit-x"
expect 2 "enterprise-pbr: the clearcoat's IOR is fixed at 1.5" -- "$gonio" fit "$out/matched.toml" --model enterprise-pbr --free layer.2.roughness --out "$out/fit-x"
expect 2 "fit: --model ID" -- "$gonio" fit "$out/matched.toml" --free layer.2.roughness --out "$out/fit-x"
expect 2 "--loss: log, cosine or chi2" -- "$gonio" fit "$out/matched.toml" --model ww-corrected --free layer.2.roughness --loss l1 --out "$out/fit-x"
# a sweep's [[fit]]: each configuration's best fit in its columns of sweep.csv; on the index-matched coat over copper,
# the base roughness each configuration has is recovered within three of its standard errors, from a start between
cat > "$out/fit-sweep.toml" <<TOML
name = "fit-matched"
stack = "$out/matched.toml"
theta_i = [30, 60]
paths = 2000000
seed = 3
[[vary]]
layer = 2
key = "roughness"
values = [0.15, 0.4]
[[fit]]
model = "ww-corrected"
free = ["layer.2.roughness"]
start = { "layer.2.roughness" = 0.25 }
TOML
expect 0 "wrote .*sweep.csv" -- "$gonio" sweep "$out/fit-sweep.toml" --quiet --out "$out/swfit"
/usr/bin/python3 - "$out/swfit/sweep.csv" <<'PY' && ok || bad "sweep [[fit]]: the fitted roughness is not each configuration's within 3 se"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
k = "fit.ww-corrected.layer.2.roughness"
assert {r[k + ".status"] for r in rows} == {"fitted"}, {r[k + ".status"] for r in rows}
fits = {(float(r["layer2.roughness"]), float(r[k]), float(r[k + ".se"])) for r in rows}
assert len(fits) == 2, fits   # one fit per configuration, on each of its rows
known = {0.15: 5.7e-5, 0.4: 1.43e-4}   # the se these paths give (tests/fit_calibration_test.py: the se is the spread)
for truth, v, se in fits:
    assert known[truth] / 2 < se < 2 * known[truth] and abs(v - truth) < 3 * se, (truth, v, se)
PY
# select = [...]: only those models run, a variant among them; an unknown id refused with the line
printf 'name = "s"\nstack = "%s"\ntheta_i = [30]\npaths = 20000\nselect = [%s]\n[[vary]]\nlayer = 2\nkey = "roughness"\nvalues = [0.2]\n' \
    "$out/matched.toml" '"ww-corrected", "openpbr+separable"' > "$out/select.toml"
expect 0 "wrote .*sweep.csv" -- "$gonio" sweep "$out/select.toml" --quiet --out "$out/swsel"
[ "$(tail -n +2 "$out/swsel/sweep.csv" | cut -d, -f5 | sort -u | tr '\n' ' ')" = "openpbr+separable reference ww-corrected " ] && ok ||
    bad "sweep select: rows of other models: $(tail -n +2 "$out/swsel/sweep.csv" | cut -d, -f5 | sort -u | tr '\n' ' ')"
printf 'name = "s"\nstack = "%s"\ntheta_i = [30]\npaths = 20000\nselect = [%s]\n[[vary]]\nlayer = 2\nkey = "roughness"\nvalues = [0.2]\n' \
    "$out/matched.toml" '"openpbr+nope"' > "$out/select-bad.toml"
expect 2 "select-bad.toml:5: select: no model 'openpbr\+nope'" -- "$gonio" sweep "$out/select-bad.toml" --quiet --out "$out/swx"
# what a [[fit]] cannot be, refused with the sweep file's line
printf 'name = "f"\nstack = "%s"\ntheta_i = [30]\n[[vary]]\nlayer = 2\nkey = "roughness"\nvalues = [0.1]\n[[fit]]\nmodel = "%s"\nfree = ["%s"]\n%s\n' \
    "$out/matched.toml" ww-corrected layer.2.albedo "" > "$out/fit-bad1.toml"
expect 2 "fit-bad1.toml:8: \[\[fit\]\]: free key layer.2.albedo: layer 2 is a conductor interface, which takes roughness, ior, k" -- "$gonio" sweep "$out/fit-bad1.toml" --quiet --out "$out/swx"
printf 'name = "f"\nstack = "%s"\ntheta_i = [30]\n[[vary]]\nlayer = 2\nkey = "roughness"\nvalues = [0.1]\n[[fit]]\nmodel = "%s"\nfree = ["%s"]\n%s\n' \
    "$out/matched.toml" no-such-model layer.2.roughness "" > "$out/fit-bad2.toml"
expect 2 "fit-bad2.toml:8: \[\[fit\]\]: model no-such-model: no such model" -- "$gonio" sweep "$out/fit-bad2.toml" --quiet --out "$out/swx"
printf 'name = "f"\nstack = "%s"\ntheta_i = [30]\n[[vary]]\nlayer = 2\nkey = "roughness"\nvalues = [0.1]\n[[fit]]\nmodel = "%s"\nfree = ["%s"]\n%s\n' \
    "$out/matched.toml" ww-corrected layer.2.roughness 'start = { layer.2.roughness = 0.2 }' > "$out/fit-bad3.toml"
expect 2 "fit-bad3.toml:11: \[\[fit\]\] start: expected .* the key in quotes" -- "$gonio" sweep "$out/fit-bad3.toml" --quiet --out "$out/swx"
printf 'name = "f"\nstack = "%s"\ntheta_i = [30]\n[[vary]]\nlayer = 2\nkey = "roughness"\nvalues = [0.1]\n[[fit]]\nmodel = "%s"\nfree = ["%s"]\n%s\n' \
    "$out/matched.toml" ww-corrected layer.2.roughness 'loss = "l1"' > "$out/fit-bad4.toml"
expect 2 "fit-bad4.toml:11: \[\[fit\]\] loss: log, cosine or chi2, got 'l1'" -- "$gonio" sweep "$out/fit-bad4.toml" --quiet --out "$out/swx"
printf 'name = "f"\nstack = "%s"\ntheta_i = [30]\n[[vary]]\nlayer = 2\nkey = "roughness"\nvalues = [0.1]\n[[fit]]\nmodel = "%s"\nfree = ["%s"]\n%s\n' \
    "$out/matched.toml" ww-corrected layer.2.roughness '[[fit]]
model = "ww-corrected"
free = ["layer.2.k"]' > "$out/fit-bad5.toml"
expect 2 "fit-bad5.toml:11: \[\[fit\]\]: a second fit of ww-corrected \(the first at line 8\)" -- "$gonio" sweep "$out/fit-bad5.toml" --quiet --out "$out/swx"
echo "cli: $pass passed, $fail failed"
[ "$fail" = 0 ]
