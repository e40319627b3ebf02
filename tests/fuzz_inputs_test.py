#!/usr/bin/env python3
"""Seeded, time-bounded fuzzing of every surface where gonio reads data from outside (issue "nothing from outside is
trusted"): stack files, sweep files, state files, model headers, values files and option strings. Each case mutates a
valid input at the byte or field level (flips, random bytes, NULs, truncation, repeated and swapped lines, extreme
numbers; a state file's fields rewritten with a fresh CRC-32C so that its field checks, not its checksum, are what is
tried) and runs the command that reads it. Every run must:
  - exit 0, 1 or 2 (no signal, no abort), and never print "a bug, please report it";
  - finish within its time limit (no hang) and within its memory limit (RLIMIT_AS; no runaway allocation).
Each surface gets its share of the time; a failure prints the case (surface, seed, command) and keeps its input.

usage: fuzz_inputs_test.py path/to/gonio [seed] [seconds]   (from the repository root; seed 1, 90 s by default)
"""
import os
import random
import re
import resource
import shutil
import struct
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from state_tamper import ANGLE, HEADER, crc32c   # the state file's layout and checksum, written once

MEMORY_LIMIT = 8 << 30   # address space per run (lavapipe's JIT reserves some; a run here needs far less)
CASE_TIMEOUT = 60


def limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))


def run(cmd, timeout=CASE_TIMEOUT):
    """(return code or 'timeout', output)"""
    try:
        p = subprocess.run(cmd, capture_output=True, timeout=timeout, preexec_fn=limit_memory)
    except subprocess.TimeoutExpired:
        return "timeout", ""
    return p.returncode, (p.stdout + p.stderr).decode("utf-8", "replace")


# ---- mutations of bytes and text ---------------------------------------------------------------------------------

EXTREMES = [b"0", b"-0", b"1e39", b"-1e39", b"1e-45", b"nan", b"inf", b"-inf", b"1e308", b"4294967296", b"-1",
            b"18446744073709551616", b"0x10", b"1_0", b"\"\"", b"[]", b"[[1]]", b"{}", b"true"]


def mutate_bytes(data, rng):
    """One random byte-level defect."""
    b = bytearray(data)
    kind = rng.randrange(9)
    if not b:
        return bytes(rng.randrange(256) for _ in range(rng.randrange(1, 64)))
    i = rng.randrange(len(b))
    if kind == 0:   # a flipped bit
        b[i] ^= 1 << rng.randrange(8)
    elif kind == 1:   # random bytes over a stretch
        for k in range(i, min(len(b), i + rng.randrange(1, 16))):
            b[k] = rng.randrange(256)
    elif kind == 2:   # a NUL inserted
        b.insert(i, 0)
    elif kind == 3:   # truncated
        del b[i:]
    elif kind == 4:   # a stretch repeated
        j = min(len(b), i + rng.randrange(1, 200))
        b[j:j] = b[i:j] * rng.randrange(1, 4)
    elif kind == 5:   # a number replaced by an extreme one
        nums = [m.span() for m in re.finditer(rb"-?\d+(\.\d+)?(e-?\d+)?", bytes(b))]
        if nums:
            s, e = rng.choice(nums)
            b[s:e] = rng.choice(EXTREMES)
    elif kind == 6:   # two lines swapped
        lines = bytes(b).split(b"\n")
        if len(lines) > 2:
            x, y = rng.randrange(len(lines)), rng.randrange(len(lines))
            lines[x], lines[y] = lines[y], lines[x]
        b = bytearray(b"\n".join(lines))
    elif kind == 7:   # a line repeated
        lines = bytes(b).split(b"\n")
        x = rng.randrange(len(lines))
        lines.insert(x, lines[x])
        b = bytearray(b"\n".join(lines))
    else:   # a long line
        b[i:i] = b"x" * rng.randrange(1000, 100000)
    return bytes(b)


# ---- state files: their fields (host/io/state.cpp, version 8) --------------------------------------------------------

def state_fields(data):
    """The (offset, size) of each fixed-size field of a version-8 state file."""
    n = struct.unpack_from("<Q", data, 8)[0]
    fields = [(8, 8)]   # the stack's length
    o = 16 + n
    for c in HEADER[1:]:
        size = struct.calcsize("<" + c)
        fields.append((o, size))
        o += size
    fields.append((o, 8))   # the angle count
    count = struct.unpack_from("<Q", data, o)[0]
    o += 8
    for _ in range(count):
        head = struct.unpack_from(ANGLE, data, o)
        for c in ANGLE[1:].replace("12q", "q" * 12):
            size = struct.calcsize("<" + c)
            fields.append((o, size))
            o += size
        o += 8 * head[-1]
    return fields


