#!/usr/bin/env bash
# The C++ of host/ and tests/ is laid out as .clang-format says (120 columns): clang-format -i FILE fixes a file.
# All the files in one clang-format run (its start-up is most of the time); where that finds a file unformatted, file
# by file, to name each.
set -u
cd "$(dirname "$0")/.."
files=$(git ls-files 'host/*.cpp' 'host/*.h' 'tests/*.cpp' 'tests/*.h' 2>/dev/null || find host tests -name '*.cpp' -o -name '*.h')
n=$(wc -w <<<"$files")
if clang-format --dry-run --Werror $files >/dev/null 2>&1; then
    echo "format: $n passed, 0 failed"
    exit 0
fi
bad=0
for f in $files; do
    if ! clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then
        echo "FAIL: $f is not formatted (clang-format -i $f)"
        bad=$((bad + 1))
    fi
done
echo "format: $((n - bad)) passed, $bad failed"
[ "$bad" = 0 ]
