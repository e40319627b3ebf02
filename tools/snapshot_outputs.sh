#!/usr/bin/env bash
# snapshot_outputs.sh GONIO OUT: run gonio on every shipped stack and sweep (small path counts) through every walk
# host (compare, simulate with the general walk, the CPU twin, --orders, --no-series, --no-baked-stack, --rse, a
# resumed run, sweeps batched), and keep slices.csv, sweep.csv and summary.json with timings removed. A refactor
# that changes no number leaves two snapshots identical:
#   tools/snapshot_outputs.sh build-before/gonio /tmp/before; tools/snapshot_outputs.sh build/gonio /tmp/after
#   diff -r /tmp/before /tmp/after
set -euo pipefail
gonio="$(realpath "$1")"
out="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
rm -rf "$out"; mkdir -p "$out/runs" "$out/kept"
runs="$out/runs"

# keep FILE AS: copy a run's outputs without the fields that measure time
keep() {
    local dir="$1" name="$2"
    [ -f "$dir/slices.csv" ] && cp "$dir/slices.csv" "$out/kept/$name.slices.csv"
    [ -f "$dir/sweep.csv" ] && cp "$dir/sweep.csv" "$out/kept/$name.sweep.csv"
    if [ -f "$dir/summary.json" ]; then
        python3 - "$dir/summary.json" "$out/kept/$name.summary.json" <<'EOF'
import json, re, sys
timing = re.compile(r"(seconds|paths_per_second|ns_per_evaluation|^device$|^driver|^host$|^date|^gonio_version)")
def strip(o):
    if isinstance(o, dict):
        return {k: strip(v) for k, v in o.items() if not timing.search(k)}
    if isinstance(o, list):
        return [strip(v) for v in o]
    return o
json.dump(strip(json.load(open(sys.argv[1]))), open(sys.argv[2], "w"), indent=1, sort_keys=True)
EOF
    fi
}

q=(--quiet)
for s in "$here"/stacks/*.toml "$here"/stacks/hard/*.toml; do
    n="$(basename "$s" .toml)"
    "$gonio" compare "$s" --theta-i 0,30,60,80 --paths 2e4 --no-report "${q[@]}" --out "$runs/$n" >/dev/null 2>&1 || true
    keep "$runs/$n" "compare.$n"
done
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
