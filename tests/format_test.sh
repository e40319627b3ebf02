#!/usr/bin/env bash
# The C++ of host/ and tests/ is laid out as .clang-format says (120 columns): clang-format -i FILE fixes a file.
set -u
cd "$(dirname "$0")/.."
files=$(git ls-files 'host/*.cpp' 'host/*.h' 'tests/*.cpp' 'tests/*.h' 2>/dev/null || find host tests -name '*.cpp' -o -name '*.h')
bad=0 n=0
for f in $files; do
    n=$((n + 1))
    if ! clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then
        echo "FAIL: $f is not formatted (clang-format -i $f)"
        bad=$((bad + 1))
    fi
done
echo "format: $((n - bad)) passed, $bad failed"
[ "$bad" = 0 ]
