"""Acceptance check of a sphere striking the end face of a free rod on its axis (issue 27):
builds configs/bodies/sphere2d_h3.yaml (steel sphere, r = 1 cm) and rod2d_struck.yaml
(axisymmetric steel rod, radius 5 mm, L = 0.1 m, its face graded to 25 um at the centre),
runs configs/scenes/sphere_on_rod.yaml (the sphere at 0.5 m/s, 1 um from the face) and
checks it, read from the result file, against Sears's model integrated here independently
of ffrsim: a rigid sphere with Hertz's law on a one-dimensional free-free rod,

  m x'' = -F,  F = K max(0, x - u)^(3/2),  K = 4/3 E* sqrt(R),  E* = E / (2 (1 - nu^2)),
  u' = (F(t) + 2 sum_{k>=1} F(t - 2 k L / c)) / Z,  c = sqrt(E / rho),  Z = rho c A,

x the sphere's pole and u the struck end along the impact, the rod's end face at x = 0.
The rod's velocity: d'Alembert, u(s, t) = f(t - s / c) + g(t + s / c) along the rod (s from
the struck end); the force F pushing the end (stress -F / A) starts a compressive wave of
particle velocity F / Z into the rod. The free far end (stress 0) sends it back as a tensile
wave of the same particle velocity; at the struck end, where the stress is held at -F / A,
it is reflected again with its stress reversed, which doubles its particle velocity there:
+2 F(t - 2 L / c) / Z, and so on every round trip. Hertz's law holds both bodies' local
compliance; the 1D rod adds the wave motion. Neglected: the rod's 3D dispersion and radial
inertia (Pochhammer-Chree; the pulse, ~70 us, is long against the rod's radius / c, 1 us),
the finite radius of the rod under Hertz's half-space (its local compliance is that of a
half-space whose surface moves out to infinity; the rod's face beyond ~a becomes the 1D
section), the sphere's own vibrations and the face's local dynamics beyond Hertz's static
field. RK4 with 2 ns steps (2 L / c an integer number of them; the delayed forces at half
steps from the stages): peak, contact time and rebound agree with 1 ns and 4 ns steps to
1e-5.

Bounds (measured on the 2-core machine in brackets):
  * force peak within 3 % of Sears's (+2.02 %): the sphere model alone is +0.65 % above
    Hertz (ball_on_plane), and the 5 mm rod is locally stiffer than Hertz's half-space: its
    face beyond r ~ a does not take the half-space's far-field indentation, estimated as
    (1 - nu^2) F / (pi E a) = 0.15 um of the 10.5 um approach at the peak (+0.9 % of force
    for Hertz's F ~ K^(2/5)); halving the face's 25 um spans moves the peak by 0.02 %, so
    this is not the mesh;
  * contact time (first touch to last, the result's contact_begin_s / contact_end_s) within
    3 % of Sears's (-1.80 %: the same stiffer contact);
  * the sphere's rebound velocity within 1 % of v0 of Sears's (0.03 % of v0): the reflected
    wave returning during the contact decides it (-0.30 v0; on a half-space, an infinitely
    long rod, it would be -0.50 v0 after 87 us of contact). The force peak (38 us) comes just
    before the wave's return (40.6 us): the peak tests Hertz on the rod's impedance, the
    contact time and the rebound test the returning wave;
  * one contact event over 7.8 round trips of the wave, as in Sears's model (the free rod's
    struck end never moves back towards the sphere), and the contact ended;
  * the force history within 5 % of Sears's peak at every row (4.27 %: the stiffer contact
    rises 0.8 us ahead and ends 1.3 us early, where the force falls at 20 N/us);
  * total momentum kept to 1e-10 of m v0 (equal and opposite forces at every collocation
    point; the Buckens frame origins are the centres of mass);
  * total energy (kinetic + elastic + contact) kept to 1e-4 of the initial (7.5e-6: BDF's
    error over 8,900 steps, no damping; the bound leaves a factor 13 for other machines'
    step sequences).

  check_sphere_on_rod.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR
"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from result_checks import Checks, inertial_velocity, sphere_on_rod_figures  # noqa: E402

ROD_RADIUS = 5e-3   # m, configs/bodies/rod2d_struck.yaml
ROD_LENGTH = 0.1    # m
V0 = 0.5            # m/s, the sphere's speed (configs/scenes/sphere_on_rod.yaml)
GAP = 1e-6          # m, pole to face at t = 0


def sears(m, K, Z, round_trip, v0, gap, t_end, h):
    """Sears's model (module docstring), RK4 with steps h shortened so that the round trip
    2 L / c is an integer number N of them: the delayed sums R(t) = sum_k F(t - 2 k L / c)
    are then read from the stored history at t and t + h (grid) and t + h / 2 (stored as the
    mean of the two mid stages' forces). Returns time, force, the sphere's velocity."""
    N = int(round(round_trip / h))
    h = round_trip / N
    n = int(np.ceil(t_end / h))
    F, R = np.zeros(n + 1), np.zeros(n + 1)       # at t_j
    Fh, Rh = np.zeros(n + 1), np.zeros(n + 1)     # at t_j + h / 2
    v_sphere = np.zeros(n + 1)
    x, v, u = -gap, v0, 0.0

    def force(x, u):
        return K * (x - u) ** 1.5 if x > u else 0.0

    for j in range(n + 1):
        if j >= N:
            R[j], Rh[j] = F[j - N] + R[j - N], Fh[j - N] + Rh[j - N]
        F[j], v_sphere[j] = force(x, u), v
        if j == n:
            break
        R_next = F[j + 1 - N] + R[j + 1 - N] if j + 1 >= N else 0.0
        k1 = (v, -F[j] / m, (F[j] + 2 * R[j]) / Z)
        f2 = force(x + h / 2 * k1[0], u + h / 2 * k1[2])
        k2 = (v + h / 2 * k1[1], -f2 / m, (f2 + 2 * Rh[j]) / Z)
        f3 = force(x + h / 2 * k2[0], u + h / 2 * k2[2])
        k3 = (v + h / 2 * k2[1], -f3 / m, (f3 + 2 * Rh[j]) / Z)
        f4 = force(x + h * k3[0], u + h * k3[2])
        k4 = (v + h * k3[1], -f4 / m, (f4 + 2 * R_next) / Z)
        Fh[j] = 0.5 * (f2 + f3)
        x += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        v += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        u += h / 6 * (k1[2] + 2 * k2[2] + 2 * k3[2] + k4[2])
    return np.arange(n + 1) * h, F, v_sphere


def main(igaprep, ffrsim, source, out):
    os.makedirs(out, exist_ok=True)
    check = Checks()
    sids = {}
    for name in ("sphere2d_h3", "rod2d_struck"):
        sids[name] = f"{out}/{name}.sid.h5"
        check.run([igaprep, "-q", f"{source}/configs/bodies/{name}.yaml", "-o", sids[name]])
    b = sphere_on_rod_figures(sids["sphere2d_h3"], sids["rod2d_struck"], ROD_RADIUS)
    m, M, rho, c, Z, K = b["m"], b["M"], b["rho"], b["c"], b["Z"], b["K"]
    check(abs(M / (rho * np.pi * ROD_RADIUS ** 2 * ROD_LENGTH) - 1) <= 1e-9,
          f"rod mass {M:.9g} kg = rho pi a^2 L (the exact geometry)")

    result = f"{out}/sphere_on_rod.h5"
    check.run([ffrsim, "-q", f"{source}/configs/scenes/sphere_on_rod.yaml", "--sid-path", out,
               "-o", result])
    with h5py.File(result, "r") as f:
        check.status_completed(f)
        t = f["time"][:]
        F = f["contacts/hit/normal_force"][:]
        begin, end = float(f.attrs["contact_begin_s"]), float(f.attrs["contact_end_s"])
        events = int(f.attrs["contact_events"])
        # Along the impact, -y (the frame origin: the centre of mass).
        v_ball, v_rod = -inertial_velocity(f, "ball")[:, 1], -inertial_velocity(f, "rod")[:, 1]
        energy = f["energy/kinetic"][:] + f["energy/elastic"][:] + f["energy/contact"][:]
        steps, wall = int(f.attrs["solver_steps"]), float(f.attrs["wall_time_s"])

    t_ref, F_ref, v_ref = sears(m, K, Z, 2 * ROD_LENGTH / c, V0, GAP, t[-1], 2e-9)
    on = np.flatnonzero(F_ref > 0)
    ref_events = 1 + int(np.count_nonzero(np.diff(on) > 1))
    # The reference's first touch and last touch, between its grid points (F ~ (t - t0)^1.5).
    ref_begin, ref_end = t_ref[on[0] - 1], t_ref[on[-1] + 1]
    peak, ref_peak = F.max(), F_ref.max()

    d = peak / ref_peak - 1
    check(abs(d) <= 3e-2, f"force peak {peak:.2f} N at {1e6 * t[F.argmax()]:.2f} us, Sears "
          f"{ref_peak:.2f} N at {1e6 * t_ref[F_ref.argmax()]:.2f} us ({d:+.2%}, bound 3 %)")
    d = (end - begin) / (ref_end - ref_begin) - 1
    check(abs(d) <= 3e-2, f"contact {1e6 * begin:.2f} .. {1e6 * end:.2f} us ({1e6 * (end - begin):.2f} "
          f"us), Sears {1e6 * ref_begin:.2f} .. {1e6 * ref_end:.2f} us ({1e6 * (ref_end - ref_begin):.2f}"
          f" us; {d:+.2%}, bound 3 %)")
    d = (v_ball[-1] - v_ref[-1]) / V0
    check(abs(d) <= 1e-2, f"sphere leaves at {v_ball[-1]:+.5f} m/s, Sears {v_ref[-1]:+.5f} m/s "
          f"({d:+.2%} of v0, bound 1 %; the rod's centre of mass at {v_rod[-1]:+.5f} m/s)")
    check(events == 1 and ref_events == 1 and F[-1] == 0.0,
          f"one contact event over {t[-1] * c / (2 * ROD_LENGTH):.1f} wave round trips "
          f"(ffrsim {events}, Sears {ref_events}), ended at the end")
    dev = np.abs(F - np.interp(t, t_ref, F_ref)).max() / ref_peak
    check(dev <= 5e-2, f"force history within {dev:.2%} of Sears's peak at every row (bound 5 %)")
    p = m * v_ball + M * v_rod
    drift = np.abs(p - p[0]).max() / (m * V0)
    check(drift <= 1e-10, f"momentum kept to {drift:.1e} of m v0 (bound 1e-10)")
    drift = np.abs(energy - energy[0]).max() / energy[0]
    check(drift <= 1e-4, f"energy kept to {drift:.1e} of the initial (bound 1e-4)")
    print(f"     sphere_on_rod: steps {steps}, wall {wall:.2f} s")
    check.exit()


if __name__ == "__main__":
    main(*sys.argv[1:5])
