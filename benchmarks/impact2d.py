#!/usr/bin/python3
"""Reproduces paper Sect. 5 (two axisymmetric steel spheres, 0.1 m/s each, 0.1 ms) from the
studies of benchmarks/studies/, run by their Snakemake workflow.

* Table 1 with Fig. 8-9: the study table1_models.yaml (every 2D model sphere2d_{h,g}{3..6}
  at 1e17 N/m^3). Prints ndof, nq and interface points next to the paper's, the force peak
  and contact duration against Hertz, the preprocessing and integration wall times and the
  hierarchical/global ratio (Fig. 9); --plot draws the force histories against Hertz
  (Fig. 8) from the runs' result files.
* --sweep: also the study fig7_penalty.yaml (every model over 8 penalty factors, Fig. 7;
  64 runs, several minutes); its picture is the study's own PNG.

Each figure is read from the studies' tables (build/studies/<study>/<study>.csv and
_timings.csv), so a second invocation only prints: the workflow reruns nothing.

usage: benchmarks/impact2d.py [--build build] [--out build/studies] [-j 2] [--sweep]
                              [--plot out.png] [--json out.json]
"""
import json
import os
import sys

from paper_study import arguments, force_history, hertz_curve, run_study, save_plot

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# Paper Table 1: model -> (ndof, normal modes, interface control points).
PAPER = {"h3": (3856, 10, 41), "h4": (2884, 10, 40), "h5": (2728, 10, 42),
         "h6": (1708, 10, 41), "g3": (9216, 10, 41), "g4": (7440, 10, 40),
         "g5": (6726, 10, 40), "g6": (5368, 10, 39)}


def print_table1(table, timings):
    print("Paper Sect. 5, Table 1 and Fig. 8-9 (study table1_models; penalty 1e17 N/m^3)")
    print(f"{'model':6} {'ndof':>6} {'paper':>6} {'nq':>4} {'iface':>5} {'paper':>5} "
          f"{'F_max N':>9} {'dF %':>6} {'T us':>7} {'dT %':>6} {'igaprep s':>9} "
          f"{'ffrsim s':>9}")
    for r in table:
        if r["status"] != "completed":
            print(f"{r['model']:6} {r['status']}")
            continue
        t, paper = timings[r["run"]], PAPER.get(r["model"], ("-", "-", "-"))
        print(f"{r['model']:6} {r['sid:ndof']:>6} {paper[0]:>6} {r['sid:nq']:>4} "
              f"{r['sid:n_interface_control_points']:>5} {paper[2]:>5} "
              f"{float(r['max_contact_force_N']):9.3f} {100 * float(r['force_vs_hertz']):+6.2f} "
              f"{1e6 * float(r['contact_duration_s']):7.2f} "
              f"{100 * float(r['duration_vs_hertz']):+6.2f} {float(t['igaprep_wall_s']):9.2f} "
              f"{float(t['wall_time_s']):9.2f}")
    r0 = next((r for r in table if r["status"] == "completed"), None)
    if r0:
        print(f"Hertz: {float(r0['hertz_max_force_N']):.3f} N, "
              f"{1e6 * float(r0['hertz_duration_s']):.2f} us")
    by = {r["model"]: timings[r["run"]] for r in table if r["status"] == "completed"}
    for n in "3456":
        if f"h{n}" in by and f"g{n}" in by:
            print(f"nlvl = {n}: integration wall time hierarchical / global = "
                  f"{float(by['h' + n]['wall_time_s']) / float(by['g' + n]['wall_time_s']):.2f}"
                  f", preprocessing {float(by['h' + n]['igaprep_wall_s']) / float(by['g' + n]['igaprep_wall_s']):.2f}")


def print_sweep(table):
    print("\nPaper Fig. 7 (study fig7_penalty): force peak - Hertz [%] over c_p [N/m^3]")
    penalties = list(dict.fromkeys(r["penalty_factor"] for r in table))
    print(f"{'model':6} " + " ".join(f"{p:>8}" for p in penalties))
    for m in dict.fromkeys(r["model"] for r in table):
        cells = []
        for p in penalties:
            r = next(r for r in table if r["model"] == m and r["penalty_factor"] == p)
            cells.append(f"{100 * float(r['force_vs_hertz']):+8.2f}"
                         if r["status"] == "completed" else f"{'failed':>8}")
        print(f"{m:6} " + " ".join(cells))


def plot_fig8(table, a):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5))
    done = [r for r in table if r["status"] == "completed"]
    th, fh = hertz_curve(float(done[0]["hertz_max_force_N"]), float(done[0]["hertz_duration_s"]))
    ax.plot(th * 1e6, fh, "k-", lw=2.5, label="Hertz")
    for r in done:
        t, f = force_history(a.out, "table1_models", r["run"])
        ax.plot(t * 1e6, f, lw=1, label=f"sphere2d_{r['model']}")
    ax.set_xlabel("time [µs]")
    ax.set_ylabel("normal contact force [N]")
    ax.set_title("Two axisymmetric steel spheres, 0.1 m/s each (paper Fig. 8)")
    ax.legend()
    save_plot(fig, a.plot)


def main():
    ap = arguments(__doc__)
    ap.add_argument("-j", "--jobs", type=int, default=2)
    ap.add_argument("--sweep", action="store_true", help="also the Fig. 7 penalty sweep")
    a = ap.parse_args()
    table, timings = run_study("table1_models", a.build, a.out, a.jobs, "impact2d")
    print_table1(table, timings)
    summary = {"table1_models": {"rows": table, "timings": list(timings.values())}}
    if a.sweep:
        sweep, _ = run_study("fig7_penalty", a.build, a.out, a.jobs, "impact2d")
        print_sweep(sweep)
        print(f"picture: {os.path.join(a.out, 'fig7_penalty', 'fig7_penalty_penalty_factor.png')}")
        summary["fig7_penalty"] = {"rows": sweep}
    if a.plot:
        plot_fig8(table, a)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(summary, f, indent=1)


if __name__ == "__main__":
    sys.exit(main())
