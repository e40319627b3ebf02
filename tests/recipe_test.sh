#!/usr/bin/env bash
# docs/ARCHITECTURE.md's dimension recipe against the real addition it was measured on (tools/recipe_files.py): the
# incident azimuth's commits touched 55 code files and the recipe names every one; the interface kind's recipe, held
# against the same commits, names few of them (the tool can fail). Skipped where the history is not there (a shallow
# clone).
set -uo pipefail
base=0a255e7 head=5e8ed73
if ! git cat-file -e "$base^{commit}" 2>/dev/null || ! git cat-file -e "$head^{commit}" 2>/dev/null; then
    echo "recipe_test: SKIPPED, commits $base and $head are not in this clone's history"
    exit 77
fi
out="$(/usr/bin/python3 tools/recipe_files.py dimension "$base^" "$head")" || { echo "recipe_test: FAIL: the tool failed"; exit 1; }
echo "$out" | tail -1
echo "$out" | tail -1 | grep -q "^recipe dimension: 55 code files touched, 55 of them named by the recipe; 0 not named;" ||
    { echo "recipe_test: FAIL: the dimension recipe does not name the files its addition touched"; echo "$out"; exit 1; }
kind="$(/usr/bin/python3 tools/recipe_files.py kind "$base^" "$head" | tail -1)"
echo "$kind"
echo "$kind" | grep -Eq "^recipe kind: 55 code files touched, [0-9] of them named by the recipe; [0-9]+ not named;" ||
    { echo "recipe_test: FAIL: the kind's recipe named the azimuth's files (the negative control)"; exit 1; }
/usr/bin/python3 tools/recipe_files.py nothing HEAD > /dev/null 2>&1; [ $? = 2 ] || { echo "recipe_test: FAIL: bad usage not refused"; exit 1; }
echo "recipe_test: ok"
