#!/usr/bin/env bash
# function_length_test.sh: no function over 100 lines (the house rule, docs/ARCHITECTURE.md) in host, shaders, tests,
# tools or python: C++, GLSL (as C++) and Python functions by Universal Ctags' end lines, and GoogleTest's TEST bodies
# (which ctags does not see as functions) by their braces. GONIO_MAX_FUNCTION_LINES overrides the limit (a check of
# the check: at 50 it names the longest).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
limit="${GONIO_MAX_FUNCTION_LINES:-100}"
command -v ctags >/dev/null || { echo "function_length: needs Universal Ctags (Debian's universal-ctags)"; exit 1; }
ctags --version | grep -q "Universal Ctags" || { echo "function_length: ctags is not Universal Ctags"; exit 1; }
long=$(
    {
        ctags -R --sort=no -f - --languages=C++,Python --langmap=C++:+.glsl.comp --kinds-C++=f --kinds-Python=fm \
            --fields=+ne -x --_xformat="%{end} %{line} %F %N" host shaders tests tools python
        /usr/bin/env python3 - <<'PY'
import glob, re
for f in sorted(glob.glob("tests/*.cpp")):
    lines = open(f, encoding="utf-8").read().split("\n")
    for i, l in enumerate(lines):
        if not re.match(r"^(TEST|TEST_F|TEST_P)\(", l):
            continue
        depth, opened = 0, False
        for j in range(i, len(lines)):
            depth += lines[j].count("{") - lines[j].count("}")
            opened = opened or "{" in lines[j]
            if opened and depth <= 0:
                name = re.sub(r"[ ,]+", ".", l.split("(", 1)[1].split(")", 1)[0])
                print(j + 1, i + 1, f, name)
                break
PY
    } | awk -v limit="$limit" '$1 ~ /^[0-9]+$/ && $1 - $2 + 1 > limit { print $1 - $2 + 1 " lines: " $3 ":" $2 " " $4 }' |
        sort -rn
)
if [ -n "$long" ]; then
    echo "function_length: functions over $limit lines (make them shorter: parameterised cases, helpers):"
    echo "$long"
    exit 1
fi
echo "function_length: no function over $limit lines"
