#!/usr/bin/env bash
# untrusted_inputs_test.sh path/to/gonio: files from outside are data, not trusted (docs/ARCHITECTURE.md "Inputs
# from outside"): a stack, sweep, model or values file is read only if it is a regular file under its size limit,
# a model's #include chain is bounded with the cycle named, and a state file is checked against its checksum and
# field by field; each case exits 2 with the reason, in seconds (each of them read without bound, hung, crashed or
# was accepted as data before). Run from the repository root.
set -u
gonio="$(realpath "$1")"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
export GONIO_CACHE_DIR="$out/cache"
pass=0 fail=0
ok()   { pass=$((pass + 1)); }
bad()  { fail=$((fail + 1)); echo "FAIL: $*"; }
expect() {   # expect RC PATTERN -- command...   (killed after 60 s: a hang fails the case)
    local want_rc="$1" pattern="$2"; shift 3
    local text rc
    text="$(timeout "${CASE_TIMEOUT:-60}" "$@" 2>&1)"; rc=$?
    if [ "$rc" != "$want_rc" ]; then bad "$* exited $rc, expected $want_rc: ${text:0:400}"; return; fi
    if ! grep -qE -- "$pattern" <<<"$text"; then bad "$*: output lacks /$pattern/: ${text:0:400}"; return; fi
    ok
}

# a device, a directory, a file over the limit: refused before a byte is read
expect 2 "/dev/zero:0: is not a regular file .*a stack file is read from a file" -- "$gonio" check /dev/zero
expect 2 "is a directory, not a stack file" -- "$gonio" check stacks
truncate -s 5M "$out/big.toml"
expect 2 "big.toml:0: is 5 MiB; a stack file is at most 4 MiB" -- "$gonio" check "$out/big.toml"
expect 2 "/dev/zero:0: is not a regular file .*a model file" -- "$gonio" compare stacks/plastic.toml --model /dev/zero \
    --paths 10 --out "$out/m"
expect 2 "/dev/zero:0: is not a regular file .*a sweep file" -- "$gonio" sweep /dev/zero --out "$out/s"
"$gonio" nodes stacks/plastic.toml --theta-i 30 --out "$out/nodes" >/dev/null 2>&1 || bad "gonio nodes failed"
"$gonio" simulate stacks/plastic.toml --theta-i 30 --paths 1000 --out "$out/ref" >/dev/null 2>&1 || bad "simulate failed"
expect 2 "/dev/zero:0: is not a regular file .*a values file" -- "$gonio" score "$out/nodes" --values /dev/zero \
    --id mine --reference "$out/ref" --out "$out/score"

# score: values a float holds (1e39 was "reflects 3.1e39 of the light", 1e300 "a bug"), ids that keep slices.csv a
# CSV; a model file may not call itself the reference
rows=$(($(wc -l <"$out/nodes/nodes.csv") - 1))
awk -v n="$rows" 'BEGIN { for (i = 0; i < n; ++i) print "1,1,1" }' >"$out/ones.csv"
awk -v n="$rows" 'BEGIN { for (i = 0; i < n; ++i) print "1e39,1,1" }' >"$out/big.csv"
expect 2 "big.csv:1: [0-9]+ values are negative, NaN, infinite or beyond the largest float" -- "$gonio" score \
    "$out/nodes" --values "$out/big.csv" --id big --reference "$out/ref" --no-report --out "$out/sb"
expect 2 "cannot name a model .not 'reference', no comma, quote or control character." -- "$gonio" score \
    "$out/nodes" --values "$out/big.csv" --id "$(printf 'two\nlines')" --reference "$out/ref" --out "$out/sc"
sed -e "s|^// gonio-model: .*|// gonio-model: reference|" tests/user_models/ww_corrected_rewrite.glsl >"$out/ref.glsl"
expect 2 "ref.glsl:1: gonio-model: 'reference' names the reference in every output" -- "$gonio" compare \
    stacks/plastic.toml --model "$out/ref.glsl" --paths 10 --out "$out/r1"

