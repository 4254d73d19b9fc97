#!/usr/bin/python3
"""Where an impact's steps go: steps, failed steps and integration time of ffrsim's scenes,
each run as it is and in variants given as scene overrides (issue 32, item 2: "the step
count with its failures before and after").

For each scene (configs/scenes/<name>.yaml; its SIDs built once with igaprep from
configs/bodies/ into --sids; ParaView frames left out, they are written in the time loop)
and each variant, it runs ffrsim --repeat times and prints, from the result file's
attributes: steps (solver_steps), error-test and convergence failures and their share of
the attempts, Newton iterations, the integration wall time (wall_time_s, median over the
repeats), the force peak (max_contact_force_N), the contact duration (contact_duration_s)
and, for two free bodies, the coefficient of restitution (relative velocity along the line
of centres after / before), and the force peak and duration against the first variant.

A variant is LABEL=KEY=VALUE[,KEY=VALUE...] (ffrsim --set overrides), e.g.
--variant "atol_v 2e-7=integrator.atol_velocity=2e-7"; the scene as it is runs first
("scene"). --ffrsim takes another build's ffrsim for every run (a change against the
commit before it: run the script twice, --json each, and compare).

usage: benchmarks/step_control.py [--build build] [--ffrsim PATH] [--sids build/benchmarks/sids]
           [--scenes impact2d_h3,impact3d_h3,...] [--repeat 3] [--variant LABEL=K=V,...]...
           [--text out.txt] [--json out.json] [--plot out.png]
       benchmarks/step_control.py --plot-only RESULTS.json out.png

results/step_control_2026-12-07.* were measured with the build of commit c629401, whose
integrator.error_test option (variants "all" and "differential") was reverted: see
benchmarks/README.md.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "e2e"))
from result_checks import restitution  # noqa: E402
SCENES = ["impact2d_h3", "impact3d_h3", "impact2d_designed", "impact3d_coarse",
          "oblique_friction", "backspin_drop", "cradle3_2d", "sphere_on_standing_rod"]


def sids_of(scene):
    text = open(os.path.join(ROOT, "configs", "scenes", scene + ".yaml")).read()
    return sorted(set(re.findall(r"sid:\s*([A-Za-z0-9_]+)\.sid\.h5", text)))


def build_sid(build, body, folder):
    path = os.path.join(folder, body + ".sid.h5")
    if not os.path.exists(path):
        print(f"igaprep {body} ...", flush=True)
        subprocess.run([os.path.join(build, "bin", "igaprep"),
                        os.path.join(ROOT, "configs", "bodies", body + ".yaml"), "-o", path,
                        "-q"], check=True)
    return path


def scene_without_frames(scene, folder):
    """A copy of the scene without outputs.visualisation (ParaView frames are written in
    the time loop and would count in the integration time)."""
    text = open(os.path.join(ROOT, "configs", "scenes", scene + ".yaml")).read()
    text = re.sub(r"\n  visualisation:.*?(?=\n\S|\n  [a-z_]+:|\Z)", "", text, flags=re.S)
    path = os.path.join(folder, scene + ".yaml")
    open(path, "w").write(text)
    return path


def run(ffrsim, scene, sid_dir, sets, folder):
    out = os.path.join(folder, "result.h5")
    cmd = [ffrsim, scene_without_frames(scene, folder), "-o", out, "--sid-path", sid_dir, "-q"]
    for s in sets:
        cmd += ["--set", s]
    subprocess.run(cmd, check=True)
    with h5py.File(out, "r") as f:
        a = f.attrs
        steps = int(a["solver_steps"])
        etf, ncf = int(a["solver_error_test_failures"]), int(a["solver_convergence_failures"])
        return {
            "steps": steps, "error_test_failures": etf, "convergence_failures": ncf,
            "failed_share": (etf + ncf) / (steps + etf + ncf),
            "newton_iterations": int(a["solver_nonlinear_iterations"]),
            "rhs_evals": int(a["solver_rhs_evals"]),
            "wall_s": float(a["wall_time_s"]),
            "force_N": float(a["max_contact_force_N"]),
            "duration_us": 1e6 * float(a["contact_duration_s"]),
            "restitution": restitution(f),
        }


def measure(ffrsim, scene, sid_dir, sets, repeat):
    with tempfile.TemporaryDirectory() as folder:
        runs = [run(ffrsim, scene, sid_dir, sets, folder) for _ in range(repeat)]
    r = dict(runs[0])
    r["wall_s"] = statistics.median(x["wall_s"] for x in runs)
    r["wall_s_runs"] = [x["wall_s"] for x in runs]
    return r


def plot(rows, variants, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    by = {(r["scene"], r["variant"]): r for r in rows}
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.8))
    x = np.arange(len(scenes))
    width = 0.8 / len(variants)
    colours = ["tab:blue", "tab:orange", "tab:green", "tab:purple"]
    for i, v in enumerate(variants):
        colour = colours[i % len(colours)]
        steps = [by[(s, v)]["steps"] for s in scenes]
        failed = [by[(s, v)]["error_test_failures"] + by[(s, v)]["convergence_failures"]
                  for s in scenes]
        wall = [by[(s, v)]["wall_s"] for s in scenes]
        axes[0].bar(x + i * width, steps, width, color=colour, label=v)
        axes[0].bar(x + i * width, failed, width, fill=False, hatch="//",
                    label="failed attempts" if i == 0 else None)
        axes[1].bar(x + i * width, wall, width, color=colour, label=v)
    for ax, title in zip(axes, ["steps (hatched: failed attempts)",
                                "integration wall time [s] (median)"]):
        ax.set_xticks(x + 0.4 - width / 2)
        ax.set_xticklabels(scenes, rotation=30, ha="right", fontsize=8)
        ax.set_yscale("log")
        ax.set_title(title)
        ax.legend(fontsize=7)
    fig.suptitle("steps and integration time by variant (benchmarks/step_control.py)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--sids", default=os.path.join(ROOT, "build", "benchmarks", "sids"))
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--ffrsim")
    ap.add_argument("--variant", action="append", default=[])
    ap.add_argument("--text")
    ap.add_argument("--json")
    ap.add_argument("--plot")
    ap.add_argument("--plot-only", nargs=2, metavar=("JSON", "PNG"))
    args = ap.parse_args()
    if args.plot_only:
        rows = json.load(open(args.plot_only[0]))
        plot(rows, list(dict.fromkeys(r["variant"] for r in rows)), args.plot_only[1])
        return 0
    os.makedirs(args.sids, exist_ok=True)
    ffrsim = args.ffrsim or os.path.join(args.build, "bin", "ffrsim")
    variants = {"scene": []}
    for v in args.variant:
        label, _, sets = v.partition("=")
        if not sets:
            ap.error(f"--variant {v}: expected LABEL=KEY=VALUE[,KEY=VALUE...]")
        variants[label] = sets.split(",")
    lines = []

    def say(s):
        print(s, flush=True)
        lines.append(s)

    rows = []
    say(f"{'scene':24} {'variant':32} {'steps':>6} {'etf':>5} {'ncf':>5} {'failed':>7} "
        f"{'Newton':>6} {'wall s':>7} {'F_max N':>9} {'T us':>7} {'e':>8} "
        f"{'dF %':>7} {'dT %':>7}")
    for scene in args.scenes.split(","):
        for body in sids_of(scene):
            build_sid(args.build, body, args.sids)
        base = None
        for name, sets in variants.items():
            r = measure(ffrsim, scene, args.sids, sets, args.repeat)
            r.update(scene=scene, variant=name)
            rows.append(r)
            base = base or r
            e = f"{r['restitution']:8.5f}" if r["restitution"] is not None else f"{'-':>8}"
            say(f"{scene:24} {name:32} {r['steps']:6d} {r['error_test_failures']:5d} "
                f"{r['convergence_failures']:5d} {r['failed_share']:7.1%} "
                f"{r['newton_iterations']:6d} {r['wall_s']:7.3f} {r['force_N']:9.3f} "
                f"{r['duration_us']:7.3f} {e} "
                f"{100 * (r['force_N'] / base['force_N'] - 1):+7.3f} "
                f"{100 * (r['duration_us'] / base['duration_us'] - 1):+7.3f}")
    say("etf, ncf: CVODE's error-test and convergence failures; failed: their share of all "
        "step attempts; wall: integration (wall_time_s), median of "
        f"{args.repeat}; e: restitution (two free bodies); dF, dT: force peak and contact "
        "duration against the first variant")
    if args.text:
        open(args.text, "w").write("\n".join(lines) + "\n")
    if args.json:
        json.dump(rows, open(args.json, "w"), indent=1)
    if args.plot:
        plot(rows, list(variants), args.plot)
    return 0


if __name__ == "__main__":
    sys.exit(main())