def mutate_state(data, rng):
    """A damaged file (bytes; its checksum then refuses it), or one field rewritten with a fresh checksum."""
    if rng.random() < 0.3:
        return mutate_bytes(data, rng)
    body = bytearray(data[:-4])
    off, size = rng.choice(state_fields(data))
    choice = rng.randrange(4)
    if choice == 0:
        value = bytes(rng.randrange(256) for _ in range(size))
    elif choice == 1:
        value = bytes(size)
    elif choice == 2:
        value = b"\xff" * size
    else:
        fmt = {1: "<B", 4: "<I", 8: rng.choice(["<d", "<Q", "<q"])}[size]
        pool = {"<d": [-1.0, 0.0, 1e-300, 89.999, 90.0, 1e308, float("nan"), float("inf")],
                "<Q": [0, 1, 2 ** 38, 2 ** 63], "<q": [-1, -2 ** 63], "<I": [0, 1, 2 ** 31], "<B": [0, 1, 2, 255]}[fmt]
        value = struct.pack(fmt, rng.choice(pool))
    body[off:off + size] = value
    return bytes(body) + struct.pack("<I", crc32c(bytes(body)))


# ---- model headers ---------------------------------------------------------------------------------------------------

HEADER_LINES = [b"// represents: any", b"// represents: coat-over-lambertian, nothing", b"// reciprocal: maybe",
                b"// energy-conserving: yes (", b"// parameter: a default 1 range [0, 1]",
                b"// parameter: a default 2 range [0, 1]", b"// parameter: A default 1 range [1, 0]",
                b"// gonio-model: reference", b"// gonio-model: a,b", b"// citation:", b"// unknown-key: 1",
                b"#include \"fuzz-self.glsl\"", b"#include \"/dev/zero\"", b"#include \"nowhere.glsl\"",
                b"#define model_f x", b"vec3 model_f(vec3 l, vec3 v) { return vec3(1e39); }"]


def mutate_model(data, rng):
    lines = data.split(b"\n")
    if rng.random() < 0.5:
        lines.insert(rng.randrange(0, 8), rng.choice(HEADER_LINES))
        return b"\n".join(lines)
    head = b"\n".join(lines[:8])
    return mutate_bytes(head, rng) + b"\n" + b"\n".join(lines[8:])


# ---- values files ----------------------------------------------------------------------------------------------------

def mutate_values(data, rng):
    lines = data.split(b"\n")
    if rng.random() < 0.5 and len(lines) > 2:
        i = rng.randrange(len(lines) - 1)
        lines[i] = rng.choice([b"1e39,1,1", b"nan,1,1", b"-1,0,0", b"1,2", b"1,2,3,4", b"", b"a,b,c", b"1e-320,0,0",
                               b"0x1p3,1,1", b" 1 , 2 , 3 ", b"1,1,1\r", b"\x00"])
        return b"\n".join(lines)
    return mutate_bytes(data, rng)


# ---- option strings --------------------------------------------------------------------------------------------------

VALUES = ["0", "-1", "1e30", "1e-30", "nan", "inf", "", "x", "1,2,3", "0:90:1", "0:89.99:0.01", "30,30", "90",
          "K/N", "0/0", "1/0", "log", "all", "ww09", "--paths", "a=b", "layer.1.roughness=0", "1e6", "4294967297",
          "/dev/zero", "-", " ", "\u00e9", "9" * 40]


def options_of(gonio, command):
    """The options a command's --help lists: (name, takes a value)."""
    _, text = run([gonio, command, "--help"])
    out = []
    for m in re.finditer(r"^  (--[a-z0-9-]+)( [A-Z]\S*)?", text, re.M):
        out.append((m.group(1), m.group(2) is not None))
    return out


def option_case(rng, table):
    args = []
    for _ in range(rng.randrange(1, 7)):
        name, takes = rng.choice(table)
        args.append(name)
        if takes or rng.random() < 0.1:
            args.append(rng.choice(VALUES))
    return args


# ---- the surfaces ----------------------------------------------------------------------------------------------------