# a stack's name carries into file names and CSV fields: no control character (a NUL cut `check`'s output); -0 is 0;
# an option's value may not be empty (`--out ""` wrote to out/NAME)
printf 'name = "a\\u0000b"\n[[layer]]\ninterface = "lambertian"\nalbedo = 0.5\n' >"$out/nul.toml"
expect 2 "nul.toml:1: name: a control character .U\+0000. at character 2" -- "$gonio" check "$out/nul.toml"
printf 'name = "z"\n[[layer]]\ninterface = "lambertian"\nalbedo = -0.0\n' >"$out/zero.toml"
expect 0 "albedo 0$" -- "$gonio" check "$out/zero.toml"
expect 2 "--out needs a value, got an empty one" -- "$gonio" simulate stacks/plastic.toml --paths 10 --out ""

# ranges are checked on the value as written, before a float holds it (roughness 1.00000001 and ior 10.0000001
# passed, rounded to 1 and 10; phase_g 0.99999999 was refused as "got 1"); a Sellmeier pole between the 2 nm points
# a stack tabulates is refused as a pole (its neighbours were in range)
layer1() {   # layer1 FILE KEY = VALUE...: stacks/plastic.toml with its coat's lines replaced by these
    awk -v add="$2" 'NR == 11 { print add; next } NR == 12 || NR == 13 { next } { print }' stacks/plastic.toml >"$out/$1"
}
layer1 rough.toml $'roughness = 1.00000001\nior = 1.5'
expect 2 "rough.toml:11: layer 1: roughness must be in \[1e-04, 1\] or 0 .*got 1.00000001 .1 as a 32-bit float." -- \
    "$gonio" check "$out/rough.toml"
layer1 ior.toml $'roughness = 0.05\nior = 10.0000001'
expect 2 "ior.toml:12: layer 1: ior must be in \[1, 10\] .*got 10.0000001 .10 as a 32-bit float." -- "$gonio" check "$out/ior.toml"
layer1 g.toml $'roughness = 0.05\nior = 1.5\nscattering_albedo = 0.5\nphase_g = 0.99999999'
expect 2 "g.toml:14: layer 1: phase_g must be in \(-1, 1\) .*got 0.99999999 .1 as a 32-bit float." -- \
    "$gonio" check "$out/g.toml"
sed 's/^exterior_ior = .*/exterior_ior = 10.000001/' stacks/plastic.toml >"$out/ext.toml"
expect 2 "ext.toml:7: exterior_ior must be in \[1, 10\] .*got 10.000001" -- "$gonio" check "$out/ext.toml"
layer1 pole.toml $'roughness = 0.05\nior = { sellmeier = [1.2, 0.0001, 0, 0.01, 0.251001, 0] }'
expect 2 "pole.toml:12: layer 1: ior: the formula has a pole at 501 nm .B2 = 1e-04, C2 = 0.251001" -- \
    "$gonio" check "$out/pole.toml"
# a spectrum just short of the primaries: the ends it must cover, to 0.01 nm outward (both read 464.31 to 611.28)
printf 'name = "s"\n[[layer]]\ninterface = "lambertian"\nalbedo = [[464.31, 0.5], [611.28, 0.5]]\n' >"$out/sp.toml"
expect 2 "covers 464.31 to 611.28 nm; it must cover at least 464.30 to 611.28 nm" -- "$gonio" check "$out/sp.toml"

# a sweep: one key varied once (twice gave sweep.csv two columns of one name), each value in the key's range as written
sweep() {   # sweep FILE VARY...: a sweep of stacks/plastic.toml with these [[vary]] blocks
    local f="$out/$1"; shift
    printf 'name = "v"\nstack = "%s"\ntheta_i = [30]\npaths = 1000\n' "$PWD/stacks/plastic.toml" >"$f"
    for v in "$@"; do printf '[[vary]]\nlayer = 1\n%s\n' "$v" >>"$f"; done
}
sweep twice.toml $'key = "roughness"\nvalues = [0.1]' $'key = "roughness"\nvalues = [0.2]'
expect 2 "twice.toml:9: \[\[vary\]\]: layer 1's roughness is varied already by the \[\[vary\]\] at line 5" -- \
    "$gonio" sweep "$out/twice.toml" --out "$out/sw"
sweep range.toml $'key = "roughness"\nvalues = [0.1, 1.00000001]'
expect 2 "range.toml:5: \[\[vary\]\]: layer 1's roughness = 1.00000001 .1 as a 32-bit float. is outside its range" -- \
    "$gonio" sweep "$out/range.toml" --out "$out/sw"

