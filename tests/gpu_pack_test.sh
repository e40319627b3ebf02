#!/usr/bin/env bash
# tools/gpu_pack.sh packs what runs here: the pack unpacks into its own folder and its run.sh, through the packed
# dynamic loader and libraries, lists the device and passes one test that dispatches (run.sh check).
# usage: gpu_pack_test.sh BUILD_DIR   (from the repository's root)
set -euo pipefail
build="$1"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
tools/gpu_pack.sh "$build" "$tmp/pack" | tee "$tmp/pack.log"
grep -qE "gpu_pack: .*, [0-9.]+M " "$tmp/pack.log" || { echo "FAIL: no size printed"; exit 1; }
size=$(du -sm "$tmp/pack" | cut -f1)
[ "$size" -le 64 ] || { echo "FAIL: the pack is $size MiB, above the 64 MiB the device tool carries"; exit 1; }
TMPDIR="$tmp" OUT="$tmp/out" "$tmp/pack/run.sh" check > "$tmp/run.log" 2>&1 || { cat "$tmp/run.log"; echo "FAIL: run.sh check"; exit 1; }
grep -q "^\* 0: " "$tmp/out/devices.txt" || { cat "$tmp/run.log"; echo "FAIL: no device listed"; exit 1; }
grep -q "PASSED" "$tmp/out/test_verdict.txt" || { cat "$tmp/out/test_verdict.txt"; echo "FAIL: test_verdict"; exit 1; }
# the binaries ran from the unpacked folder, through its loader
[ -x "$tmp/gonio-gpu/lib/ld-linux-x86-64.so.2" ] && [ -x "$tmp/gonio-gpu/bin/gonio" ] || { echo "FAIL: not unpacked"; exit 1; }
echo "gpu_pack: ok ($size MiB)"
