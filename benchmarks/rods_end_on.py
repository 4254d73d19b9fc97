#!/usr/bin/python3
"""Two coaxial steel rods end-on, flat face on flat face, against the 1D wave solution.

Issue 27: builds configs/bodies/rod2d_100mm.yaml and rod2d_50mm.yaml (axisymmetric, radius
2.5 mm) with igaprep, runs configs/scenes/rods_end_on.yaml (equal lengths, L/d = 20) and
rods_end_on_unequal.yaml (a 50 mm striker on the 100 mm rod) and prints, from the result
files, against one-dimensional wave theory (bar speed c = sqrt(E / rho)):

  force plateau rho c A v / 2 (mean between the half-plateau crossings, 2 us in from each),
  contact time 2 L_s / c (half-plateau crossings of the force averaged over 0.6 us, the
  period of its ringing at the top of the rods' dynamic band), the rods' velocities
  afterwards (striker 0, struck rod v L_s / L_t), the total energy's drift, steps and wall
  time (median of --repeat runs; the issue's target: <= 60 s on the 2-core machine).

Then it sweeps the penalty c_p of both scenes (--penalties), the choice the
scenes' header comments explain: a flat face touches everywhere at once, so c_p is an
interface layer whose stored energy, E / (4 c_p L_s) of the striker's kinetic energy at the
plateau, comes back at the end; a layer stiffer than what the dynamic band resolves
(c_p >~ pi rho c f_cut, 2.6e14 Pa/m at the scenes' 2 MHz cutoff) makes the faces bounce.

usage: benchmarks/rods_end_on.py [--build build] [--repeat 3] [--penalties 3e13,1e14,3e14,1e15]
                                 [--png out.png] [--text out.txt]
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
from result_checks import inertial_velocity, level_crossings  # noqa: E402
RADIUS = 2.5e-3            # m, configs/bodies/rod2d_*.yaml
LENGTHS = {"rod2d_100mm": 0.1, "rod2d_50mm": 0.05}
V = 1.0                    # m/s, the striker's speed in both scenes
RINGING_PERIOD = 0.6e-6    # s (tests/e2e/check_rods_end_on.py)
SCENES = (("rods_end_on", "rod2d_100mm", "rod2d_100mm"),
          ("rods_end_on_unequal", "rod2d_50mm", "rod2d_100mm"))


def measure(result, material, striker, struck):
    rho, E = material
    c = np.sqrt(E / rho)
    area = np.pi * RADIUS ** 2
    plateau = rho * c * area * V / 2
    duration = 2 * LENGTHS[striker] / c
    with h5py.File(result, "r") as f:
        a = f.attrs
        t = f["time"][:]
        F = f["contacts/faces/normal_force"][:]
        rise, fall = level_crossings(t, F, plateau / 2, RINGING_PERIOD)
        window = (t >= rise + 2e-6) & (t <= fall - 2e-6)
        energy = f["energy/kinetic"][:] + f["energy/elastic"][:] + f["energy/contact"][:]
        va = inertial_velocity(f, "striker")[:, 1]  # along the axis, y
        vb = inertial_velocity(f, "struck")[:, 1]
        status = a["status"].decode() if isinstance(a["status"], bytes) else a["status"]
        return dict(status=status, t=t, F=F, plateau=plateau, duration=duration,
                    mean=float(F[window].mean()) if window.any() else float("nan"),
                    lo=float(F[window].min()) if window.any() else float("nan"),
                    hi=float(F[window].max()) if window.any() else float("nan"),
                    time=fall - rise, events=int(a["contact_events"]),
                    v_striker=float(va[-1]), v_struck=float(vb[-1]),
                    v_struck_ref=V * LENGTHS[striker] / LENGTHS[struck],
                    drift=float(np.abs(energy - energy[0]).max() / energy[0]),
                    steps=int(a["solver_steps"]), wall=float(a["wall_time_s"]))


def run(ffrsim, scene_path, sids, result):
    subprocess.run([ffrsim, "-q", scene_path, "--sid-path", sids, "-o", result], check=True)


def report(name, m, lines):
    lines.append(
        f"{name:22s} {m['status']:9s} plateau {m['mean']:7.2f} N ({m['mean'] / m['plateau'] - 1:+.2%}; "
        f"{m['lo']:.0f}..{m['hi']:.0f}) time {1e6 * m['time']:7.3f} us "
        f"({m['time'] / m['duration'] - 1:+.2%}) striker {m['v_striker']:+.4f} struck "
        f"{m['v_struck']:.4f} (ref {m['v_struck_ref']:.3f}) events {m['events']} "
        f"energy {m['drift']:.1e} steps {m['steps']} wall {m['wall']:.2f} s")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--penalties", default="3e13,1e14,3e14,1e15")
    ap.add_argument("--png")
    ap.add_argument("--text")
    args = ap.parse_args()
    igaprep = os.path.join(args.build, "bin", "igaprep")
    ffrsim = os.path.join(args.build, "bin", "ffrsim")
    lines = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in LENGTHS:
            subprocess.run([igaprep, "-q", os.path.join(ROOT, "configs", "bodies", f"{name}.yaml"),
                            "-o", os.path.join(tmp, f"{name}.sid.h5")], check=True)
        with h5py.File(os.path.join(tmp, "rod2d_100mm.sid.h5"), "r") as s:
            material = (float(s["material/density"][()]), float(s["material/youngs_modulus"][()]))
        lines.append("scene                  1D wave solution: plateau rho c A v / 2 = "
                     f"{material[0] * np.sqrt(material[1] / material[0]) * np.pi * RADIUS ** 2 * V / 2:.2f} N")
        results = {}
        for scene, striker, struck in SCENES:
            path = os.path.join(ROOT, "configs", "scenes", f"{scene}.yaml")
            walls = []
            for r in range(args.repeat):
                out = os.path.join(tmp, f"{scene}.h5")
                run(ffrsim, path, tmp, out)
                m = measure(out, material, striker, struck)
                walls.append(m["wall"])
            m["wall"] = statistics.median(walls)
            results[scene] = m
            report(scene, m, lines)
        for scene, striker, struck in SCENES:
            lines.append("")
            lines.append(f"penalty sweep, {scene} (wall of one run):")
            text = open(os.path.join(ROOT, "configs", "scenes", f"{scene}.yaml")).read()
            for p in args.penalties.split(","):
                scene_text, n = re.subn(r"penalty_factor: *[0-9.e+]+",
                                        f"penalty_factor: {float(p):.3e}", text)
                assert n == 1
                path = os.path.join(tmp, f"penalty_{p}.yaml")
                open(path, "w").write(scene_text)
                out = os.path.join(tmp, f"penalty_{p}.h5")
                try:
                    run(ffrsim, path, tmp, out)
                    report(f"  c_p = {float(p):.0e} Pa/m", measure(out, material, striker, struck),
                           lines)
                except subprocess.CalledProcessError as e:
                    lines.append(f"  c_p = {float(p):.0e} Pa/m  ffrsim failed (exit {e.returncode})")
    print("\n".join(lines))
    if args.text:
        open(args.text, "w").write("\n".join(lines) + "\n")
    if args.png:
        plot(results, args.png)


def plot(results, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
    for ax, (scene, striker, _) in zip(axes, SCENES):
        m = results[scene]
        t0 = m["t"][np.argmax(m["F"] > 0)]
        ax.plot(1e6 * (m["t"] - t0), m["F"], lw=0.8, label="ffrsim")
        ax.plot([-2, 0, 0, 1e6 * m["duration"], 1e6 * m["duration"], 1e6 * m["duration"] + 10],
                [0, 0, m["plateau"], m["plateau"], 0, 0], "k--", lw=1, label="1D wave solution")
        ax.set_xlim(-2, 1e6 * m["duration"] + 10)
        ax.set_xlabel("time from first touch (us)")
        ax.set_title(f"{scene}: {striker} striker")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("contact force (N)")
    axes[0].legend()
    fig.tight_layout()
    fig.savefig(png, dpi=130)


if __name__ == "__main__":
    main()
