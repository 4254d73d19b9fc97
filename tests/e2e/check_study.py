"""Parameter studies on Snakemake (issue 14): the workflow of benchmarks/studies/ on the study
tests/e2e/study_penalty_density.yaml (sphere2d_h3 over 3 penalty factors x 2 densities, one
penalty factor negative), run with `snakemake -j2` as a user would:

  * The table has the 6 runs in the study's order; the 2 with the negative penalty factor
    are marked failed with ffrsim's message and exit code 2, the other 4 completed, and the
    rest of the study was not stopped by them.
  * Each distinct body input was built once: 2 SIDs (one per density) for 6 runs; their
    records name the override; the SIDs' ndof and nq are in the table.
  * The figures are the result files' own attributes, bit for bit (repr in the CSV).
  * Physics through the workflow: at 1e17 N/m^3 the force peak is within 1 % of Hertz for
    both densities, and halving the density scales the peak by 2^(-3/5) (Hertz: F_max ~
    m*^(3/5)) to 1 % and the duration by 2^(-2/5) to 1 %: the body override reached the
    SID and the scene override the run. The PNG of the swept parameters exists.
  * A run stopped by SIGTERM in the middle of the impact (a scheduler's time limit) is
    continued by the next invocation with ffrsim --restart and ends as the uninterrupted
    run to 1e-3.
  * A second invocation does nothing; changing one value (3e17 -> 2e17) runs exactly the
    simulations with it (2, one per density) and the collection, builds no SID, and leaves
    the other rows as they were.
  * Bad study files (unknown key, a value that is not a list, a {field} naming no
    parameter): exit code 2 and one line naming the file, the line and the key.

usage: check_study.py SOURCE_DIR BIN_DIR OUT_DIR
"""
import csv
import json
import os
import re
import shutil
import signal
import subprocess
import sys

import h5py

from result_checks import Checks, signal_at_fraction

source, bin_dir, out = sys.argv[1:4]
shutil.rmtree(out, ignore_errors=True)
os.makedirs(out)
check = Checks()
snakefile = os.path.join(source, "benchmarks", "studies", "Snakefile")
study_file = os.path.join(source, "tests", "e2e", "study_penalty_density.yaml")
studies = os.path.join(out, "studies")


def snakemake(study, *extra):
    cmd = ["snakemake", "-s", snakefile, "-j2", "--config", f"study={study}", f"bin={bin_dir}",
           f"out={studies}", *extra]
    return subprocess.run(cmd, capture_output=True, text=True)


def job_counts(text):
    """Jobs per rule from Snakemake's 'Job stats' table (empty when nothing is to be done)."""
    counts = {}
    m = re.search(r"Job stats:\n(.*?)\n\s*\n", text, re.S)
    for line in (m.group(1).splitlines() if m else []):
        parts = line.split()
        if len(parts) >= 2 and parts[1].isdigit() and parts[0] != "total":
            counts[parts[0]] = int(parts[1])
    return counts