# a count beyond what a double holds exactly is named as such (1e30 was "expected a whole non-negative number")
expect 2 "--paths: a count of at most 9007199254740992 .2\^53" -- "$gonio" simulate stacks/plastic.toml --paths 1e30 \
    --out "$out/p"

# nodes: a grid whose values no values file could hold is refused with its size (it ended in std::bad_alloc); score
# reads nodes.json as data from outside, each field against what gonio nodes writes
expect 2 "nodes: 1.194e\+09 nodes .9 angles x 1 side x 518400 bins x 16 x 16. is more than the 44739242" -- \
    "$gonio" nodes stacks/plastic.toml --theta-i 0:80:10 --dtheta 0.25 --dphi 0.25 --nodes-per-bin 16 --out "$out/nb"
mkdir -p "$out/nk"
sed 's/"k": *4/"k": 5000/' "$out/nodes/nodes.json" >"$out/nk/nodes.json"
expect 2 "nk/nodes.json:1: k: expected 1 to 16, got 5000" -- "$gonio" score "$out/nk" --values "$out/ones.csv" \
    --id mine --reference "$out/ref" --no-report --out "$out/sk"
sed 's/"nodes": *[0-9]*/"nodes": 5/' "$out/nodes/nodes.json" >"$out/nk/nodes.json"
expect 2 "nk/nodes.json:1: nodes: the grid has [0-9]+, got 5" -- "$gonio" score "$out/nk" --values "$out/ones.csv" \
    --id mine --reference "$out/ref" --no-report --out "$out/sk"

# merge: a configuration file whose rows were edited is named as damaged (its end line holds their CRC-32C)
sweep merge.toml $'key = "roughness"\nvalues = [0.1, 0.2]'
"$gonio" sweep "$out/merge.toml" --out "$out/mg" --quiet >/dev/null 2>&1 || bad "sweep merge.toml failed"
sed -i '2s/,R,/,T,/' "$out/mg/configs/c-00000001.csv"
expect 2 "cannot merge .*mg: configuration 1: damaged .its rows differ from their CRC-32C." -- "$gonio" merge "$out/mg"

# export reads a run's summary.json and slices.csv as data: a truncated one is named with its line (a traceback before)
"$gonio" simulate stacks/plastic.toml --theta-i 0:85:5 --paths 200 --quiet --out "$out/table" >/dev/null 2>&1 ||
    bad "simulate of the table failed"
head -c 300 "$out/table/summary.json" >"$out/cut.json" && mv "$out/cut.json" "$out/table/summary.json"
expect 2 "table/summary.json:[0-9]+: not a summary.json gonio wrote" -- "$gonio" export "$out/table" --format merl \
    --out "$out/t.binary"

# a model file that includes itself, or a file that includes it back: the cycle named, not expanded without end
model() {   # model NAME INCLUDE: a user's model (tests/user_models/ww_corrected_rewrite.glsl) that includes INCLUDE first
    sed -e "s|^// gonio-model: .*|// gonio-model: $1|" -e "0,/^#include/s||#include \"$2\"\n#include|" \
        tests/user_models/ww_corrected_rewrite.glsl >"$out/$1.glsl"
}
model self self.glsl
expect 2 "self.glsl: #include nested deeper than 32 files: a cycle, .*self.glsl -> .*self.glsl" -- \
    "$gonio" compare stacks/plastic.toml --model "$out/self.glsl" --paths 10 --out "$out/c1"
printf '#include "b.glsl"\n' >"$out/a.glsl"
printf '#include "a.glsl"\n' >"$out/b.glsl"
model via-a a.glsl
expect 2 "a cycle, .*a.glsl -> .*b.glsl -> .*a.glsl" -- \
    "$gonio" compare stacks/plastic.toml --model "$out/via-a.glsl" --paths 10 --out "$out/c2"
# an include guard is what stops a file included twice: the same pair, guarded, compiles and runs
printf '#ifndef A_GLSL\n#define A_GLSL\n#include "b2.glsl"\n#endif\n' >"$out/a2.glsl"
printf '#ifndef B_GLSL\n#define B_GLSL\n#include "a2.glsl"\n#endif\n' >"$out/b2.glsl"
model guarded a2.glsl
expect 0 "guarded" -- "$gonio" compare stacks/plastic.toml --model "$out/guarded.glsl" --models guarded --theta-i 30 \
    --paths 1000 --out "$out/c3"

