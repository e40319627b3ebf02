#!/usr/bin/env bash
# untrusted_inputs_test.sh path/to/gonio: files from outside are data, not trusted (docs/ARCHITECTURE.md "Inputs
# from outside"): a stack, sweep, model or values file is read only if it is a regular file under its size limit,
# and a model's #include chain is bounded with the cycle named; each case exits 2 with the reason, in seconds (each
# of them read without bound, hung or was misreported before). Run from the repository root.
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

echo "untrusted inputs: $pass passed, $fail failed"
[ "$fail" = 0 ]