def read_table(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


# The study, from nothing.
r = snakemake(study_file)
check(r.returncode == 0, f"snakemake -j2 on the study: exit {r.returncode}")
if r.returncode != 0:
    print(r.stdout[-3000:] + r.stderr[-3000:])
    check.exit()
counts = job_counts(r.stdout + r.stderr)
check(counts.get("sid") == 2 and counts.get("simulate") == 6 and counts.get("collect") == 1,
      f"2 SIDs, 6 runs, 1 collection: {counts}")
table_path = os.path.join(studies, "penalty_density", "penalty_density.csv")
rows = read_table(table_path)
check([(r["penalty_factor"], r["density"]) for r in rows] ==
      [(p, d) for p in ("1e+17", "3e+17", "-1e+17") for d in ("7850", "3925")],
      "6 rows in the study's order (first parameter slowest)")
failed = [r for r in rows if r["status"] != "completed"]
check(len(failed) == 2 and all(r["penalty_factor"] == "-1e+17" for r in failed),
      f"the 2 runs with the negative penalty factor failed, the others completed: "
      f"{[r['status'][:40] for r in rows]}")
check(all(r["status"].startswith("failed: ffrsim exit 2:") and "penalty_factor" in r["status"]
          and r["max_contact_force_N"] == "" for r in failed),
      f"a failed row names ffrsim's exit code and the key, and has no figures: "
      f"{failed[0]['status'] if failed else ''}")

# Each distinct body input built once.
records = sorted(f for f in os.listdir(os.path.join(studies, "sids")) if f.endswith(".json"))
sids = sorted(f for f in os.listdir(os.path.join(studies, "sids")) if f.endswith(".sid.h5"))
check(len(records) == 2 and len(sids) == 2, f"2 SIDs in the cache: {sids}")
overrides = sorted(json.load(open(os.path.join(studies, "sids", f)))["overrides"][0]
                   for f in records)
check(overrides == ["material.density=3925", "material.density=7850"],
      f"one SID per density: {overrides}")
check(all(r["sid:ndof"] == "3154" and r["sid:nq"] == "64" for r in rows if r not in failed),
      "the SIDs' ndof (3154) and nq (64) in the table (configs/bodies/sphere2d_h3.yaml)")

# The figures are the result files' attributes, bit for bit.
summaries = {}
for r in rows:
    with open(os.path.join(studies, "penalty_density", "runs", r["run"], "summary.json")) as f:
        summaries[r["run"]] = json.load(f)
same = True
for r in rows:
    if r["status"] != "completed":
        continue
    with h5py.File(summaries[r["run"]]["result"], "r") as f:
        for k in ("max_contact_force_N", "contact_duration_s", "force_vs_hertz"):
            same &= float(r[k]) == float(f.attrs[k])
check(same, "the table's figures equal the result files' attributes bit for bit")

# Physics through the workflow.
by = {(r["penalty_factor"], r["density"]): r for r in rows}
heavy, light = by[("1e+17", "7850")], by[("1e+17", "3925")]
for r in (heavy, light):
    check(abs(float(r["force_vs_hertz"])) < 0.01,
          f"density {r['density']}: force peak {float(r['force_vs_hertz']):+.3%} from Hertz")
force_ratio = float(light["max_contact_force_N"]) / float(heavy["max_contact_force_N"])
duration_ratio = float(light["contact_duration_s"]) / float(heavy["contact_duration_s"])
check(abs(force_ratio / 2 ** -0.6 - 1) < 0.01,
      f"half the density: force peak x {force_ratio:.4f} (Hertz 2^(-3/5) = {2 ** -0.6:.4f})")
check(abs(duration_ratio / 2 ** -0.4 - 1) < 0.01,
      f"half the density: duration x {duration_ratio:.4f} (Hertz 2^(-2/5) = {2 ** -0.4:.4f})")
for p in ("penalty_factor", "density"):
    png = os.path.join(studies, "penalty_density", f"penalty_density_{p}.png")
    check(os.path.exists(png) and open(png, "rb").read(8) == b"\x89PNG\r\n\x1a\n",
          f"picture against {p}")
timings = read_table(os.path.join(studies, "penalty_density", "penalty_density_timings.csv"))
check(len(timings) == 6 and all(float(t["wall_time_s"]) > 0 for t in timings
                                if t["wall_time_s"]),
      "the timings table has every run")

# A second invocation does nothing.
r = snakemake(study_file)
check(r.returncode == 0 and "Nothing to be done" in r.stdout + r.stderr,
      "a second invocation does nothing")

# A run stopped by a scheduler (SIGTERM in the middle of the impact, as at a Slurm time
# limit) is continued from its result file when the workflow runs again. As after such an
# invocation: the run has no summary and the study no table (the collection never ran).
sys.path.insert(0, os.path.join(source, "benchmarks", "studies"))
from study_file import Study  # noqa: E402
import study_jobs  # noqa: E402
study = Study(study_file)
run = next(r for r in study.runs(study_jobs.program_versions(bin_dir))
           if r.values == {"penalty_factor": 1.0e17, "density": 7850})
run_dir = os.path.join(studies, "penalty_density", "runs", run.id)
before = json.load(open(os.path.join(run_dir, "summary.json")))
os.remove(os.path.join(run_dir, "summary.json"))
os.remove(table_path)
result = os.path.join(run_dir, "result.h5")
cmd = [os.path.join(bin_dir, "ffrsim"), "-v", run.scene, "-o", result]
for s in run.ffrsim_sets(os.path.join(studies, "sids")):
    cmd += ["--set", s]
# Progress lines every 50 ms of wall time, so that the signal lands near 40 % of this
# ~1 s run (with the default 1 s, the first line may come after the end).
cmd += ["--set", "outputs.progress_interval=0.05"]
code, _ = signal_at_fraction(cmd, 1.0e-4, 0.4, signal.SIGTERM)
with h5py.File(result, "r") as f:
    status = f.attrs["status"]
check(code == 1 and status.startswith("interrupted by SIGTERM"),
      f"the run stopped by SIGTERM: exit {code}, {status}")
r = snakemake(study_file)
counts = job_counts(r.stdout + r.stderr)
after = json.load(open(os.path.join(run_dir, "summary.json")))
check(r.returncode == 0 and counts.get("simulate") == 1 and after.get("restarted") is True
      and after["status"] == "completed", f"the next invocation continued it with "
      f"ffrsim --restart: {counts}, restarted {after.get('restarted')}, {after['status']}")
# CVODE starts afresh at the last row on disk (order 1, new steps): the continued run
# follows the uninterrupted one to the local error control (rtol 1e-6 over ~1000 steps).
for k in ("max_contact_force_N", "contact_duration_s"):
    x, y = after["figures"][k], before["figures"][k]
    check(abs(x / y - 1) < 1e-3, f"continued run: {k} {x:.9g} against {y:.9g} uninterrupted")
rows = read_table(table_path)  # with the continued run's row

# One value changed: one new run and the collection, no SID.
changed = os.path.join(out, "study_changed.yaml")
text = open(study_file).read().replace("3.0e17", "2.0e17")
text = text.replace("../../configs/", os.path.join(source, "configs") + "/")
open(changed, "w").write(text)
r = snakemake(changed)
counts = job_counts(r.stdout + r.stderr)
check(r.returncode == 0 and counts.get("simulate") == 2 and "sid" not in counts,
      f"3e17 -> 2e17 (both densities): 2 new runs, no SID: {counts}")
new_rows = read_table(table_path)
kept = [n for n, o in zip(new_rows, rows) if o["penalty_factor"] != "3e+17"]
check(kept == [o for o in rows if o["penalty_factor"] != "3e+17"],
      "the other rows are unchanged, bit for bit")
check([n["penalty_factor"] for n in new_rows].count("2e+17") == 2, "the new value's rows")

# Bad study files.
bad = {
    "unknown_key": ("study: x\nscene: s.yaml\nparametrs: []\nparameters:\n"
                    "  - {name: p, values: [1]}\n", r":3: key 'parametrs': unknown key"),
    "values_not_list": ("study: x\nscene: s.yaml\nparameters:\n  - name: p\n"
                        "    values: 3e17\n", r":5: key 'parameters\[0\]\.values': expected a list"),
    "unknown_field": ("study: x\nscene: s_{modl}.yaml\nparameters:\n  - name: model\n"
                      "    values: [h3]\n", r":2: key 'scene': '\{modl\}' names no parameter"),
}
for name, (text, pattern) in bad.items():
    path = os.path.join(out, f"{name}.yaml")
    open(path, "w").write(text)
    r = snakemake(path)
    lines = r.stderr.strip().splitlines()
    check(r.returncode == 2 and len(lines) == 1 and re.search(re.escape(path) + pattern,
                                                              lines[0]) is not None,
          f"bad study {name}: exit {r.returncode}, {lines}")
check.exit()
