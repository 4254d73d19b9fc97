"""What the paper benchmarks impact2d.py (Sect. 5) and impact3d.py (Sect. 6) share: running
a study of benchmarks/studies/ through its Snakemake workflow, reading its tables, the
Hertz force history and the force histories of its runs' result files."""
import argparse
import csv
import json
import os
import subprocess
import sys

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STUDIES = os.path.join(ROOT, "benchmarks", "studies")


def run_study(name, build, out, jobs, caller):
    """The study `name` through its workflow with `jobs` cores; returns its table rows and
    its timings by run. A second call reruns nothing that is up to date."""
    study = os.path.join(STUDIES, f"{name}.yaml")
    cmd = ["snakemake", "-s", os.path.join(STUDIES, "Snakefile"), "-j", str(jobs), "-q",
           "--config", f"study={study}", f"bin={os.path.join(build, 'bin')}", f"out={out}"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{caller}: the study {name} failed (exit {p.returncode}):\n"
                 f"{p.stdout[-2000:]}{p.stderr[-2000:]}")
    base = os.path.join(out, name, name)
    with open(base + ".csv", newline="") as f:
        table = list(csv.DictReader(f))
    with open(base + "_timings.csv", newline="") as f:
        timings = {r["run"]: r for r in csv.DictReader(f)}
    return table, timings


def hertz_curve(fmax, duration):
    """Hertz force history by integrating m* d'' = -K d^1.5 (shape only: scaled to fmax)."""
    # Dimensionless: x'' = -x^1.5 from (0, 1); scale to the given fmax and duration.
    dt, x, v, xs = 1e-4, 0.0, 1.0, [0.0]
    while True:
        a1 = -max(x, 0) ** 1.5
        xh, vh = x + 0.5 * dt * v, v + 0.5 * dt * a1
        a2 = -max(xh, 0) ** 1.5
        x, v = x + dt * vh, v + dt * a2
        if x <= 0:
            break
        xs.append(x)
    f = np.array(xs) ** 1.5
    t = np.linspace(0, duration, len(f))
    return t, f / f.max() * fmax


def run_summary(out, study, run):
    """The summary.json the workflow wrote for one run (its result file, its SIDs, ...)."""
    with open(os.path.join(out, study, "runs", run, "summary.json")) as f:
        return json.load(f)


def force_history(out, study, run):
    """(time [s], normal force [N]) of the first contact pair of one run's result file."""
    with h5py.File(run_summary(out, study, run)["result"], "r") as f:
        pair = list(f["contacts"].keys())[0]
        return f["time"][:], f["contacts"][pair]["normal_force"][:]


def arguments(doc):
    """The options both benchmarks take: --build, --out, --plot, --json."""
    ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "studies"))
    ap.add_argument("--plot", default=None)
    ap.add_argument("--json", default=None)
    return ap


def save_plot(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    print(f"\nplot: {path}")
