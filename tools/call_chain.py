#!/usr/bin/env python3
"""call_chain.py: a command's call chain from its options to its summary file, file by file, as a reviewer follows it,
checked against the code and counted.

usage: tools/call_chain.py [compare|render]      (from the repository root; default: both)

Each chain below is the command's run function and, indented under each function, the calls it makes that carry what
the summary file holds (the stack read, the models loaded, the case prepared, the reference, the models' bins, the
metrics, the file written), in the order they run; helpers that compute nothing the file holds are left out, and a
stage's entry point stands for its inside (simulate_gpu for the walk). The tool checks every step against the code
(Universal Ctags): the function is defined in the file named, and its name is called in its caller's body. Control
then passes through the files in that order, into each call and back out of it, up to the call that writes the file.
A move is a step into a file of another folder; a climb is a move to a folder of a higher floor (the layering of
docs/ARCHITECTURE.md: spectral < core < gpu < reference < models < io < render < run < sweep < cli), i.e. control
coming back up from a lower floor. It prints the path and the counts, and exits 1 if a step does not hold.
"""
import json
import re
import subprocess
import sys

FLOORS = ["spectral", "core", "gpu", "reference", "models", "io", "render", "run", "sweep", "cli"]

# (depth, function, file): the chain, each step called by the nearest step above it of one depth less
CHAINS = {
    "compare": """
run_compare host/cli/cmd_compare.cpp
  stack_operand host/cli/simulate_run.cpp
    parse_stack_file host/core/stack.cpp
  load_model_files host/cli/common_options.cpp
    load_user_model host/models/user_model.cpp
  prepare_run host/cli/simulate_run.cpp
  compare_on_device host/cli/cmd_compare.cpp
    run_and_write_case host/run/case.cpp
      run_case host/run/case.cpp
        simulate_gpu host/reference/reference_gpu.cpp
        evaluate_models host/models/model_evaluator.cpp
        models_on_case host/run/case.cpp
          compare_models host/run/comparison.cpp
      write_case host/run/case.cpp
        write_case_files host/run/case.cpp
          models_summary host/run/case.cpp
            models_json host/run/models_json.cpp
          write_summary_json host/io/output.cpp
""",
    "render": """
run_render host/cli/cmd_render.cpp
  check_render_settings host/cli/cmd_render.cpp
    load_model_files host/cli/common_options.cpp
      load_user_model host/models/user_model.cpp
  parse_stack_file host/core/stack.cpp
  render_to_directory host/run/render_case.cpp
    render_sphere_stage host/render/sphere_stage.cpp
      load_render_environment host/render/sphere_stage.cpp
      simulate_table_halves host/render/sphere_stage.cpp
        simulate_gpu host/reference/reference_gpu.cpp
      table_from_halves host/render/reference_render.cpp
      render_reference host/render/reference_render.cpp
      render_models host/render/model_render.cpp
    write_json_file host/io/json.cpp
""",
}


def parse_chain(text):
    steps = []
    for line in text.strip("\n").split("\n"):
        depth = (len(line) - len(line.lstrip(" "))) // 2
        name, path = line.split()
        steps.append((depth, name, path))
    return steps


def definitions(paths):
    """{(name, path): (first line, last line)} of the functions in these files."""
    out = subprocess.run(["ctags", "--output-format=json", "--fields=+ne", "--kinds-C++=f", "-o", "-", *paths],
                         check=True, capture_output=True, text=True).stdout
    defs = {}
    for line in out.splitlines():
        t = json.loads(line)
        if t.get("_type") == "tag" and "end" in t:
            defs[(t["name"], t["path"])] = (t["line"], t["end"])
    return defs


def check(steps):
    """The steps that do not hold: (step, why)."""
    defs = definitions(sorted({p for _, _, p in steps}))
    lines = {p: open(p).read().split("\n") for _, _, p in steps}
    bad = []
    for i, (depth, name, path) in enumerate(steps):
        if (name, path) not in defs:
            bad.append((name, f"not defined in {path}"))
            continue
        if depth == 0:
            continue
        caller = next(s for s in reversed(steps[:i]) if s[0] == depth - 1)
        first, last = defs.get((caller[1], caller[2]), (0, -1))
        body = "\n".join(lines[caller[2]][first - 1:last])
        if not re.search(rf"\b{re.escape(name)}\s*\(", body):
            bad.append((name, f"not called in {caller[1]} ({caller[2]})"))
    return bad


def folder(path):
    parts = path.split("/")
    return parts[1] if parts[0] == "host" else parts[0]


def walk(steps):
    """The files control passes through, in order: into each step, and back to its caller after the step's own calls
    (none after the last step: the file is written)."""
    visits, stack = [], []
    for depth, name, path in steps:
        while len(stack) > depth:   # the calls deeper than this one have returned
            stack.pop()
            if stack:
                visits.append(stack[-1])
        stack.append(path)
        visits.append(path)
    return visits


def count(visits):
    moves = climbs = 0
    for a, b in zip(visits, visits[1:]):
        if folder(a) != folder(b):
            moves += 1
            if FLOORS.index(folder(b)) > FLOORS.index(folder(a)):
                climbs += 1
    return moves, climbs


def main(argv):
    names = argv[1:] or list(CHAINS)
    if any(n not in CHAINS for n in names):
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    failed = False
    for n in names:
        steps = parse_chain(CHAINS[n])
        bad = check(steps)
        for name, why in bad:
            print(f"call_chain {n}: {name}: {why}")
        failed = failed or bool(bad)
        visits = walk(steps)
        folders = [folder(visits[0])] + [folder(b) for a, b in zip(visits, visits[1:]) if folder(a) != folder(b)]
        moves, climbs = count(visits)
        print(f"{n}: {' > '.join(folders)}")
        print(f"{n}: {len(steps)} calls, {moves} moves between folders, {climbs} returns to a higher floor")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
