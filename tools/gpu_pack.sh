#!/usr/bin/env bash
# gpu_pack.sh: gonio, its device tests and every shared library they load, in one folder that runs on a machine with
# only a GPU driver and a Vulkan loader (no package registry, any glibc): the binaries are started through the
# packed dynamic loader with the packed libraries first, so they find the Debian 12 libraries they were built with;
# the Vulkan loader and the GPU's driver (its ICD, found by the loader as usual) are the machine's own where it has
# them, else the packed loader.
#
#   tools/gpu_pack.sh [BUILD_DIR] [PACK_DIR]     (defaults: build, build/gpu-pack; BUILD_DIR built with the tests)
#   PACK_DIR/run.sh [bench|tests|all|check]      (on the GPU machine, from the repository's root: stacks/ and tests/
#                                                 are the checkout's own; what it measured goes to $OUT or out/gpu)
#
# The pack is run.sh and gonio-gpu.tar.xz: bin/ (gonio and the device tests' binaries, stripped), lib/ (what ldd says
# they load, glibc and its loader included, the Vulkan loader apart in lib/vulkan/) and source_dir; run.sh unpacks it
# into a temporary folder. It is meant to travel with the working tree (the device tool's `carry`: 64 MiB at most).
# The binaries embed the same SPIR-V, each about 14 MiB stripped: gzip's 32 KiB window saw no repeat between them
# (67 MiB for 14 binaries); xz with a 64 MiB dictionary at its fastest preset packs them in 14 MiB, 178 MiB unpacked,
# in 11 s here. run.sh unpacks with xz, or with Python's lzma where the machine has no xz; it prints its size.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(cd "${1:-$here/build}" && pwd)"
pack="${2:-$build/gpu-pack}"
# the device tests (ctest label gpu): their binaries, as CMakeLists.txt names them
tests=(closed_form reference reference_session output models belcour verdict hard_cases model_bins scattering_walk
       user_model render series)
[ -x "$build/gonio" ] || { echo "gpu_pack: no $build/gonio (./run build first)" >&2; exit 2; }
for t in "${tests[@]}"; do
    [ -x "$build/test_$t" ] || { echo "gpu_pack: no $build/test_$t (configure with -DBUILD_TESTING=ON)" >&2; exit 2; }
