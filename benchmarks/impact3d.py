#!/usr/bin/python3
"""Reproduces paper Sect. 6 (two 3D steel spheres, 0.1 m/s each, 0.1 ms) from the study
benchmarks/studies/table2_models.yaml, run by its Snakemake workflow one job at a time (the
global reference's igaprep needs about 17 GB).

* Table 2 with Fig. 13: ndof, nq and interface points next to the paper's, the force peak
  and contact duration against Hertz, the preprocessing (igaprep) and integration (ffrsim)
  wall and CPU times and peak memory, and the hierarchical/global ratios. The references
  g3, g4 and g5 are one space (their body files; tests/preproc/input/body_hierarchy_test.cc), built once.
* The 2D axisymmetric models of Sect. 5 beside them (study table1_models, seconds): the
  3D force peak and duration against the 2D ones of the same nlvl (--no-2d skips it).
* --rhs-cost: the right-hand-side cost against nq on the reference's SID, the largest
  (build/bin/rhs_cost, sub-bodies of its first NQ coordinates), and its exponent.
* --plot: the force histories against Hertz with a detail of the peak (Fig. 14) and the
  computation times (Fig. 13).

Each figure is read from the studies' tables (build/studies/<study>/<study>.csv and
_timings.csv), so a second invocation only prints: the workflow reruns nothing, unless
igaprep's or ffrsim's version (git revision) changed, which is part of every SID and run
hash; then everything is built and run again (~20 min).

usage: benchmarks/impact3d.py [--build build] [--out build/studies] [--no-2d]
                              [--rhs-cost] [--plot out.png] [--json out.json]
"""
import json
import os
import subprocess
import sys

import h5py

from paper_study import (arguments, force_history, hertz_curve, run_study, run_summary,
                         save_plot)

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STUDY = "table2_models"
# Paper Table 2: model -> (ndof, interface control points, preprocessing time [s]).
PAPER = {"h3": (18891, 273, 273), "h4": (14940, 297, 262), "h5": (12711, 321, 246),
         "g3": (139431, 441, 6000), "g4": (117267, 441, 9720), "g5": (92823, 441, 7680)}
PAPER_ANSYS_S = 6 * 3600 + 33 * 60  # Sect. 6: the isoparametric ANSYS model, 10 ns steps
SAME_SPACE = {"g3": "g5", "g4": "g5"}  # built once, as g5
RHS_NQ = [150, 300, 600, 900, 1200]    # and the SID's own nq


def completed(table, timings):
    """model -> (table row, timings row) of the completed runs."""
    return {r["model"]: (r, timings[r["run"]]) for r in table if r["status"] == "completed"}


def print_table2(done, two_d):
    print("Paper Sect. 6, Table 2 and Fig. 13 (study table2_models; penalty 1e17 N/m^3; "
          "2 threads, one job at a time)")
    print(f"{'model':6} {'ndof':>6} {'paper':>6} {'nq':>5} {'iface':>5} {'paper':>5} "
          f"{'F_max N':>9} {'dF %':>6} {'T us':>6} {'dT %':>6} {'vs 2D %':>7} "
          f"{'igaprep s':>9} {'GiB':>5} {'paper s':>7} {'ffrsim s':>8} {'CPU s':>6} "
          f"{'steps':>5}")
    for m in ["h3", "h4", "h5", "g3", "g4", "g5"]:
        src = SAME_SPACE.get(m, m)
        if src not in done:
            print(f"{m:6} not run")
            continue
        r, t = done[src]
        paper = PAPER[m]
        vs2d = "-"
        if m in two_d:
            vs2d = f"{100 * (float(r['max_contact_force_N']) / two_d[m] - 1):+7.2f}"
        print(f"{m:6} {r['sid:ndof']:>6} {paper[0]:>6} {r['sid:nq']:>5} "
              f"{r['sid:n_interface_control_points']:>5} {paper[1]:>5} "
              f"{float(r['max_contact_force_N']):9.3f} {100 * float(r['force_vs_hertz']):+6.2f} "
              f"{1e6 * float(r['contact_duration_s']):6.2f} "
              f"{100 * float(r['duration_vs_hertz']):+6.2f} {vs2d:>7} "
              f"{float(t['igaprep_wall_s']):9.1f} {float(t['igaprep_peak_rss_mib']) / 1024:5.2f} "
              f"{paper[2]:>7} {float(t['wall_time_s']):8.2f} {float(t['process_cpu_s']):6.1f} "
              f"{r['solver_steps']:>5}" + (f"   (= {src}: one space)" if src != m else ""))
    r0 = next(iter(done.values()))[0]
    print(f"Hertz: {float(r0['hertz_max_force_N']):.3f} N, "
          f"{1e6 * float(r0['hertz_duration_s']):.2f} us; ANSYS (paper): {PAPER_ANSYS_S} s")
    if "g5" in done:
        g = done["g5"][1]
        for n in "345":
            if f"h{n}" in done:
                h = done[f"h{n}"][1]
                print(f"nlvl = {n}: hierarchical / global: ffrsim wall "
                      f"{float(h['wall_time_s']) / float(g['wall_time_s']):.2f}, igaprep wall "
                      f"{float(h['igaprep_wall_s']) / float(g['igaprep_wall_s']):.3f}, ndof "
                      f"{int(done[f'h{n}'][0]['sid:ndof']) / int(done['g5'][0]['sid:ndof']):.3f}"
                      f" (paper {PAPER[f'h{n}'][0] / PAPER[f'g{n}'][0]:.3f})")


