#!/usr/bin/python3
"""The hanging 3D Newton's cradle against the same cradle of rigid spheres (issue 27).

Builds configs/bodies/sphere3d_poles.yaml (a 3D sphere with contact regions at two antipodal
points, two chains of hierarchy boxes) with igaprep, runs configs/scenes/cradleN_3d.yaml
(N = 3 or 5 flexible spheres hanging on strings, the first swinging in at 0.1 m/s, no
damping) and its reference cradleN_3d_rigid.yaml (the same strings, joints and gravity with rigid
spheres and Hertz's law between neighbours' centres, runtime/forces/hertz_point_contact),
and prints from the two result files, against the issue's bounds for the hanging cradle:

  * each sphere's final velocity along the row: flexible against rigid, in per cent of the
    incoming speed (bound 3 %);
  * each pair's force peak, flexible against rigid (bound 3 %);
  * the joints' largest violation over the run (bound 1e-10 m);
  * the total energy's largest change over the run against the incoming kinetic energy
    (kinetic + gravity + elastic + contact; nothing dissipates);
  * steps and wall time of both runs, igaprep's wall time, ndof and nq.

usage: benchmarks/cradle_3d.py [--spheres 3|5] [--build build] [--sid FILE] [--out DIR]
                               [--png FILE] [--text FILE] [--json FILE]
--sid reuses a built sphere3d_poles SID instead of running igaprep.
"""
import argparse
import json
import os
import subprocess
import sys
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "e2e"))
from result_checks import inertial_velocity  # noqa: E402

V0 = 0.1  # m/s, the first sphere's speed in both scenes
ENERGY = ("kinetic", "gravity", "elastic", "contact", "force_elements")


def run(cmd):
    start = time.monotonic()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return time.monotonic() - start


def figures(result, forces, spheres, pairs):
    """Final velocities along x, force peaks and histories, joint violation, energy drift."""
    with h5py.File(result, "r") as f:
        t = f["time"][:]
        out = dict(steps=int(f.attrs["solver_steps"]), t=t,
                   v={s: inertial_velocity(f, s)[:, 0] for s in spheres})
        out["F"] = {p: np.abs(f[forces.format(p)][:]) for p in pairs}
        out["violation"] = max(float(np.abs(f[f"joints/{j}/violation"][:]).max())
                               for j in f["joints"])
        energy = sum(f[f"energy/{k}"][:] for k in ENERGY if f"energy/{k}" in f)
        out["energy_drift"] = float(np.abs(energy - energy[0]).max())
        out["kinetic0"] = float(f["energy/kinetic"][0])
        return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--spheres", type=int, choices=(3, 5), default=3)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--sid")
    ap.add_argument("--out", default="/tmp/cradle3_3d")
    ap.add_argument("--png")
    ap.add_argument("--text")
    ap.add_argument("--json")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    bin_ = os.path.join(a.build, "bin")
    sid = a.sid or os.path.join(a.out, "sphere3d_poles.sid.h5")
    t_pre = None
    if not a.sid:
        t_pre = run([f"{bin_}/igaprep", "-q", f"{ROOT}/configs/bodies/sphere3d_poles.yaml",
                     "-o", sid])
    with h5py.File(sid, "r") as s:
        ndof, nq = int(s.attrs["ndof"]), int(s.attrs["nq"])
    n = a.spheres
    spheres = [f"s{i + 1}" for i in range(n)]
    pairs = [f"s{i + 1}-s{i + 2}" for i in range(n - 1)]
    scene = f"cradle{n}_3d"
    flex, rigid = os.path.join(a.out, f"{scene}.h5"), os.path.join(a.out, f"{scene}_rigid.h5")
    sids = [a for i in range(n) for a in ("--set", f"bodies.{i}.sid={os.path.basename(sid)}")]
    t_flex = run([f"{bin_}/ffrsim", "-q", f"{ROOT}/configs/scenes/{scene}.yaml",
                  "--sid-path", os.path.dirname(os.path.abspath(sid)), "-o", flex] + sids)
    t_rigid = run([f"{bin_}/ffrsim", "-q", f"{ROOT}/configs/scenes/{scene}_rigid.yaml",
                   "-o", rigid])
    F = figures(flex, "contacts/{}/normal_force", spheres, pairs)
    R = figures(rigid, "force_elements/{}/tension", spheres, pairs)
    lines = [f"hanging 3D Newton's cradle, {n} steel spheres r = 1 cm on 5 cm strings, "
             f"{V0:g} m/s in; sphere3d_poles: ndof {ndof}, nq {nq}"
             + (f", igaprep {t_pre:.1f} s" if t_pre else "")]
    rows = dict(ndof=ndof, nq=nq, igaprep_s=t_pre, spheres={}, pairs={})
    for s in spheres:
        d = (F["v"][s][-1] - R["v"][s][-1]) / V0
        rows["spheres"][s] = dict(flexible=float(F["v"][s][-1]), rigid=float(R["v"][s][-1]),
                                  difference_of_v0=float(d))
        lines.append(f"  {s} leaves at {F['v'][s][-1]:+.6f} m/s, rigid {R['v'][s][-1]:+.6f} m/s: "
                     f"{d:+.3%} of v0 (bound 3 %)")
    for p in pairs:
        d = F["F"][p].max() / R["F"][p].max() - 1
        rows["pairs"][p] = dict(flexible_N=float(F["F"][p].max()), rigid_N=float(R["F"][p].max()),
                                difference=float(d))
        lines.append(f"  {p} force peak {F['F'][p].max():.3f} N, rigid {R['F'][p].max():.3f} N: "
                     f"{d:+.3%} (bound 3 %)")
    for name, X, wall in (("flexible", F, t_flex), ("rigid", R, t_rigid)):
        rows[name] = dict(steps=X["steps"], wall_s=wall, joint_violation_m=X["violation"],
                          energy_drift_of_kinetic=X["energy_drift"] / X["kinetic0"])
        lines.append(f"  {name}: joints within {X['violation']:.1e} m (bound 1e-10 m), energy "
                     f"kept to {X['energy_drift'] / X['kinetic0']:.1e} of the kinetic energy, "
                     f"{X['steps']} steps, {wall:.1f} s")
    text = "\n".join(lines)
    print(text)
    if a.text:
        with open(a.text, "w") as f:
            f.write(text + "\n")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(rows, f, indent=1)
    if a.png:
        plot(F, R, spheres, pairs, a.png)


def plot(F, R, spheres, pairs, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    for p, c in zip(pairs, ("C0", "C1", "C2", "C3")):
        ax1.plot(1e6 * F["t"], F["F"][p], c, label=f"{p} flexible")
        ax1.plot(1e6 * R["t"], R["F"][p], c + "--", label=f"{p} rigid + Hertz")
    ax1.set_ylabel("contact force, N")
    ax1.legend(fontsize=8)
    for s, c in zip(spheres, ("C0", "C1", "C2", "C3", "C4")):
        ax2.plot(1e6 * F["t"], F["v"][s], c, label=f"{s} flexible")
        ax2.plot(1e6 * R["t"], R["v"][s], c + "--", label=f"{s} rigid")
    ax2.set_xlabel("time, us")
    ax2.set_ylabel("velocity along the row, m/s")
    ax2.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=120)


if __name__ == "__main__":
    main()
