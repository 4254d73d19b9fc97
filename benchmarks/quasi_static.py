#!/usr/bin/python3
"""Sweeps the quasi-static cutoff and the number of normal modes on the Sect. 5 impact.

Issue 11: the high Craig-Bampton modes are quasi-static (runtime/bodies/quasi_static_modes.h)
instead of damped. For each model (sphere2d_h3, sphere2d_g3 by default), each number of
fixed-interface normal modes (body file reduction.normal_modes) and each treatment of the
high modes, it builds the SID with igaprep, runs configs/scenes/impact2d_<model>.yaml with
the body entries' `quasi_static` key set, and prints, from the result file:

  force peak (root attribute max_contact_force_N) against Hertz (common/mechanics/hertz.h, 146.013 N)
  and against the elastodynamic reference 146.7-147.0 N (an independent full FE solution:
  axisymmetric, quadratic elements, converged; implicit time integration; issue 11),
  contact duration (contact_end_s - contact_begin_s) against 82.66 us,
  coefficient of restitution (rebound / approach speed), impulse / (2 m* v), total
  energy drift, steps (solver_steps) and integration wall time (wall_time_s, median of
  --repeat runs).

Treatments: "damped" is the paper's (no quasi-static modes; the SID's damping, zeta = 1
above 4 f_1), "none" switches both off (every mode dynamic and undamped: unusable, run only
with --undamped), "f<F>" makes the modes above F x f_1 quasi-static (f_1: the lowest
elastic frequency; F = 4 is ffrsim's default) with no damping at all.

usage: benchmarks/quasi_static.py [--build build] [--models h3,g3] [--modes 10,20,40]
                                  [--factors 2,4,8,16] [--repeat 1] [--json out.json]
                                  [--text out.txt]
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HERTZ_N = 146.013          # common/mechanics/hertz.h for this impact (printed by ffrsim)
ELASTODYNAMIC_N = (146.7, 147.0)
ELASTODYNAMIC_US = 82.66


def body_file(model, modes, folder):
    text = open(os.path.join(ROOT, "configs", "bodies", f"sphere2d_{model}.yaml")).read()
    text, n = re.subn(r"normal_modes: *[0-9]+", f"normal_modes: {modes}", text)
    assert n == 1, "the body file names reduction.normal_modes once"
    path = os.path.join(folder, f"sphere2d_{model}_m{modes}.yaml")
    open(path, "w").write(text)
    return path


def scene_file(model, sid_name, treatment, folder):
    text = open(os.path.join(ROOT, "configs", "scenes", f"impact2d_{model}.yaml")).read()
    if treatment == "damped":
        extra = "    quasi_static: false\n"
    elif treatment == "none":
        extra = "    quasi_static: false\n    damping: {scale: 0}\n"
    else:
        extra = f"    quasi_static: {{above_first_elastic: {float(treatment[1:])}}}\n" \
                "    damping: {scale: 0}\n"
    text, n = re.subn(r"    sid: sphere2d_\w+\.sid\.h5\n", f"    sid: {sid_name}\n" + extra, text)
    assert n == 2
    path = os.path.join(folder, f"scene_{treatment}.yaml")
    open(path, "w").write(text)
    return path


def measure(result, sid):
    with h5py.File(sid, "r") as s:
        mass = float(s["sid/mass"][()])
        freq = s["sid/frequencies_hz"][:]
    with h5py.File(result, "r") as f:
        a = f.attrs
        t = f["time"][:]
        F = f["contacts/impact/normal_force"][:]
        vl, vu = f["bodies/lower/velocity"][:, 1], f["bodies/upper/velocity"][:, 1]
        E = f["energy/kinetic"][:] + f["energy/elastic"][:] + f["energy/contact"][:]
        qs = int(f["bodies/lower"].attrs["quasi_static_modes"])
        status = a["status"].decode() if isinstance(a["status"], bytes) else a["status"]
        return {
            "status": status,
            "nq": int(len(freq)), "quasi_static_modes": qs,
            "highest_dynamic_hz": float(np.sort(freq)[len(freq) - qs - 1]) if qs < len(freq) else 0.0,
            "force_N": float(a["max_contact_force_N"]),
            "duration_us": (float(a["contact_end_s"]) - float(a["contact_begin_s"])) * 1e6,
            "restitution": float(-(vl[-1] + vu[-1]) / (vl[0] + vu[0])),
            "impulse_ratio": float(np.trapz(F, t) / (mass * (vl[0] + vu[0]))),
            "energy_drift": float((E.max() - E.min()) / E[0]),
            "steps": int(a["solver_steps"]),
            "wall_s": float(a["wall_time_s"]),
        }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--models", default="h3,g3")
    ap.add_argument("--modes", default="10,20,40")
    ap.add_argument("--factors", default="2,4,8,16")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--undamped", action="store_true", help="also run 'none' (takes hours)")
    ap.add_argument("--json", default=None)
    ap.add_argument("--text", default=None)
    a = ap.parse_args()
    igaprep = os.path.join(a.build, "bin", "igaprep")
    ffrsim = os.path.join(a.build, "bin", "ffrsim")
    treatments = ["damped"] + (["none"] if a.undamped else []) + \
        [f"f{x}" for x in a.factors.split(",")]
    lines, rows = [], []

    def say(s):
        print(s, flush=True)
        lines.append(s)

    lo, hi = ELASTODYNAMIC_N
    say(f"Sect. 5 impact, Hertz {HERTZ_N} N; elastodynamic reference {lo}-{hi} N, "
        f"{ELASTODYNAMIC_US} us, restitution 1.0000")
    say(f"{'model':6} {'modes':>5} {'treatment':>9} {'nq':>3} {'qs':>3} {'f_dyn kHz':>9} "
        f"{'F_max N':>8} {'vs Hertz':>8} {'vs ref':>7} {'T us':>6} {'vs ref':>7} "
        f"{'e':>7} {'impulse':>8} {'dE':>8} {'steps':>6} {'wall s':>7}")
    with tempfile.TemporaryDirectory(prefix="quasi_static_") as tmp:
        for model in a.models.split(","):
            for modes in [int(m) for m in a.modes.split(",")]:
                body = body_file(model, modes, tmp)
                sid_name = f"sphere2d_{model}_m{modes}.sid.h5"
                sid = os.path.join(tmp, sid_name)
                subprocess.run([igaprep, "-q", body, "-o", sid], check=True)
                for tr in treatments:
                    scene = scene_file(model, sid_name, tr, tmp)
                    out = os.path.join(tmp, "result.h5")
                    walls, r = [], None
                    for _ in range(a.repeat):
                        p = subprocess.run([ffrsim, "-q", scene, "--sid-path", tmp, "-o", out],
                                           capture_output=True, text=True)
                        if p.returncode != 0:
                            r = {"error": p.stderr.strip()}
                            break
                        r = measure(out, sid)
                        walls.append(r["wall_s"])
                    row = {"model": model, "normal_modes": modes, "treatment": tr, **r}
                    rows.append(row)
                    if "error" in r:
                        say(f"{model:6} {modes:5d} {tr:>9} failed: {r['error']}")
                        continue
                    r["wall_s"] = statistics.median(walls)
                    ref = r["force_N"] / lo - 1 if r["force_N"] < lo else \
                        (r["force_N"] / hi - 1 if r["force_N"] > hi else 0.0)
                    say(f"{model:6} {modes:5d} {tr:>9} {r['nq']:3d} {r['quasi_static_modes']:3d} "
                        f"{r['highest_dynamic_hz'] / 1e3:9.0f} {r['force_N']:8.3f} "
                        f"{r['force_N'] / HERTZ_N - 1:+8.2%} {ref:+7.2%} {r['duration_us']:6.2f} "
                        f"{r['duration_us'] / ELASTODYNAMIC_US - 1:+7.2%} {r['restitution']:7.5f} "
                        f"{r['impulse_ratio'] - 1:+8.3%} {r['energy_drift']:8.1e} "
                        f"{r['steps']:6d} {r['wall_s']:7.2f}")
    say("vs ref: distance to the reference band 146.7-147.0 N (0 inside); T vs 82.66 us; "
        "e: restitution; impulse: vs 2 m* v; dE: total-energy drift / initial energy")
    if a.json:
        json.dump(rows, open(a.json, "w"), indent=1)
    if a.text:
        open(a.text, "w").write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