# options: one given twice is refused with both values (the last won unseen), but for the repeatable ones (--model
# FILE, fit's --start); a run's size is checked before anything is allocated
expect 2 "--models given twice .--models openpbr, then --models ww09.: give it once" -- "$gonio" compare \
    stacks/plastic.toml --models openpbr --models ww09 --paths 10 --out "$out/o1"
expect 2 "--quiet given twice: give it once" -- "$gonio" simulate stacks/plastic.toml --quiet --quiet --paths 10 \
    --out "$out/o2"
expect 2 "--theta-i: at most 1000 incident angles in a run, got 9000" -- "$gonio" simulate stacks/plastic.toml \
    --theta-i 0:89.99:0.01 --paths 10 --out "$out/o3"
expect 2 "histograms would take up to 20.6[0-9]* GiB .891 angles x 259200 bins x 2 sides x 48 bytes.; at most 16 GiB" \
    -- "$gonio" simulate stacks/plastic.toml --theta-i 0:89:0.1 --dtheta 0.25 --dphi 0.5 --paths 10 --out "$out/o4"

# fit: only points of a key's valid set (a roughness 0 or in [1e-4, 1]: a start at 0 descends from 1e-4, where it
# stayed at 0 or ended at 5e-6 with a worse loss), each value free once, only keys a stack file takes, and a
# reference whose loss is finite
expect 0 "layer.1.roughness = 0.0[1-9][0-9]* .* .from 0." -- "$gonio" fit stacks/plastic.toml --model ww09 \
    --free layer.1.roughness --start layer.1.roughness=0 --theta-i 0,30 --paths 1e5 --quiet --no-report --out "$out/f0"
expect 2 "start layer.1.roughness=1e-06: outside the key's range \[1e-04, 1\] or 0" -- "$gonio" fit \
    stacks/plastic.toml --model ww09 --free layer.1.roughness --start layer.1.roughness=1e-6 --paths 10 --out "$out/f1"
expect 2 "free keys: layer.2.albedo and layer.2.albedo.r overlap" -- "$gonio" fit stacks/plastic.toml --model ww09 \
    --free layer.2.albedo,layer.2.albedo.r --paths 10 --out "$out/f3"
expect 2 "free keys: layer.1.roughness is given twice" -- "$gonio" fit stacks/plastic.toml --model ww09 \
    --free layer.1.roughness,layer.1.roughness --paths 10 --out "$out/f4"
expect 2 "layer 2 is the last of a transmissive stack, whose substrate has no medium" -- "$gonio" fit \
    stacks/transparent-slab.toml --model belcour18-forward --free layer.2.optical_depth --paths 10 --out "$out/f5"
expect 2 "the reference gives the log loss no cell to use .16 paths per angle" -- "$gonio" fit stacks/plastic.toml \
    --model ww09 --free layer.1.roughness --theta-i 30 --paths 16 --quiet --no-report --out "$out/f6"

# an output may not overwrite an input of the same command (fit and score said the reference was left as it is;
# export --out DIR/state.gonio destroyed its own source)
expect 2 "fit: --out .*ref is the reference's directory, which is left as it is" -- "$gonio" fit --reference \
    "$out/ref" --model ww09 --free layer.1.roughness --out "$out/ref"
expect 2 "score: --out .*ref/ is the reference's directory" -- "$gonio" score "$out/nodes" --values \
    "$out/ones.csv" --id ones --reference "$out/ref" --out "$out/ref/"
expect 2 "export: --out .*ref/state.gonio is a file of .*ref, the run it reads" -- "$gonio" export "$out/ref" \
    --format merl --out "$out/ref/state.gonio"
[ -s "$out/ref/state.gonio" ] && ok || bad "the reference's state.gonio is gone"

