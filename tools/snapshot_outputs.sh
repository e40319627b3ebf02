#!/usr/bin/env bash
# snapshot_outputs.sh GONIO OUT: run gonio on every shipped stack and sweep (small path counts) through every walk
# host (compare, simulate with the general walk, the CPU twin, --orders, --no-series, --no-baked-stack, --rse, a
# resumed run, sweeps batched) and every command that writes numbers (fit, fit --reference, score, render, the
# spectral runs of simulate and compare, compare --rgb-vs-spectral), and keep slices.csv, sweep.csv and the JSON files
# (summary, fit, render, models-spectral, rgb-vs-spectral) with timings removed, the EXRs' checksums, and the console
# tables of compare, fit and score. A refactor that changes no number leaves two snapshots identical:
#   tools/snapshot_outputs.sh build-before/gonio /tmp/before; tools/snapshot_outputs.sh build/gonio /tmp/after
#   diff -r /tmp/before /tmp/after
set -euo pipefail
gonio="$(realpath "$1")"
out="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
rm -rf "$out"; mkdir -p "$out/runs" "$out/kept"
runs="$out/runs"

# keep DIR AS: copy a run's outputs without the fields that measure time
keep() {
    local dir="$1" name="$2"
    [ -f "$dir/slices.csv" ] && cp "$dir/slices.csv" "$out/kept/$name.slices.csv"
    [ -f "$dir/sweep.csv" ] && cp "$dir/sweep.csv" "$out/kept/$name.sweep.csv"
    [ -f "$dir/rgb-vs-spectral.csv" ] && cp "$dir/rgb-vs-spectral.csv" "$out/kept/$name.rgb-vs-spectral.csv"
    for j in summary fit render models-spectral rgb-vs-spectral; do
        [ -f "$dir/$j.json" ] || continue
        python3 - "$dir/$j.json" "$out/kept/$name.$j.json" <<'EOF'
import json, re, sys
timing = re.compile(r"(seconds|paths_per_second|ns_per_evaluation|cost_at_equal|^device$|^driver|^host$|^date|^gonio_version)")
def strip(o):
    if isinstance(o, dict):
        return {k: strip(v) for k, v in o.items() if not timing.search(k)}
    if isinstance(o, list):
        return [strip(v) for v in o]
    return o
json.dump(strip(json.load(open(sys.argv[1]))), open(sys.argv[2], "w"), indent=1, sort_keys=True)
EOF
    done
    (cd "$dir" && find . -name '*.exr' | sort | xargs -r md5sum) > "$out/kept/$name.exr.md5"
    [ -s "$out/kept/$name.exr.md5" ] || rm -f "$out/kept/$name.exr.md5"
    return 0
}
# console AS CMD...: run a command, keep its standard output (lines that carry seconds left out)
console() {
    local name="$1"; shift
    "$@" 2>/dev/null | grep -v -E "seconds|[0-9] s\)|[0-9] s,|[0-9] s$" > "$out/kept/$name.stdout" || true
}

