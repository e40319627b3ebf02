"""What the study scripts (tools/study_*.py) share: the first line of a study's data set, which says where it came
from (docs/STUDIES.md)."""
import argparse
import csv
import json
import os
import subprocess

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")


def provenance(tool, sweep_dir, data_path, figure_path):
    """'# gonio VERSION at commit C; regenerate: ...': the build's version, the checkout's commit, and the two commands
    (the sweep's file from SWEEP_DIR/sweep.json) that write the data set again"""
    version = "gonio (version unknown)"
    try:
        version = subprocess.run([os.path.join(ROOT, "build", "gonio"), "--version"], capture_output=True,
                                 text=True).stdout.strip() or version
        commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True).stdout.strip()
        version += f" at commit {commit}" if commit else ""
    except OSError:
        pass
    with open(os.path.join(sweep_dir, "sweep.json")) as fh:
        sweep_file = os.path.relpath(json.load(fh)["sweep_file"])
    return (f"# {version}; regenerate: build/gonio sweep {sweep_file} --out {sweep_dir} && python3 tools/{tool} "
            f"{sweep_dir} {data_path} {figure_path}\n")


def write_runs_data(gonio, data_path, rows, regenerate):
    """a study of runs' DATA.csv: its first line '# gonio VERSION at commit C; regenerate: REGENERATE' (the gonio
    binary's version, the checkout's commit), then the rows (dicts, the first one's keys as the header)"""
    version = "gonio (version unknown)"
    try:
        version = subprocess.run([gonio, "--version"], capture_output=True, text=True).stdout.strip() or version
    except OSError:
        pass
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    with open(data_path, "w", newline="") as fh:
        fh.write(f"# {version} at commit {commit}; regenerate: {regenerate}\n")
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def runs_arguments(doc):
    """the arguments every study of runs takes: WORK_DIR, DATA.csv, --paths, --gonio (its own added by the caller)"""
    p = argparse.ArgumentParser(description=doc.split("\n\n")[0])
    p.add_argument("work")
    p.add_argument("data")
    p.add_argument("--paths", default="1e6")
    p.add_argument("--gonio", default=os.path.join(ROOT, "build", "gonio"))
    return p