# a state file (host/io/state.cpp): its checksum and every field against what a run writes (tests/state_tamper.py
# edits one field and writes the checksum anew, so that the field's own check is what refuses it). A damaged or
# edited file is refused by every command that reads one, before anything of it is used.
state="$out/ref/state.gonio"
tampered() {   # tampered EDIT [--keep-checksum]: DIR holding the edited state, its name from the edit
    local dir="$out/t-${1//[^a-z0-9]/_}"
    mkdir -p "$dir"
    /usr/bin/python3 tests/state_tamper.py "$state" "$dir/state.gonio" "$@" || bad "state_tamper.py $*"
    echo "$dir"
}
checksum="checksum does not match its contents .CRC-32C [0-9a-f]{8}, stored [0-9a-f]{8}.: it was damaged or edited"
expect 2 "$checksum" -- "$gonio" simulate stacks/plastic.toml --paths 2000 --quiet --resume "$(tampered flip:3)"
expect 2 "$checksum" -- "$gonio" fit --reference "$(tampered flip:40)" --model ww09 --free layer.1.roughness \
    --out "$out/f"
expect 2 "$checksum" -- "$gonio" score "$out/nodes" --values "$out/nodes/nodes.csv" --id mine \
    --reference "$(tampered flip:100)" --out "$out/score2"
expect 2 "$checksum" -- "$gonio" simulate stacks/plastic.toml --paths 2000 --quiet --resume "$(tampered paths:0 --keep-checksum)"
expect 2 "bin grid 0 x 180 .expected 90 x 180 for bins of 1 x 2 degrees." -- "$gonio" simulate stacks/plastic.toml --paths 2000 --quiet --resume "$(tampered grid:0,180)"
expect 2 "bin grid 1 x 1 .expected 90 x 180" -- "$gonio" fit --reference "$(tampered grid:1,1)" --model ww09 \
    --free layer.1.roughness --out "$out/f2"
expect 2 "dtheta 7 .expected a width that divides 90." -- "$gonio" simulate stacks/plastic.toml --paths 2000 --quiet --resume "$(tampered dtheta:7)"
expect 2 "paths 0 .expected 1 to" -- "$gonio" simulate stacks/plastic.toml --paths 2000 --quiet --resume "$(tampered paths:0)"
expect 2 "rse_quantile 5 .expected a quantile in .0, 1\]." -- "$gonio" simulate stacks/plastic.toml --paths 2000 --quiet --resume "$(tampered rse_quantile:5)"
expect 2 "incident azimuth 360 .expected an azimuth in \[0, 360. degrees." -- "$gonio" simulate stacks/plastic.toml --paths 2000 --quiet --resume "$(tampered phi_i:360)"
expect 2 "angle 30: energy book entry -0.93.* .expected 0 or more." -- "$gonio" simulate stacks/plastic.toml --paths 2000 --quiet --resume "$(tampered energy:-0.93)"
expect 2 "incident angle 95 .expected an angle in \[0, 90. degrees." -- "$gonio" simulate stacks/plastic.toml --paths 2000 --quiet --resume "$(tampered theta:95)"
expect 2 "incident angle 30 .expected each once." -- "$gonio" simulate stacks/plastic.toml --paths 2000 --quiet --resume "$(tampered duplicate)"
expect 2 "corrupt state file .data after its last angle." -- "$gonio" simulate stacks/plastic.toml --paths 2000 --quiet --resume "$(tampered trailing)"
# a refusal names the option the file came from: --reference's missing state, not --resume's; a state's angle, not
# --theta-i
expect 2 "nothing/state.gonio: cannot open the state file for reading" -- "$gonio" fit --reference "$out/nothing" \
    --model ww09 --free layer.1.roughness --out "$out/f7"
text="$("$gonio" fit --reference "$out/nothing" --model ww09 --free layer.1.roughness --out "$out/f7" 2>&1)"
if grep -q -- "--resume" <<<"$text"; then bad "fit --reference's refusal names --resume: $text"; else ok; fi
text="$("$gonio" simulate stacks/plastic.toml --paths 2000 --quiet --resume "$(tampered theta:95)" 2>&1)"
if grep -q -- "--theta-i" <<<"$text"; then bad "a state's angle is blamed on --theta-i: $text"; else ok; fi
# the file is replaced at once or the run fails (exit 1), never "wrote"
mkdir -p "$out/isdir/state.gonio"
expect 1 "cannot replace .*isdir/state.gonio" -- "$gonio" simulate stacks/plastic.toml --theta-i 30 --paths 1000 \
    --out "$out/isdir"

echo "untrusted inputs: $pass passed, $fail failed"
[ "$fail" = 0 ]