class Fuzz:
    def __init__(self, gonio, seed, seconds, work):
        self.gonio, self.seed, self.seconds, self.work = gonio, seed, seconds, work
        self.failures, self.cases = [], {}

    def check(self, surface, case, cmd, keep):
        rc, text = run(cmd)
        self.cases[surface] = self.cases.get(surface, 0) + 1
        bad = None
        if rc == "timeout":
            bad = f"no answer in {CASE_TIMEOUT} s"
        elif rc not in (0, 1, 2):
            bad = f"exit {rc}" + (" (a signal)" if rc < 0 else "")
        elif "a bug, please report it" in text:
            bad = "an internal error"
        if bad:
            kept = os.path.join(self.work, f"failed-{surface}-{case}")
            shutil.copy(keep, kept)
            self.failures.append(f"{surface} case {case} (seed {self.seed}): {bad}: {' '.join(cmd)} "
                                 f"[input kept as {kept}] {text[-400:]}")

    def setup(self):
        g, w = self.gonio, self.work
        self.nodes, self.ref = os.path.join(w, "nodes"), os.path.join(w, "ref")
        for cmd in ([g, "nodes", "stacks/plastic.toml", "--theta-i", "30", "--out", self.nodes],
                    [g, "simulate", "stacks/plastic.toml", "--theta-i", "30", "--paths", "2000", "--quiet",
                     "--out", self.ref]):
            rc, text = run(cmd)
            if rc != 0:
                sys.exit(f"setup failed: {' '.join(cmd)}: {text}")
        rows = sum(1 for _ in open(os.path.join(self.nodes, "nodes.csv"))) - 1
        self.values = ("1,1,1\n" * rows).encode()
        self.state = open(os.path.join(self.ref, "state.gonio"), "rb").read()

    def surfaces(self):
        g, w = self.gonio, self.work
        stacks = [os.path.join("stacks", f) for f in sorted(os.listdir("stacks")) if f.endswith(".toml")]
        sweep = open("tests/sweeps/tiny.toml", "rb").read()
        model = open("tests/user_models/ww_corrected_rewrite.glsl", "rb").read()

        def stack_case(rng, i):
            f = os.path.join(w, "fuzz.toml")
            open(f, "wb").write(mutate_bytes(open(rng.choice(stacks), "rb").read(), rng))
            return [g, "check", f], f

        def sweep_case(rng, i):
            f = os.path.join(w, "tests", "sweeps", "fuzz.toml")   # as tiny.toml lies: its "../../stacks/" resolves
            text = mutate_bytes(sweep, rng).replace(b"paths = 20000", b"paths = 200")
            open(f, "wb").write(text)
            return [g, "sweep", f, "--quiet", "--out", os.path.join(w, "sweep-out")], f

        def state_case(rng, i):
            d = os.path.join(w, "state")
            os.makedirs(d, exist_ok=True)
            f = os.path.join(d, "state.gonio")
            open(f, "wb").write(mutate_state(self.state, rng))
            return [g, "score", self.nodes, "--values", os.path.join(w, "ones.csv"), "--id", "ones", "--reference",
                    d, "--no-report", "--out", os.path.join(w, "score-out")], f

        def model_case(rng, i):
            f = os.path.join(w, "fuzz-self.glsl")
            open(f, "wb").write(mutate_model(model, rng))
            # the file is read, its header parsed and the model compiled; then `--models none` is refused (exit 2),
            # before any path is traced
            return [g, "compare", "stacks/plastic.toml", "--model", f, "--models", "none", "--theta-i", "30",
                    "--paths", "64", "--quiet", "--no-report", "--out", os.path.join(w, "model-out")], f

        def values_case(rng, i):
            f = os.path.join(w, "values.csv")
            open(f, "wb").write(mutate_values(self.values, rng))
            return [g, "score", self.nodes, "--values", f, "--id", "v", "--reference", self.ref, "--no-report",
                    "--out", os.path.join(w, "values-out")], f

        tables = {c: options_of(g, c) for c in ["simulate", "compare", "fit", "render", "nodes", "score", "sweep",
                                                  "export", "bench"]}

        def option_surface(rng, i):
            command = rng.choice(sorted(tables))
            f = os.path.join(w, "options.txt")
            args = option_case(rng, tables[command])
            open(f, "w").write(" ".join(args))
            # a stack that does not exist: every option is parsed and checked, and nothing runs
            return [g, command, os.path.join(w, "no-such-stack.toml")] + args, f

        return [("stack", stack_case), ("sweep", sweep_case), ("state", state_case), ("model", model_case),
                ("values", values_case), ("options", option_surface)]

    def go(self):
        os.makedirs(os.path.join(self.work, "tests", "sweeps"), exist_ok=True)
        os.symlink(os.path.abspath("stacks"), os.path.join(self.work, "stacks"))
        self.setup()
        open(os.path.join(self.work, "ones.csv"), "wb").write(self.values)
        surfaces = self.surfaces()
        share = self.seconds / len(surfaces)
        for k, (name, make) in enumerate(surfaces):
            rng = random.Random(f"{self.seed}-{name}")
            end = time.monotonic() + share
            i = 0
            while time.monotonic() < end or i == 0:
                cmd, keep = make(rng, i)
                self.check(name, i, cmd, keep)
                i += 1


def main():
    gonio = os.path.realpath(sys.argv[1])
    seed = int(sys.argv[2]) if len(sys.argv) > 2 else 1
    seconds = float(sys.argv[3]) if len(sys.argv) > 3 else 90
    work = tempfile.mkdtemp(prefix="gonio-fuzz-inputs-")
    fuzz = Fuzz(gonio, seed, seconds, work)
    fuzz.go()
    total = sum(fuzz.cases.values())
    print("fuzz inputs:", ", ".join(f"{s} {n}" for s, n in fuzz.cases.items()), f"cases; {len(fuzz.failures)} failed")
    for f in fuzz.failures:
        print("FAIL:", f)
    if fuzz.failures:
        print("inputs kept in", work)
        sys.exit(1)
    shutil.rmtree(work)
    print(f"fuzz inputs: {total} cases, none crashed, hung or ran out of memory")


if __name__ == "__main__":
    main()