q=(--quiet)
for s in "$here"/stacks/*.toml "$here"/stacks/hard/*.toml; do
    n="$(basename "$s" .toml)"
    console "compare.$n" "$gonio" compare "$s" --theta-i 0,30,60,80 --paths 2e4 --no-report "${q[@]}" --out "$runs/$n"
    keep "$runs/$n" "compare.$n"
done
# fit, and fit --reference on its run
m="$here/stacks/coats/clear-over-grey-metal.toml"
console fit "$gonio" fit "$m" --model ww-corrected --free layer.2.roughness --theta-i 30,60 --paths 1e5 --no-report "${q[@]}" --out "$runs/fit"
keep "$runs/fit" fit
console fit-reference "$gonio" fit --reference "$runs/fit" --model openpbr --free layer.2.roughness --no-report "${q[@]}" --out "$runs/fit-r"
keep "$runs/fit-r" fit-reference
# score: a constant f at the nodes of a run's bins
"$gonio" simulate "$here/stacks/plastic.toml" --theta-i 0,45 --paths 2e4 "${q[@]}" --out "$runs/score-ref" >/dev/null 2>&1
"$gonio" nodes "$here/stacks/plastic.toml" --theta-i 0,45 --out "$runs/nodes" >/dev/null 2>&1 || true
if [ -f "$runs/nodes/nodes.csv" ]; then
    python3 -c "import sys; n = sum(1 for _ in open(sys.argv[1])) - 1; open(sys.argv[2], 'w').write('0.1,0.1,0.1\n' * n)" "$runs/nodes/nodes.csv" "$runs/values.csv"
    console score "$gonio" score "$runs/nodes" --values "$runs/values.csv" --id constant --reference "$runs/score-ref" --no-report --out "$runs/score"
    keep "$runs/score" score
fi
# render (its table made now), and compare --render
"$gonio" render "$here/stacks/plastic.toml" --env furnace --size 16 --spp 4 --paths 2e3 --theta-i 0:88:8 --no-report --quiet --out "$runs/render" >/dev/null 2>&1
keep "$runs/render" render
"$gonio" compare "$here/stacks/plastic.toml" --theta-i 0,45 --paths 2e4 --render furnace --render-size 16 --render-paths 2e3 --no-report "${q[@]}" --out "$runs/compare-render" >/dev/null 2>&1
keep "$runs/compare-render/render" compare-render
# the spectral runs
g="$here/stacks/coats/coated-gold.toml"
"$gonio" simulate "$g" --spectral --theta-i 0,45 --paths 2e4 "${q[@]}" --out "$runs/spectral" >/dev/null 2>&1
keep "$runs/spectral" spectral
"$gonio" compare "$g" --spectral --theta-i 0,45 --paths 2e4 --no-report "${q[@]}" --out "$runs/spectral-compare" >/dev/null 2>&1
keep "$runs/spectral-compare" spectral-compare
"$gonio" compare "$g" --rgb-vs-spectral --theta-i 0,45 --paths 2e4 --no-report "${q[@]}" --out "$runs/rgb-vs-spectral" >/dev/null 2>&1
keep "$runs/rgb-vs-spectral" rgb-vs-spectral
for s in plastic metallic-paint transparent-slab frosted-metal; do
    st="$here/stacks/$s.toml"
    "$gonio" simulate "$st" --theta-i 0,45 --paths 2e4 --general-walk "${q[@]}" --out "$runs/g.$s" >/dev/null 2>&1
    keep "$runs/g.$s" "general.$s"
    "$gonio" simulate "$st" --theta-i 0,45 --paths 4e3 --cpu-twin "${q[@]}" --out "$runs/c.$s" >/dev/null 2>&1
    keep "$runs/c.$s" "cpu-twin.$s"
    "$gonio" simulate "$st" --theta-i 0,45 --paths 2e4 --orders "${q[@]}" --out "$runs/o.$s" >/dev/null 2>&1
    keep "$runs/o.$s" "orders.$s"
    "$gonio" simulate "$st" --theta-i 0,45 --paths 2e4 --no-series --no-baked-stack "${q[@]}" --out "$runs/n.$s" >/dev/null 2>&1
    keep "$runs/n.$s" "no-series.$s"
    "$gonio" simulate "$st" --theta-i 30 --rse 0.3 --paths 1e7 "${q[@]}" --out "$runs/r.$s" >/dev/null 2>&1
    keep "$runs/r.$s" "rse.$s"
    "$gonio" simulate "$st" --theta-i 0,45 --paths 1e4 "${q[@]}" --out "$runs/m.$s" >/dev/null 2>&1
    "$gonio" simulate "$st" --theta-i 0,45 --paths 3e4 --resume "$runs/m.$s" "${q[@]}" --out "$runs/m.$s" >/dev/null 2>&1
    keep "$runs/m.$s" "resumed.$s"
done
for w in "$here"/sweeps/*.toml; do
    n="$(basename "$w" .toml)"
    sed -e 's/^paths = .*/paths = 5e3/' -e "s#\.\./stacks/#$here/stacks/#" "$w" > "$runs/$n.toml"
    "$gonio" sweep "$runs/$n.toml" --batch 7 "${q[@]}" --out "$runs/sweep.$n" >/dev/null 2>&1
    keep "$runs/sweep.$n" "sweep.$n"
done
echo "snapshot: $(ls "$out/kept" | wc -l) files in $out/kept"