def two_d_peaks(a):
    """model -> force peak [N] of the 2D study table1_models (Sect. 5)."""
    table, timings = run_study("table1_models", a.build, a.out, 2, "impact3d")
    return {m: float(r["max_contact_force_N"]) for m, (r, _) in completed(table, timings).items()}


def rhs_cost(done, a):
    """build/bin/rhs_cost on the SID the reference's run used; returns its JSON object."""
    if "g5" not in done:
        sys.exit("impact3d: --rhs-cost needs the study's completed run of g5")
    used = run_summary(a.out, STUDY, done["g5"][0]["run"])["sids"]["sphere3d_g5.sid.h5"]
    sid = os.path.join(a.out, "sids", used)
    with h5py.File(sid, "r") as f:
        nq = int(f.attrs["nq"])
    cmd = [os.path.join(a.build, "bin", "rhs_cost"), sid, "21"] + [str(n) for n in RHS_NQ + [nq]]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"impact3d: rhs_cost failed (exit {p.returncode}): {p.stderr[-2000:]}")
    lines = p.stdout.strip().splitlines()
    print("\nRight-hand-side cost against nq (rhs_cost on the reference's SID):")
    print("\n".join(lines[:-1]))
    return json.loads(lines[-1])


def plot(done, a):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, ax2, ax3) = plt.subplots(1, 3, figsize=(15, 4.5),
                                       gridspec_kw={"width_ratios": [2, 1.2, 1.2]})
    r0 = next(iter(done.values()))[0]
    th, fh = hertz_curve(float(r0["hertz_max_force_N"]), float(r0["hertz_duration_s"]))
    for axis in (ax, ax2):
        axis.plot(th * 1e6, fh, "k-", lw=2.5, label="Hertz")
    for m, (r, _) in done.items():
        t, f = force_history(a.out, STUDY, r["run"])
        label = "sphere3d_g3 = g4 = g5" if m == "g5" else f"sphere3d_{m}"
        for axis in (ax, ax2):
            axis.plot(t * 1e6, f, lw=1, label=label)
    ax.set_xlabel("time [µs]")
    ax.set_ylabel("normal contact force [N]")
    ax.set_title("Two 3D steel spheres, 0.1 m/s each (paper Fig. 14)")
    ax.legend()
    peak = float(r0["hertz_max_force_N"])
    ax2.set_xlim(0.4e6 * float(r0["hertz_duration_s"]), 0.6e6 * float(r0["hertz_duration_s"]))
    ax2.set_ylim(0.985 * peak, 1.012 * peak)
    ax2.set_xlabel("time [µs]")
    ax2.set_title("detail at the peak")
    models = list(done)
    x = range(len(models))
    ax3.bar([i - 0.2 for i in x], [float(done[m][1]["wall_time_s"]) for m in models], 0.4,
            label="ffrsim")
    ax3.bar([i + 0.2 for i in x], [float(done[m][1]["igaprep_wall_s"]) for m in models], 0.4,
            label="igaprep")
    ax3.set_xticks(list(x), models)
    ax3.set_yscale("log")
    ax3.set_ylabel("wall time [s] (2 cores)")
    ax3.set_title("computation times (paper Fig. 13)")
    ax3.legend()
    save_plot(fig, a.plot)


def main():
    ap = arguments(__doc__)
    ap.add_argument("--no-2d", action="store_true", help="skip the 2D study beside")
    ap.add_argument("--rhs-cost", action="store_true", help="also the rhs cost against nq")
    a = ap.parse_args()
    # -j 2 with 2 threads per job (the study's resources): one job at a time.
    table, timings = run_study(STUDY, a.build, a.out, 2, "impact3d")
    done = completed(table, timings)
    if not done:
        sys.exit("impact3d: no run of the study completed; see build/studies/table2_models")
    two_d = {} if a.no_2d else two_d_peaks(a)
    print_table2(done, two_d)
    summary = {STUDY: {"rows": table, "timings": list(timings.values())}, "forces_2d": two_d}
    if a.rhs_cost:
        summary["rhs_cost"] = rhs_cost(done, a)
    if a.plot:
        plot(done, a)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(summary, f, indent=1)


if __name__ == "__main__":
    sys.exit(main())
