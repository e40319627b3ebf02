#!/usr/bin/env python3
"""Export a gonio table (a simulate / compare output over many incident angles) to a format renderers read.

usage: export.py DIR --format merl|rgl-bsdf --out FILE [--source reference|MODEL_ID]

  merl   MERL .binary (Matusik et al. 2003): isotropic, reflection, RGB; needs incident angles from 0 to at least
         80 degrees at most 5 degrees apart (gonio simulate STACK --theta-i 0,2,...,88). Cells below the horizon,
         or beyond the last tabulated angle, are written as "no data" (negative).
  rgl-bsdf  RGL .bsdf tensor file (Dupuy & Jakob 2018) for Mitsuba 3's `measured` plugin (scalar_rgb):
         reflection, RGB; the same angles needed; needs the mitsuba package (pip install mitsuba), whose warp
         places the file's nodes.
Exit codes: 0 written; 2 a table or option that cannot be exported (the reason on stderr); 1 a failure.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import gonio  # noqa: E402
from gonio.outputs import FormatError  # noqa: E402
from gonio.table import TableError, export_merl  # noqa: E402
from gonio import rgl  # noqa: E402


def main():
    ap = argparse.ArgumentParser(prog="gonio export", description=__doc__.split("\n\n")[0])
    ap.add_argument("dir")
    ap.add_argument("--format", required=True, choices=["merl", "rgl-bsdf"])
    ap.add_argument("--out", required=True)
    ap.add_argument("--source", default="reference", help="reference (default) or a model id of a compare output")
    a = ap.parse_args()
    try:
        run = gonio.read_run(a.dir)
        if a.source not in run.sources():
            raise TableError(f"{a.dir} has no {a.source!r}; it has {', '.join(run.sources())}")
        if a.format == "merl":
            covered = export_merl(run, a.out, a.source)
            print(f"wrote {a.out} (MERL, {a.source}; {100 * covered:.1f}% of the cells have data, the rest is below "
                  f"the horizon or beyond the last incident angle)")
        else:
            try:
                import mitsuba  # noqa: F401
            except ImportError:
                raise TableError("--format rgl-bsdf needs the mitsuba package (pip install mitsuba)")
            rgl.export_rgl(run, a.out, a.source)
            print(f"wrote {a.out} (RGL .bsdf, {a.source}; Mitsuba 3: {{'type': 'measured', 'filename': '{a.out}'}})")
    except (TableError, FormatError, FileNotFoundError) as e:
        print(f"gonio export: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
