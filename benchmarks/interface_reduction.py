#!/usr/bin/python3
"""Interface reduction (issue 32, item 1 and 3): the force peak, contact duration,
restitution, steps and integration wall time of the paper's impacts against the size of the
contact region's interface basis, from the full Craig-Bampton interface down to a few tens
of coordinates.

For each model (a body file and the scene of two such bodies) and each variant (igaprep
--set overrides of the body file's `reduction`: `interface_modes` for characteristic
constraint modes, `pressure_patches` for the static responses to Hertz-shaped pressure
patches, preproc/reduction/), it builds the SID once and runs the scene --repeat times with
both bodies on it (ParaView frames left out), and prints: nq per body, the SID's accuracy
guard (interface_compliance_error: the static compliance the basis misses between the patch
radii), igaprep's wall time, the force peak and duration with their deviation from the full
basis, the restitution (relative velocity after / before along the line of centres), the
steps with their failures and the integration wall time (median).

Models: "sect5" sphere2d_h3 / impact2d_h3, "sect6" sphere3d_h3 / impact3d_h3, "designed"
sphere3d_designed / impact3d_designed (its patch radius: 1.2 times the design's contact
radius, read from its full SID's /design/contact_radius), "global" sphere3d_g5 /
impact3d_g5 (Sect. 6's global reference; not in the default list: its full igaprep needs
about 16 GiB and 7 minutes).

usage: benchmarks/interface_reduction.py [--build build] [--work DIR] [--models sect5,sect6,designed,global]
           [--repeat 3] [--text out.txt] [--json out.json] [--plot out.png]
       benchmarks/interface_reduction.py --plot-only RESULTS.json out.png
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from step_control import restitution, scene_without_frames  # noqa: E402  (result_checks')

PATCHES = "reduction.pressure_patches={{radius: {radius}, radii: {radii}{extra}}}"


def variants(model, radius):
    """(label, igaprep --set overrides) per variant; the full interface first."""
    def patches(radii, extra=""):
        return PATCHES.format(radius=radius, radii=radii, extra=extra)
    full = [("full interface", [])]
    if model == "sect5":
        return full + [(f"{n} char. modes", [f"reduction.interface_modes={n}"])
                       for n in (10, 20, 40)] + \
            [(f"patches, {r} radii", [patches(r)]) for r in (4, 8, 16)]
    if model == "sect6":
        return full + [(f"{n} char. modes", [f"reduction.interface_modes={n}"])
                       for n in (100, 200, 400)] + \
            [("patches, 4 radii", [patches(4)]),
             ("patches, 8 radii", [patches(8)]),
             ("patches, 8 radii, normal", [patches(8, ", tangential: false")]),
             ("patches, 16 radii", [patches(16)]),
             ("patches, 8 radii + 50 char.", [patches(8), "reduction.interface_modes=50"])]
    if model == "global":  # igaprep of the full reference: 441 s, 15.7 GiB
        return full + [("patches, 8 radii, normal", [patches(8, ", tangential: false")])]
    return full + [("patches, 8 radii", [patches(8)]),
                   ("patches, 8 radii, normal", [patches(8, ", tangential: false")])]


MODELS = {"sect5": ("sphere2d_h3", "impact2d_h3", 2.0e-4),
          "sect6": ("sphere3d_h3", "impact3d_h3", 2.0e-4),
          "designed": ("sphere3d_designed", "impact3d_designed", None),
          "global": ("sphere3d_g5", "impact3d_g5", 2.0e-4)}


def build_sid(igaprep, body, sets, path):
    cmd = [igaprep, os.path.join(ROOT, "configs", "bodies", body + ".yaml"), "-o", path, "-q"]
    for s in sets:
        cmd += ["--set", s]
    t0 = time.monotonic()
    subprocess.run(cmd, check=True)
    wall = time.monotonic() - t0
    with h5py.File(path, "r") as f:
        a = f.attrs
        return {"nq": int(a["nq"]), "igaprep_s": wall,
                "guard": float(a.get("interface_compliance_error", -1.0)),
                "patch_modes": int(a.get("patch_modes", 0)),
                "characteristic_modes": int(a.get("characteristic_modes", 0))}


def run_scene(ffrsim, scene, sid, folder):
    out = os.path.join(folder, "result.h5")
    cmd = [ffrsim, scene, "-o", out, "-q", "--set", f"bodies.0.sid={sid}",
           "--set", f"bodies.1.sid={sid}"]
    subprocess.run(cmd, check=True)
    with h5py.File(out, "r") as f:
        a = f.attrs
        return {"steps": int(a["solver_steps"]),
                "failures": int(a["solver_error_test_failures"]) +
                int(a["solver_convergence_failures"]),
                "wall_s": float(a["wall_time_s"]),
                "force_N": float(a["max_contact_force_N"]),
                "duration_us": 1e6 * float(a["contact_duration_s"]),
                "restitution": restitution(f)}


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    models = list(dict.fromkeys(r["model"] for r in rows))
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    markers = {"full": "s", "char": "o", "patc": "^"}

    def kind(variant):
        return "full" if variant.startswith("full") else \
            "patc" if variant.startswith("patches") else "char"

    for m, colour in zip(models, ["tab:blue", "tab:orange", "tab:green"]):
        rs = [r for r in rows if r["model"] == m]
        for r in rs:
            mk = markers[kind(r["variant"])]
            axes[0].plot(r["nq"], max(abs(r["dF_pct"]), 1e-4), mk, color=colour)
            axes[1].plot(r["nq"], max(abs(r["dT_pct"]), 1e-4), mk, color=colour)
            axes[2].plot(r["nq"], r["wall_s"], mk, color=colour)
        axes[2].plot([], [], "-", color=colour, label=m)
    for k, name in markers.items():
        axes[2].plot([], [], name, color="grey",
                     label={"full": "full interface", "char": "characteristic modes",
                            "patc": "pressure patches"}[k])
    for ax in axes[:2]:
        ax.axhline(0.1, color="red", lw=0.8, ls="--")
    axes[0].set_title("|force peak - full| [%] (dashed: 0.1 %; full: drawn at 1e-4)")
    axes[1].set_title("|duration - full| [%]")
    axes[2].set_title("integration wall time [s] (median)")
    for ax in axes:
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("nq per body")
    axes[2].legend(fontsize=7)
    fig.suptitle("interface reduction: accuracy and time against nq "
                 "(benchmarks/interface_reduction.py)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--work", help="folder for the SIDs (default: a temporary one)")
    ap.add_argument("--models", default="sect5,sect6,designed")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--text")
    ap.add_argument("--json")
    ap.add_argument("--plot")
    ap.add_argument("--plot-only", nargs=2, metavar=("JSON", "PNG"))
    args = ap.parse_args()
    if args.plot_only:
        plot(json.load(open(args.plot_only[0])), args.plot_only[1])
        return 0
    igaprep = os.path.join(args.build, "bin", "igaprep")
    ffrsim = os.path.join(args.build, "bin", "ffrsim")
    lines, rows = [], []

    def say(s):
        print(s, flush=True)
        lines.append(s)

    say(f"{'model':9} {'variant':28} {'nq':>5} {'guard':>9} {'igaprep s':>9} {'F_max N':>9} "
        f"{'dF %':>7} {'T us':>7} {'dT %':>7} {'e':>8} {'steps':>6} {'failed':>6} {'wall s':>7}")
    with tempfile.TemporaryDirectory() as tmp:
        work = args.work or tmp
        os.makedirs(work, exist_ok=True)
        for model in args.models.split(","):
            body, scene_name, radius = MODELS[model]
            scene = scene_without_frames(scene_name, work)
            base = None
            for i in range(len(variants(model, 0.0))):
                sid = os.path.join(work, f"{body}_{i}.sid.h5")
                if radius is None and i == 1:  # a designed body: from its full SID
                    with h5py.File(os.path.join(work, f"{body}_0.sid.h5"), "r") as f:
                        radius = 1.2 * float(f["design/contact_radius"][()])
                label, sets = variants(model, radius or 0.0)[i]
                r = build_sid(igaprep, body, sets, sid)
                runs = [run_scene(ffrsim, scene, sid, work) for _ in range(args.repeat)]
                r.update(runs[0])
                r["wall_s"] = statistics.median(x["wall_s"] for x in runs)
                r["wall_s_runs"] = [x["wall_s"] for x in runs]
                base = base or r
                r["dF_pct"] = 100 * (r["force_N"] / base["force_N"] - 1)
                r["dT_pct"] = 100 * (r["duration_us"] / base["duration_us"] - 1)
                r.update(model=model, variant=label, overrides=sets)
                rows.append(r)
                e = f"{r['restitution']:8.5f}" if r["restitution"] is not None else f"{'-':>8}"
                guard = f"{r['guard']:9.2e}" if r["guard"] >= 0 else f"{'-':>9}"
                say(f"{model:9} {label:28} {r['nq']:5d} {guard} {r['igaprep_s']:9.1f} "
                    f"{r['force_N']:9.3f} {r['dF_pct']:+7.3f} {r['duration_us']:7.3f} "
                    f"{r['dT_pct']:+7.3f} {e} {r['steps']:6d} {r['failures']:6d} "
                    f"{r['wall_s']:7.3f}")
                if i > 0:
                    os.remove(sid)  # 3D SIDs are 0.2-1.2 GB each
    say("nq: elastic coordinates per body; guard: the SID's interface_compliance_error; "
        "dF, dT: against the full interface; e: restitution; failed: CVODE's error-test and "
        f"convergence failures; wall: ffrsim's integration wall time, median of {args.repeat}")
    if args.text:
        open(args.text, "w").write("\n".join(lines) + "\n")
    if args.json:
        json.dump(rows, open(args.json, "w"), indent=1)
    if args.plot:
        plot(rows, args.plot)
    return 0


if __name__ == "__main__":
    sys.exit(main())
