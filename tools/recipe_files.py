#!/usr/bin/env python3
"""recipe_files.py: a recipe of docs/ARCHITECTURE.md ("How to add ...", "New dimensions") held against the files a
real addition touched.

usage: tools/recipe_files.py RECIPE BASE [HEAD]      (from the repository root; HEAD defaults to HEAD)
       RECIPE: kind | medium | model | command | dimension

The recipe's files are the paths its paragraph names in backticks (`host/core/stack.h`; a bare name such as `stack.cpp`
is the root's file of that name, or else found by its name in the tree; `a.{h,cpp}` and `a.h/.cpp` are both files; NAME, NN-ID and N stand for any part of
a name). The addition's files are `git diff --name-only BASE HEAD`. It prints, by folder, the files named and
touched, touched but not named (code, then tests and docs), and named but not touched, and a last line of counts:

    recipe kind: 11 code files touched, 9 of them named by the recipe; 2 not named; 3 named, not touched; 4 tests, 2 docs

Exit 0 whatever it finds (it measures); 2 on bad usage.
"""
import fnmatch
import os
import re
import subprocess
import sys

ARCHITECTURE = "docs/ARCHITECTURE.md"
# Where each recipe's paragraph starts in ARCHITECTURE (it runs to the next blank line; the dimension's to the next
# section)
STARTS = {
    "kind": "**An interface kind.**",
    "medium": "**A medium**",
    "model": "**A built-in model**",
    "command": "**A command**",
    "dimension": "## New dimensions",
}
PATHLIKE = re.compile(r"^[A-Za-z0-9_./{},*-]+$")
EXTENSIONS = (".cpp", ".h", ".glsl", ".comp", ".frag", ".vert", ".toml", ".sh", ".py", ".md", ".cmake", ".txt")


def paragraph(text, recipe):
    start = text.index(STARTS[recipe])
    end = text.find("\n## ", start + 1) if recipe == "dimension" else text.find("\n\n", start)
    return text[start:end if end >= 0 else len(text)]


def expand(token):
    """`a/b.{h,cpp}` -> a/b.h, a/b.cpp; `a/b.h/.cpp` -> a/b.h, a/b.cpp; placeholders -> glob patterns."""
    m = re.match(r"^(.*)\{([^}]*)\}(.*)$", token)
    if m:
        return [p for part in m.group(2).split(",") for p in expand(m.group(1) + part + m.group(3))]
    m = re.match(r"^(.*)\.([a-z]+)/\.([a-z]+)$", token)
    if m:
        return [f"{m.group(1)}.{m.group(2)}", f"{m.group(1)}.{m.group(3)}"]
    for placeholder in ("NN-ID", "NAME", "ID", "N"):
        token = re.sub(rf"(?<![A-Za-z]){placeholder}(?![a-z])", "*", token)
    return [token]


def recipe_files(text, tracked):
    """The files the recipe names: the tracked files its exact names resolve to, and its patterns (a placeholder's
    glob, or a folder ending in /), of which an addition touches one file or a few."""
    exact, patterns = set(), []
    for token in re.findall(r"`([^`]+)`", text):
        token = token.split(" ")[0].rstrip(",.;:")
        if not PATHLIKE.match(token) or not (("/" in token) or token.endswith(EXTENSIONS)):
            continue
        for pattern in expand(token):
            if pattern.endswith("/") or "*" in pattern:
                patterns.append(pattern)
            elif pattern.endswith(EXTENSIONS):   # a bare name: the root's file of that name, else any of that name
                bare = "/" not in pattern and pattern not in tracked
                exact.update(f for f in tracked if f == pattern or (bare and os.path.basename(f) == pattern))
    return exact, patterns


def matches(path, pattern):
    return path.startswith(pattern) if pattern.endswith("/") else fnmatch.fnmatch(path, pattern)


def kind_of(path):
    if path.startswith("tests/") or path.startswith("stacks/hard/"):   # a hard stack is a test's input
        return "test"
    if path.endswith(".md") or path.startswith("docs/"):
        return "doc"
    return "code"


def by_folder(paths):
    out = {}
    for p in sorted(paths):
        out.setdefault(os.path.dirname(p) or ".", []).append(os.path.basename(p))
    return out


def show(title, paths):
    print(f"{title} ({len(paths)}):")
    for folder, names in by_folder(paths).items():
        print(f"  {folder}/: {', '.join(names)}")


def git(*args):
    """The lines git prints."""
    return subprocess.run(["git", *args], check=True, capture_output=True, text=True).stdout.split("\n")


def main(argv):
    if len(argv) not in (3, 4) or argv[1] not in STARTS:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    recipe, base = argv[1], argv[2]
    head = argv[3] if len(argv) == 4 else "HEAD"
    try:
        tracked = [f for f in git("ls-files") if f]
        touched = {f for f in git("diff", "--name-only", base, head) if f}
    except subprocess.CalledProcessError as e:
        print(f"recipe_files: git: {e.stderr.strip()}", file=sys.stderr)
        return 2
    text = paragraph(open(ARCHITECTURE).read(), recipe)
    exact, patterns = recipe_files(text, tracked)
    named = {f for f in touched if f in exact or any(matches(f, p) for p in patterns)}
    code = {f for f in touched if kind_of(f) == "code"}
    missed = sorted(f for f in exact - touched if kind_of(f) == "code") + \
        [p for p in patterns if not any(matches(f, p) for f in touched) and kind_of(p) == "code"]
    show(f"named by the recipe and touched by {base}..{head}", sorted(code & named))
    show("touched, not named (code)", sorted(code - named))
    show("touched (tests)", sorted(f for f in touched if kind_of(f) == "test"))
    show("touched (docs)", sorted(f for f in touched if kind_of(f) == "doc"))
    show("named, not touched (files, and patterns no touched file matches)", missed)
    print(f"recipe {recipe}: {len(code)} code files touched, {len(code & named)} of them named by the recipe; "
          f"{len(code - named)} not named; {len(missed)} named, not touched; "
          f"{sum(kind_of(f) == 'test' for f in touched)} tests, {sum(kind_of(f) == 'doc' for f in touched)} docs")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
