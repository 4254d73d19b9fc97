"""Acceptance check of the collinear Newton's cradle (issue 27): builds sphere2d_poles (an
axisymmetric sphere with a contact region at each pole, globally graded) and
sphere2d_h3_poles (the same regions on sphere2d_h3's hierarchical mesh, two boxes per level:
one chain at each pole), runs configs/scenes/cradle3_2d.yaml and cradle5_2d.yaml with each
(3 and 5 spheres in a row, the first at 0.1 m/s; the inner ones struck at one region and
striking with the other) and checks them, read from the result files,
against the same chain of rigid spheres with Hertz's law between neighbours, integrated
here independently of ffrsim (RK4, 1e-8 s steps: the force peaks converge to 1e-9):
  m x_i'' = F_{i-1} - F_i,  F_i = K max(0, x_i - x_{i+1})^(3/2),
  K = 4/3 E* sqrt(R*),  E* = E / (2 (1 - nu^2)),  R* = R / 2  (two equal spheres).

  check_cradle.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR

Bounds (the issue's acceptance for the collinear cradle):
  * total linear momentum kept to 1e-10 of m v (the contact forces are equal and opposite
    at every collocation point; the frame origin is the centre of mass, so m v is the body's
    momentum exactly);
  * each sphere's final speed within 1 % of the incoming speed (1e-3 m/s) of the rigid
    chain's;
  * each pair's force peak within 2 % of the rigid chain's (a single impact of these models
    is +0.5 ... +0.7 % above Hertz: paper Sect. 5);
  * every pair carried force and every contact has ended at the end (no chattering left).
"""
import os
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from result_checks import Checks  # noqa: E402

igaprep, ffrsim, source, out = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
BODIES = ("sphere2d_poles", "sphere2d_h3_poles")
for body in BODIES:
    subprocess.run([igaprep, "-q", f"{source}/configs/bodies/{body}.yaml", "-o",
                    f"{out}/{body}.sid.h5"], check=True)
sid = f"{out}/{BODIES[0]}.sid.h5"
check = Checks()


def rigid_chain(m, K, v0, T, steps):
    """Final velocities and each contact's force peak of a chain of rigid spheres."""
    n = len(v0)
    x, v, dt = np.zeros(n), np.array(v0, float), T / steps

    def accelerations(x):
        d = np.maximum(x[:-1] - x[1:], 0.0)
        F = K * d ** 1.5
        a = np.zeros(n)
        a[:-1] -= F / m
        a[1:] += F / m
        return a, F

    peaks = np.zeros(n - 1)
    for _ in range(steps):
        a1, F = accelerations(x)
        peaks = np.maximum(peaks, F)
        a2, _ = accelerations(x + 0.5 * dt * v)
        a3, _ = accelerations(x + 0.5 * dt * (v + 0.5 * dt * a1))
        a4, _ = accelerations(x + dt * (v + 0.5 * dt * a2))
        x = x + dt / 6 * (v + 2 * (v + 0.5 * dt * a1) + 2 * (v + 0.5 * dt * a2) + (v + dt * a3))
        v = v + dt / 6 * (a1 + 2 * a2 + 2 * a3 + a4)
    return v, peaks


with h5py.File(sid, "r") as s:
    mass = float(s["sid/mass"][()])
    E = float(s["material/youngs_modulus"][()])
    nu = float(s["material/poisson_ratio"][()])
    R = float(s["geometry/radius"][()])
K = 4.0 / 3.0 * E / (2 * (1 - nu * nu)) * np.sqrt(R / 2)
v0 = 0.1

for body, n in [(b, n) for b in BODIES for n in (3, 5)]:
    scene = f"cradle{n}_2d" + ("" if body == BODIES[0] else f" ({body})")
    result = f"{out}/cradle{n}_2d_{body}.h5"
    sids = [f"bodies.{i}.sid={body}.sid.h5" for i in range(n)]
    subprocess.run([ffrsim, "-q", f"{source}/configs/scenes/cradle{n}_2d.yaml", "--sid-path", out,
                    "-o", result] + [a for s in sids for a in ("--set", s)], check=True)
    with h5py.File(result, "r") as f:
        check.status_completed(f)
        T = float(f["time"][-1])
        v_ref, F_ref = rigid_chain(mass, K, [v0] + [0.0] * (n - 1), T, int(round(T / 1e-8)))
        v = np.array([f[f"bodies/s{i + 1}/velocity"][:, 1] for i in range(n)])
        p = mass * v.sum(axis=0)
        drift = np.abs(p - p[0]).max() / (mass * v0)
        check(drift <= 1e-10, f"{scene}: momentum kept to {drift:.1e} of m v (bound 1e-10)")
        for i in range(n):
            d = (v[i, -1] - v_ref[i]) / v0
            check(abs(d) <= 1e-2, f"{scene}: s{i + 1} leaves at {v[i, -1]:+.6f} m/s, rigid chain "
                  f"{v_ref[i]:+.6f} m/s ({d:+.3%} of 0.1 m/s, bound 1 %)")
        for i in range(n - 1):
            F = f[f"contacts/s{i + 1}-s{i + 2}/normal_force"][:]
            d = F.max() / F_ref[i] - 1
            check(abs(d) <= 2e-2, f"{scene}: pair s{i + 1}-s{i + 2} peaks at {F.max():.3f} N, "
                  f"rigid chain {F_ref[i]:.3f} N ({d:+.3%}, bound 2 %)")
            check(F.max() > 0 and F[-1] == 0.0,
                  f"{scene}: pair s{i + 1}-s{i + 2} touched and has let go at the end")
        print(f"     {scene}: steps {f.attrs['solver_steps']}, wall {float(f.attrs['wall_time_s']):.2f} s")
check.exit()