done
rm -rf "$pack"
stage="$(mktemp -d)"
trap 'rm -rf "$stage"' EXIT
mkdir -p "$pack" "$stage/bin" "$stage/lib/vulkan"
cp "$build/gonio" "$stage/bin/"
for t in "${tests[@]}"; do cp "$build/test_$t" "$stage/bin/"; done
strip --strip-unneeded "$stage"/bin/*
# every library the binaries load (ldd: the resolved paths), the dynamic loader among them
for b in "$stage"/bin/*; do ldd "$b"; done | awk '$3 ~ /^\// { print $3 } $1 ~ /^\/.*ld-linux/ { print $1 }' | sort -u |
    while read -r lib; do
        case "$(basename "$lib")" in
            libvulkan.so*) cp -L "$lib" "$stage/lib/vulkan/" ;;   # used only where the machine has no loader
            *) cp -L "$lib" "$stage/lib/" ;;
        esac
    done
loader="$(cd "$stage/lib" && ls ld-linux-*.so.* | head -1)"
# where the binaries look for stacks/, tests/ and tools/ (compiled in: GONIO_SOURCE_DIR)
echo "$here" > "$stage/source_dir"
tar -C "$stage" -cf - bin lib source_dir | xz --lzma2=preset=1,dict=64MiB -c > "$pack/gonio-gpu.tar.xz"
cat > "$pack/run.sh" <<RUN
#!/usr/bin/env bash
# run.sh: gonio's bench and device tests on this machine's GPU, from the packed binaries (tools/gpu_pack.sh).
#   run.sh [bench|tests|all|check]   from the repository's root; results in \$OUT (else out/gpu); check: the device
#                                    and one quick test, to try the pack
set -uo pipefail
here="\$(cd "\$(dirname "\${BASH_SOURCE[0]}")" && pwd)"
pack="\${TMPDIR:-/tmp}/gonio-gpu"
unxz_stream() {   # the archive decompressed to stdout: xz, else Python's lzma
    if command -v xz >/dev/null; then xz -dc "\$1"; else python3 -c 'import lzma, shutil, sys
shutil.copyfileobj(lzma.open(sys.argv[1]), sys.stdout.buffer)' "\$1"; fi
}
if [ ! -f "\$pack/source_dir" ] || [ "\$here/gonio-gpu.tar.xz" -nt "\$pack/source_dir" ]; then
    rm -rf "\$pack" && mkdir -p "\$pack" && unxz_stream "\$here/gonio-gpu.tar.xz" | tar -C "\$pack" -xf - ||
        { echo "run.sh: cannot unpack \$here/gonio-gpu.tar.xz into \$pack" >&2; exit 2; }
fi
what="\${1:-all}"
out="\${OUT:-out/gpu}"
mkdir -p "\$out"
libs="\$pack/lib"
# the machine's Vulkan loader if it has one (its driver's ICD is registered for it), else the packed one
if ! ldconfig -p 2>/dev/null | grep -q 'libvulkan.so.1 '; then libs="\$libs:\$pack/lib/vulkan"; fi
for d in /usr/lib/x86_64-linux-gnu /usr/lib64 /lib/x86_64-linux-gnu; do [ -e "\$d/libvulkan.so.1" ] && libs="\$libs:\$d"; done
run() { "\$pack/lib/$loader" --library-path "\$libs" "\$pack/bin/\$1" "\${@:2}"; }
# the tests read stacks/ and tests/ at the path the build recorded: this checkout stands in for it
src="\$(cat "\$pack/source_dir")"
if [ ! -d "\$src/stacks" ]; then
    mkdir -p "\$(dirname "\$src")" && ln -sfn "\$PWD" "\$src" ||
        { echo "run.sh: the tests need the checkout at \$src (cannot link \$PWD there)" >&2; exit 2; }
fi
export GONIO_NO_CACHE=1
rc=0
run gonio devices | tee "\$out/devices.txt" || rc=1
nproc > "\$out/cpus.txt"; grep -m1 'model name' /proc/cpuinfo >> "\$out/cpus.txt" || true
if [ "\$what" = check ]; then   # the pack itself: the device, and one quick test that dispatches
    run test_verdict --gtest_brief=1 > "\$out/test_verdict.txt" 2>&1 && tail -1 "\$out/test_verdict.txt" || rc=1
fi
if [ "\$what" = bench ] || [ "\$what" = all ]; then
    for s in stacks/plastic.toml stacks/metallic-paint.toml stacks/frosted-metal.toml stacks/transparent-slab.toml \\
             stacks/pigmented-plastic.toml stacks/hazy-metallic-paint.toml; do
        n="\$(basename "\$s" .toml)"
        run gonio bench "\$s" --paths 1e8 --cpu-paths 1e5 --out "\$out/bench-\$n" > "\$out/bench-\$n.txt" 2>&1 || rc=1
        tail -3 "\$out/bench-\$n.txt"
    done
fi
if [ "\$what" = tests ] || [ "\$what" = all ]; then
    for t in $(printf '%s ' "${tests[@]}"); do
        start=\$SECONDS
        if run "test_\$t" > "\$out/test_\$t.txt" 2>&1; then r=passed; else r=FAILED; rc=1; fi
        printf '%-20s %s %d s\n' "test_\$t" "\$r" "\$((SECONDS - start))" | tee -a "\$out/tests.txt"
    done
fi
exit \$rc
RUN
chmod +x "$pack/run.sh"
du -sh "$pack" | awk '{ print "gpu_pack: " $2 ", " $1 " (the device tool carries 64 MiB at most)" }'
