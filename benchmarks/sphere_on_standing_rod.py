#!/usr/bin/python3
"""Repeated impacts: a steel sphere on the top face of a steel rod standing on a rigid floor.

Issue 27: builds configs/bodies/sphere2d_h3.yaml (r = 1 cm) and rod2d_standing.yaml (radius
4 mm, L = 0.25 m, its top face graded to 25 um at the centre, its bottom face a second
contact region) with igaprep, runs configs/scenes/sphere_on_standing_rod.yaml (0.5 m/s; the
floor a rigid plane under a 1.5e13 Pa/m penalty) and prints, from the result file, against
the 1D model of tests/e2e/check_sphere_on_standing_rod.py (a rigid sphere with Hertz's law
on a rod integrated along its characteristics, standing on the same penalty layer): each
contact of the sphere and of the floor (begin, end, force peak), the sphere's velocity
between and after the contacts, the rod's, momentum and energy drift, steps and wall time
(median of --repeat runs). Then the variants that show which figures are the model's and
which the scene's: the floor's penalty halved, the rod's quasi-static cutoff doubled, the
reference with a free rod (no floor: one contact only, tests/e2e/check_sphere_on_rod.py's
finding) and the reference on a floor 100 times stiffer (close to rigid).

usage: benchmarks/sphere_on_standing_rod.py [--build build] [--repeat 3] [--png out.png]
                                            [--text out.txt]
"""
import argparse
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
from check_sphere_on_standing_rod import (FLOOR_GAP, FLOOR_PENALTY, GAP, ROD_LENGTH,  # noqa: E402
                                          ROD_RADIUS, V0, contacts, standing_rod)
from result_checks import inertial_velocity, sphere_on_rod_figures  # noqa: E402
from sphere_on_rod import igaprep_run  # noqa: E402

STEP = 5e-9  # s, the reference's RK4 step (h / 2 agrees to 1e-4 and better: the check)


def measure(result, m, M):
    with h5py.File(result, "r") as f:
        a = f.attrs
        t = f["time"][:]
        F, F_floor = f["contacts/hit/normal_force"][:], f["contacts/stand/normal_force"][:]
        vb, vr = -inertial_velocity(f, "ball")[:, 1], -inertial_velocity(f, "rod")[:, 1]
        energy = f["energy/kinetic"][:] + f["energy/elastic"][:] + f["energy/contact"][:]
        impulse = np.concatenate([[0.0], np.cumsum(0.5 * (F_floor[1:] + F_floor[:-1]) * np.diff(t))])
        p = m * vb + M * vr + impulse
        status = a["status"].decode() if isinstance(a["status"], bytes) else a["status"]
        return dict(status=status, t=t, F=F, F_floor=F_floor, vb=vb, vr=vr, impulse=impulse[-1],
                    momentum=float(np.abs(p - p[0]).max() / (m * V0)),
                    energy=float(np.abs(energy - energy[0]).max() / energy[0]),
                    steps=int(a["solver_steps"]), wall=float(a["wall_time_s"]))


