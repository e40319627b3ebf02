#!/usr/bin/env bash
# The commands' call chains of tools/call_chain.py hold against the code (each step defined where it says and called by
# its caller), and compare's, from its options to summary.json, and render's, to render.json, each keep within 12 moves
# between folders and 4 returns to a higher floor (docs/ARCHITECTURE.md "Data flow").
set -uo pipefail
command -v ctags >/dev/null || { echo "call_chain_test: needs Universal Ctags (Debian's universal-ctags)"; exit 1; }
out="$(/usr/bin/python3 tools/call_chain.py)"; rc=$?
echo "$out"
[ "$rc" = 0 ] || { echo "call_chain_test: FAIL: a chain does not hold against the code"; exit 1; }
for command in compare render; do
    read -r moves climbs < <(echo "$out" |
        sed -n "s/^$command: [0-9]* calls, \([0-9]*\) moves between folders, \([0-9]*\) returns.*/\1 \2/p")
    [ -n "${moves:-}" ] && [ "$moves" -le 12 ] && [ "$climbs" -le 4 ] || {
        echo "call_chain_test: FAIL: $command's chain takes ${moves:-?} moves and ${climbs:-?} returns (at most 12 and 4)"
        exit 1
    }
done
# the check can fail: a chain naming a function where it is not defined is refused
sed 's#^  prepare_run host/cli/simulate_run.cpp#  prepare_run host/run/case.cpp#' tools/call_chain.py > "${TMPDIR:-/tmp}/call_chain_broken.py"
broken="$(/usr/bin/python3 "${TMPDIR:-/tmp}/call_chain_broken.py" compare)"; [ $? = 1 ] &&
    echo "$broken" | grep -q "^call_chain compare: prepare_run: not defined in host/run/case.cpp" ||
    { echo "call_chain_test: FAIL: a step in the wrong file was not refused: $broken"; exit 1; }
echo "call_chain_test: ok"
