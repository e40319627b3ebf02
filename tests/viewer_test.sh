#!/usr/bin/env bash
# The viewer (gonio-view) under Xvfb with lavapipe and the validation layer, no human:
#  1. a scripted run changes a parameter and saves a screenshot; the picture must show the panels (not blank;
#     the reference's hemisphere has the frosted metal's copper-coloured lobe where the specular direction is;
#     the difference panels are there) and the validation layer must stay silent;
#  2. resizing the window to 1 pixel and back, an edit that makes the stack file invalid while the viewer runs
#     (kept the previous stack, showed why), then a valid edit (reloaded), then SIGTERM: a clean exit;
#  3. closing the window (as the close button does) ends the viewer cleanly;
#  4. bad usage is refused with a message.
# usage: tests/viewer_test.sh path/to/gonio-view   (from the repository root)
set -uo pipefail
viewer="$1"
if ! command -v Xvfb >/dev/null; then
    echo "viewer_test: SKIPPED, Xvfb is not installed (Debian: apt-get install xvfb)"
    exit 77
fi
tmp="$(mktemp -d)"
pid=""
xpid=""
# Our own X server on a display it picks itself (-displayfd: no clash with another test's), ended by its pid on
# every path out of this script (xvfb-run's own cleanup can fail and leave its server running)
cleanup() {
    [ -n "$pid" ] && kill "$pid" 2>/dev/null
    if [ -n "$xpid" ]; then kill "$xpid" 2>/dev/null; wait "$xpid" 2>/dev/null; fi
    rm -rf "$tmp"
}
trap cleanup EXIT
fail() { echo "viewer_test: FAIL: $*"; for f in "$tmp"/*.log; do [ -f "$f" ] && { echo "--- $f"; tail -n 30 "$f"; }; done; exit 1; }
Xvfb -displayfd 9 -screen 0 1600x1000x24 -nolisten tcp 9>"$tmp/display" > "$tmp/xvfb.log" 2>&1 &
xpid=$!
for _ in $(seq 1 100); do [ -s "$tmp/display" ] && break; kill -0 "$xpid" 2>/dev/null || break; sleep 0.1; done
[ -s "$tmp/display" ] || fail "Xvfb did not start"
export DISPLAY=":$(head -n1 "$tmp/display")"
xvfb() { "$@"; }   # the viewer on our X server
silent() { ! grep -q "vulkan validation" "$1" || fail "the validation layer spoke in $1"; }
wait_for() {   # wait_for FILE PATTERN SECONDS
    for _ in $(seq 1 $((10 * $3))); do grep -q "$2" "$1" && return 0; kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    grep -q "$2" "$1" || fail "no '$2' in $1 after $3 s"
}
start=$(date +%s)
export MESA_SHADER_CACHE_DIR="${MESA_SHADER_CACHE_DIR:-$tmp/mesa-cache}"
cp stacks/frosted-metal.toml "$tmp/frosted.toml"

# 1. scripted run: roughness of the coat 0.2 -> 0.25, models chosen, screenshot after 1 M paths
xvfb "$viewer" stacks/frosted-metal.toml --validate --frames 20 --wait-paths 1000000 --theta-i 30 \
    --set layer.1.roughness=0.25 --set models=ww-corrected,belcour18-forward \
    --set save_dir="$tmp/saved" --set save=toml --set save=exr --screenshot "$tmp/shot.png" > "$tmp/run1.log" 2>&1 || fail "scripted run exited with $?"
silent "$tmp/run1.log"
grep -q "frames/s" "$tmp/run1.log" || fail "no frame rate reported"
grep "frames/s" "$tmp/run1.log"
# saved: the changed stack reads back (gonio check) with the new roughness; the EXR is an OpenEXR file
gonio="$(dirname "$viewer")/gonio"
"$gonio" check "$tmp/saved/frosted-metal-view.toml" > "$tmp/check.log" 2>&1 || fail "the saved stack does not read back"
grep -q "roughness = 0.25" "$tmp/saved/frosted-metal-view.toml" || fail "the saved stack lacks the changed roughness"
[ "$(head -c 4 "$tmp/saved/frosted-metal-view.exr" | od -An -tx1 | tr -d ' ')" = "762f3101" ] || fail "the saved EXR is not OpenEXR"
PYTHONPATH="$PWD/tests" /usr/bin/python3 - "$tmp/shot.png" "$tmp/run1.log" <<'EOF' || fail "the screenshot does not show the expected panels"
import sys
from viewer_png import Screenshot
shot = Screenshot(sys.argv[1], open(sys.argv[2]).read())
w, h, px, disc, panels = shot.w, shot.h, shot.px, shot.disc, shot.panels
assert (w, h) == (1280, 800), f"size {w}x{h}"
# not blank: many distinct colours over the window
colours = {px(x, y) for y in range(0, h, 4) for x in range(0, w, 4)}
assert len(colours) > 500, f"only {len(colours)} colours: blank?"
for need in ["reference", "ww-corrected", "ww-corrected_-_reference", "belcour18-forward", "belcour18-forward_-_reference"]:
    assert need in panels and panels[need][2] > 100, f"panel {need} missing or small: {panels.get(need)}"
# the reference: theta_i = 30, the specular lobe at phi = 180, i.e. u = -sin(30 deg): bright and copper-coloured
# (red > green > blue, the conductor's k = [3.6, 2.6, 2.3]); far from it (grazing, the light's side) it is dark
r, g, b = shot.mean_rgb("reference", -0.5, 0.0)
print(f"viewer_test: reference lobe colour {r:.0f} {g:.0f} {b:.0f}")
assert r > 150 and r > g > b, "the reference's lobe is not bright copper"
far = disc("reference", 0.9, 0.0)
assert sum(far) < r + g + b - 150, f"no contrast between the lobe and grazing angles: {far}"
# the horizon ring is drawn around each panel
ring = disc("reference", 0.7085, 0.7085)   # radius 1.002
assert abs(ring[0] - 140) < 30 and ring[0] == ring[1] == ring[2], f"no horizon ring: {ring}"
# difference panels: signed colours (white-ish where the model agrees, red or blue elsewhere)
d = [disc("ww-corrected_-_reference", u / 10, v / 10) for u in range(-9, 10) for v in range(-9, 10) if u * u + v * v < 81]
assert any(p[0] > p[2] + 40 for p in d) or any(p[2] > p[0] + 40 for p in d), "the difference panel shows no difference"
assert sum(1 for p in d if min(p) > 150) > 0.1 * len(d), "the difference panel is not mostly light"
print("viewer_test: screenshot ok")
EOF
# the README's picture comes from this run
[ -n "${GONIO_VIEWER_SCREENSHOT:-}" ] && cp "$tmp/shot.png" "$GONIO_VIEWER_SCREENSHOT"

# 1b. the light at an incident azimuth (--phi-i 90, then phi_i=270 by --set): the reference's and a model's specular
# lobe turn with it, to phi = 270 (u 0, v -0.5) and then to phi = 90 (v +0.5), and leave phi = 180 (u -0.5)
for phi in 90 270; do
    set=(); [ "$phi" = 270 ] && set=(--set phi_i=270)
    xvfb "$viewer" stacks/frosted-metal.toml --validate --frames 10 --wait-paths 300000 --theta-i 30 --phi-i 90 \
        "${set[@]}" --set models=ww-corrected --screenshot "$tmp/shot-az$phi.png" > "$tmp/run-az$phi.log" 2>&1 ||
        fail "the run at phi_i $phi exited with $?"
    silent "$tmp/run-az$phi.log"
    PYTHONPATH="$PWD/tests" /usr/bin/python3 - "$tmp/shot-az$phi.png" "$tmp/run-az$phi.log" "$phi" <<'EOF' ||
import math, sys
from viewer_png import Screenshot
shot, phi = Screenshot(sys.argv[1], open(sys.argv[2]).read()), float(sys.argv[3])
u, v = 0.5 * math.cos(math.radians(phi + 180)), 0.5 * math.sin(math.radians(phi + 180))
for panel in ("reference", "ww-corrected"):
    lobe, plane = shot.mean_rgb(panel, u, v), shot.mean_rgb(panel, -0.5, 0.0)
    print(f"viewer_test: phi_i {phi:g}, {panel}: lobe {lobe[0]:.0f} {lobe[1]:.0f} {lobe[2]:.0f}, phi 180 {plane[0]:.0f}")
    assert lobe[0] > lobe[1] > lobe[2], f"{panel}: no copper lobe at phi {phi + 180:g}"
    assert sum(plane) < sum(lobe) - 150, f"{panel}: the lobe is still at phi 180"
EOF
        fail "the screenshot at phi_i $phi does not show the lobe turned"
done

# 2. resize to 1x1 and back; the stack file made invalid, then valid again, while the viewer runs; SIGTERM
cp stacks/frosted-metal.toml "$tmp/live.toml"
: > "$tmp/run2.log"
"$viewer" "$tmp/live.toml" --validate --frames 100000000 --resize 5:1x1 --resize 15:900x600 --resize 25:1280x800 \
    >> "$tmp/run2.log" 2>&1 &
pid=$!
wait_for "$tmp/run2.log" "frame 25: resizing" 90
sed -i 's/^roughness = 0.2 .*/roughness = -0.5/' "$tmp/live.toml"
wait_for "$tmp/run2.log" "keeping the previous stack" 30
grep -q "live.toml:.*roughness" "$tmp/run2.log" || fail "the error does not name the file, line and parameter"
sed -i 's/^roughness = -0.5/roughness = 0.3/' "$tmp/live.toml"
wait_for "$tmp/run2.log" "reloaded" 30
sleep 1
kill -TERM "$pid"
wait "$pid"; rc=$?; pid=""
[ "$rc" = 0 ] || fail "the viewer exited with $rc after SIGTERM (resize / reload run)"
silent "$tmp/run2.log"
grep -q "frames/s" "$tmp/run2.log" || fail "no clean shutdown report after SIGTERM"

# 2b. a user's model file (--model): shown, recompiled when it changes; a broken edit keeps the previous model
cp examples/user_model.glsl "$tmp/mine.glsl"
cp tests/user_models/broken.glsl "$tmp/broken.glsl"
: > "$tmp/run2b.log"
"$viewer" stacks/plastic.toml --validate --model "$tmp/mine.glsl" --set models=schlick-coat --frames 100000000 \
    >> "$tmp/run2b.log" 2>&1 &
pid=$!
sleep 5
sed -i 's|return vec3(specular)|return vec3(0.0) * undeclared_thing + vec3(specular)|' "$tmp/mine.glsl"
wait_for "$tmp/run2b.log" "keeping the previous model" 60
grep -q "mine.glsl:[0-9]*:.*undeclared_thing" "$tmp/run2b.log" || fail "the model's compile error does not name the file and line"
cp examples/user_model.glsl "$tmp/mine.glsl"
wait_for "$tmp/run2b.log" "recompiled .*mine.glsl" 60
sleep 1
kill -TERM "$pid"
wait "$pid"; rc=$?; pid=""
[ "$rc" = 0 ] || fail "the viewer exited with $rc after SIGTERM (model file run)"
silent "$tmp/run2b.log"
"$viewer" stacks/plastic.toml --model "$tmp/broken.glsl" > "$tmp/u5.log" 2>&1; [ $? = 2 ] \
    && grep -q "broken.glsl:8:" "$tmp/u5.log" || fail "a broken --model file not refused with its line"

# 3. the window asked to close (the close button's path) at frame 3 of many
xvfb "$viewer" "$tmp/frosted.toml" --validate --frames 100000 --close-at 3 > "$tmp/run3.log" 2>&1 || fail "close run exited with $?"
silent "$tmp/run3.log"
grep -q "frames drawn" "$tmp/run3.log" || fail "closing the window did not end the viewer cleanly"

# 4. bad usage
"$viewer" > "$tmp/u1.log" 2>&1; [ $? = 2 ] && grep -q "no stack file" "$tmp/u1.log" || fail "no stack file not refused"
"$viewer" "$tmp/frosted.toml" --frames 0 > "$tmp/u2.log" 2>&1; [ $? = 2 ] || fail "--frames 0 not refused"
xvfb "$viewer" "$tmp/frosted.toml" --frames 5 --set layer.9.roughness=1 > "$tmp/u3.log" 2>&1; [ $? = 2 ] \
    && grep -q "layers 1 to 2" "$tmp/u3.log" || fail "--set on a missing layer not refused"
env -u DISPLAY -u WAYLAND_DISPLAY "$viewer" "$tmp/frosted.toml" > "$tmp/u4.log" 2>&1; [ $? = 1 ] \
    && grep -q "needs a display" "$tmp/u4.log" || fail "no display: no clear message"
"$viewer" --help | grep -q "usage: gonio-view" || fail "--help"

echo "viewer_test: ok in $(( $(date +%s) - start )) s"