def describe(label, t, F, F_floor, vb):
    """Lines on one run or reference: its contacts, the floor's, the sphere's velocities."""
    hits, floors = contacts(t, F), contacts(t, F_floor)
    out = [f"{label}: the sphere touched {len(hits)} time(s), the floor {len(floors)}"]
    for k, (b, e, p) in enumerate(hits):
        after = vb[min(np.searchsorted(t, e) + 1, len(t) - 1)]
        out.append(f"  sphere {k + 1}: {1e6 * b:7.2f} .. {1e6 * e:7.2f} us, peak {p:7.2f} N, "
                   f"sphere then at {after:+.5f} m/s")
    for b, e, p in floors:
        out.append(f"  floor:    {1e6 * b:7.2f} .. {1e6 * e:7.2f} us, peak {p:7.2f} N")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--png")
    ap.add_argument("--text")
    args = ap.parse_args()
    igaprep = os.path.join(args.build, "bin", "igaprep")
    ffrsim = os.path.join(args.build, "bin", "ffrsim")
    scene = os.path.join(ROOT, "configs", "scenes", "sphere_on_standing_rod.yaml")
    lines = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in ("sphere2d_h3", "rod2d_standing"):
            wall, nq, ndof = igaprep_run(igaprep, os.path.join(ROOT, "configs", "bodies", f"{name}.yaml"),
                                         os.path.join(tmp, f"{name}.sid.h5"))
            lines.append(f"igaprep {name}: ndof {ndof}, nq {nq}, {wall:.2f} s")
        b = sphere_on_rod_figures(os.path.join(tmp, "sphere2d_h3.sid.h5"),
                                  os.path.join(tmp, "rod2d_standing.sid.h5"), ROD_RADIUS)
        m, M, rho, c, Z, K = b["m"], b["M"], b["rho"], b["c"], b["Z"], b["K"]
        lines.append(f"sphere m = {m:.5f} kg, rod M = {M:.5f} kg, c = {c:.1f} m/s, Z = {Z:.1f} kg/s, "
                     f"2 L / c = {2e6 * ROD_LENGTH / c:.2f} us, floor layer rho c / c_p = "
                     f"{1e6 * rho * c / FLOOR_PENALTY:.2f} us, v0 = {V0} m/s")
        out = os.path.join(tmp, "run.h5")
        walls = []
        for _ in range(args.repeat):
            subprocess.run([ffrsim, "-q", scene, "--sid-path", tmp, "-o", out], check=True)
            res = measure(out, m, M)
            walls.append(res["wall"])
        T = float(res["t"][-1])

        def reference(c_p, travel=ROD_LENGTH / c):
            return standing_rod(m, K, Z, rho * c, travel, c_p, V0, GAP, FLOOR_GAP, T, STEP)

        ref = reference(FLOOR_PENALTY)
        lines.append("")
        lines += describe("ffrsim", res["t"], res["F"], res["F_floor"], res["vb"])
        lines += describe("1D model, same floor layer", *ref)
        v_rod_ref = (m * (V0 - ref[3][-1]) - np.trapz(ref[2], ref[0])) / M
        lines.append(f"afterwards: sphere {res['vb'][-1]:+.5f} m/s (1D {ref[3][-1]:+.5f}), rod "
                     f"{res['vr'][-1]:+.5f} m/s (1D {v_rod_ref:+.5f}); floor impulse "
                     f"{1e3 * res['impulse']:.4f} mN s (1D {1e3 * np.trapz(ref[2], ref[0]):.4f})")
        lines.append(f"momentum (with the floor's impulse) drift {res['momentum']:.1e} of m v0, "
                     f"energy drift {res['energy']:.1e}; status {res['status']}, steps {res['steps']}, "
                     f"wall {statistics.median(walls):.2f} s (median of {args.repeat})")
        lines.append("")
        lines += describe("1D model, a floor 100 times stiffer (27 ns layer)", *reference(100 * FLOOR_PENALTY))
        lines += describe("1D model, no floor (free rod)", *reference(0.0))
        text = open(scene).read()
        for label, pattern, repl in (
                ("floor penalty halved", r"penalty_factor: 1.5e13", "penalty_factor: 0.75e13"),
                ("rod's quasi-static cutoff 600 kHz", r"above_hz: 3.0e5", "above_hz: 6.0e5")):
            variant, n = re.subn(pattern, repl, text)
            assert n == 1
            path = os.path.join(tmp, "variant.yaml")
            open(path, "w").write(variant)
            subprocess.run([ffrsim, "-q", path, "--sid-path", tmp, "-o", out], check=True)
            q = measure(out, m, M)
            lines.append("")
            lines += describe(f"ffrsim, {label} (steps {q['steps']}, wall {q['wall']:.2f} s)",
                              q["t"], q["F"], q["F_floor"], q["vb"])
            if "penalty" in label:
                lines += describe("1D model, that floor layer", *reference(0.5 * FLOOR_PENALTY))
    print("\n".join(lines))
    if args.text:
        open(args.text, "w").write("\n".join(lines) + "\n")
    if args.png:
        plot(res, ref, args.png)


def plot(res, ref, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4))
    ax.plot(1e6 * res["t"], res["F"], lw=1.2, label="sphere on the top face, ffrsim")
    ax.plot(1e6 * ref[0], ref[1], "k--", lw=1, label="1D model")
    ax.plot(1e6 * res["t"], res["F_floor"], lw=1.2, label="floor under the bottom face, ffrsim")
    ax.plot(1e6 * ref[0], ref[2], ":", color="k", lw=1, label="1D model")
    ax.set_xlabel("time (us)")
    ax.set_ylabel("contact force (N)")
    ax.set_title("sphere2d_h3 at 0.5 m/s on rod2d_standing (d = 8 mm, L = 0.25 m) on a floor",
                 fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    bx.plot(1e6 * res["t"], res["vb"], lw=1.2, label="sphere, ffrsim")
    bx.plot(1e6 * ref[0], ref[3], "k--", lw=1, label="sphere, 1D model")
    bx.plot(1e6 * res["t"], res["vr"], lw=1.2, label="rod's centre of mass, ffrsim")
    bx.set_xlabel("time (us)")
    bx.set_ylabel("velocity along the impact, down (m/s)")
    bx.legend(fontsize=8)
    bx.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png, dpi=130)


if __name__ == "__main__":
    main()
