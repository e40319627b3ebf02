#!/usr/bin/env bash
# ./run gonio ARGS installs and builds only what running gonio ARGS needs (GONIO_RUN_PLAN=1 prints the plan):
# a simulation none of the tests' packages, the viewer's or the environment maps, and only the gonio target; a
# render under one of Blender's maps blender-data; gonio view the viewer's packages and gonio-view.
# usage: run_plan_test.sh   (from the repository root)
set -u
fails=0
plan() { GONIO_RUN_PLAN=1 ./run gonio "$@"; }
has() { grep -qw -- "$2" <<<"$1"; }
expect() {   # expect WHAT yes|no WORD PLAN
    local got=no
    has "$4" "$3" && got=yes
    [ "$got" = "$2" ] || { echo "FAIL: $1: '$3' expected $2 in: $4"; fails=$((fails + 1)); }
}
sim="$(plan simulate stacks/plastic.toml --theta-i 0,30,60,80 --paths 1e8 --seed 1 --out out/plastic)"
for p in libgtest-dev munge slurmctld xvfb clang-format vulkan-validationlayers blender-data libglfw3-dev \
         libimgui-dev python3-venv; do
    expect "simulate" no "$p" "$sim"
done
expect "simulate" yes mesa-vulkan-drivers "$sim"
expect "simulate" yes glslang-dev "$sim"
[ "$(grep '^targets:' <<<"$sim")" = "targets: gonio" ] || { echo "FAIL: simulate builds more than gonio: $sim"; fails=$((fails + 1)); }
expect "render --env forest" yes blender-data "$(plan render stacks/plastic.toml --env forest --out x)"
expect "render --env studio" no blender-data "$(plan render stacks/plastic.toml --env studio --out x)"
expect "bench --render sunset" yes blender-data "$(plan bench stacks/plastic.toml --render sunset)"
view="$(plan view stacks/plastic.toml)"
expect "view" yes libimgui-dev "$view"
expect "view" yes gonio-view "$view"
expect "view" no libgtest-dev "$view"
# ./run test installs every group, the lean ones included
for group in BUILD FIGURE VIEWER ENV TEST; do
    grep -q "\"\${${group}_PACKAGES\[@\]}\"" <(sed -n '/^ALL_PACKAGES=/,/)$/p' run) ||
        { echo "FAIL: ALL_PACKAGES leaves out ${group}_PACKAGES"; fails=$((fails + 1)); }
done
[ "$fails" = 0 ] && echo "run_plan_test: ok" || exit 1
