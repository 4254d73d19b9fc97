"""Acceptance check of a flexible sphere bouncing on a rigid plane (issue 27): builds
sphere2d_h3, runs configs/scenes/ball_on_plane.yaml (5 contacts with a rigid floor under
gravity, no damping) and checks every bounce, read from the result file, against Hertz's
impact of a sphere on a rigid half-space.

  check_ball_on_plane.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR

Hertz is computed here, independently of ffrsim (common/mechanics/hertz.cc), from the SID's
material, radius and mass: E* = E / (1 - nu^2), R* = R, m* = m, K = 4/3 E* sqrt(R*), and
the ball's weight P = m g pressing it on during the contact (the floor does not fall with
it): m d'' = P - K d^(3/2) from the approach speed v, so that
  1/2 m v^2 + P d_max = 2/5 K d_max^(5/2),  F = K d_max^(3/2),
  T = 2 int_0^d_max dd / sqrt(v^2 + 2 P d / m - 4/5 K d^(5/2) / m)
(the weight, 0.32 N, raises the force peak by 0.33 % and the duration by 0.10 % over the
unloaded closed forms), with v the bounce's approach speed: the ball's speed in the last
row before the contact, carried to the contact's first row under gravity. By symmetry the
frictionless rigid floor is the mid-plane of the Sect. 5 impact (two equal spheres at
+-0.1 m/s): without gravity this is that impact's half, whose elastodynamic FE reference
lies +0.47 ... +0.68 % above Hertz (146.7-147.0 N; tests/e2e/check_energy_conserving_impact.py).
Bounds:
  * 5 contact events (root attribute contact_events), the first one's figures also the
    headline attributes;
  * each bounce's force peak within 0.5 % of Hertz (the issue's bound; measured +0.32 % on
    every bounce, and +0.65 % against the unloaded closed form:
    the paper's penalty 1e17 N/m^3 on sphere2d_h3, whose Sect. 5 impact is +0.46 %; a wrong
    collocation weight or a lost ring factor moves it by tens of %);
  * each bounce's duration (first to last row in contact, rows every 0.1 us, +0.1 us)
    within 0.5 % of Hertz (measured -0.17 ... -0.30 %; the rows resolve 0.12 %);
  * rebound speed ratio >= 0.999 per bounce (the issue's bound; speeds taken at the rows
    next to the contact, carried to its ends under gravity);
  * total energy (kinetic + elastic + gravity + penalty) within 1e-4 of its initial value
    over the run (the issue's bound; measured 6.6e-5, BDF order 2's dissipation at
    rtol 1e-6, no damping);
  * ffrsim's Hertz attributes of the pair (sphere on a rigid plane) equal the independent
    values to 1e-9 (the same formulas and integration rule).
"""
import os
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from result_checks import Checks, contact_runs  # noqa: E402

igaprep, ffrsim, source, out = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
sid = f"{out}/sphere2d_h3.sid.h5"
result = f"{out}/ball_on_plane.h5"
subprocess.run([igaprep, "-q", f"{source}/configs/bodies/sphere2d_h3.yaml", "-o", sid], check=True)
subprocess.run([ffrsim, "-q", f"{source}/configs/scenes/ball_on_plane.yaml", "--sid-path", out,
                "-o", result], check=True)
check = Checks()


def hertz(E, nu, R, m, v, P):
    """Force peak and duration of Hertz's sphere on a rigid half-space under the steady load
    P (the weight): the root of 1/2 m v^2 + P d = 2/5 K d^(5/2) by bisection to round-off,
    T = 2 int_0^dm dd / sqrt(v^2 + 2 P d / m - 4/5 K d^(5/2) / m) with d = dm (1 - s^2),
    60-point Gauss-Legendre (smooth integrand)."""
    K = 4.0 / 3.0 * E / (1 - nu * nu) * np.sqrt(R)
    f = lambda d: 0.4 * K * d ** 2.5 - P * d - 0.5 * m * v * v  # noqa: E731
    lo, hi = 0.0, 1e-9
    while f(hi) <= 0:
        hi *= 2
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) <= 0 else (lo, mid)
    dm = 0.5 * (lo + hi)
    x, w = np.polynomial.legendre.leggauss(60)
    s, w = 0.5 * (x + 1), 0.5 * w
    d = dm * (1 - s * s)
    g = v * v + 2 * P * d / m - 0.8 * K * d ** 2.5 / m
    return K * dm ** 1.5, 2 * np.sum(w * 2 * dm * s / np.sqrt(g))


with h5py.File(sid, "r") as s:
    mass = float(s["sid/mass"][()])
    E = float(s["material/youngs_modulus"][()])
    nu = float(s["material/poisson_ratio"][()])
    R = float(s["geometry/radius"][()])

with h5py.File(result, "r") as f:
    check.status_completed(f)
    scene = f.attrs["scene_yaml"]
    scene = scene.decode() if isinstance(scene, bytes) else scene
    check("gravity: [0, -9.81, 0]" in scene, "the scene's gravity is (0, -9.81, 0) m/s^2")
    g = 9.81
    t = f["time"][:]
    pair = f["contacts/bounce"]
    F = pair["normal_force"][:]
    # The ball is turned about x: its velocity rows are body components, inertial v_y = -v[1].
    vy = -f["bodies/ball/velocity"][:, 1]
    events = contact_runs(pair["active_points"][:])
    check(len(events) == 5, f"{len(events)} bounces in the rows (expected 5)")
    check(int(f.attrs["contact_events"]) == 5,
          f"root attribute contact_events = {int(f.attrs['contact_events'])} (expected 5)")
    for k, (i, j) in enumerate(events):
        # Approach: the last row before the contact (or the initial state), carried to row i;
        # rebound: the first row after it, carried back to row j.
        before = max(i - 1, 0)
        v_in = -(vy[before] - g * (t[i] - t[before]))
        v_out = vy[j + 1] + g * (t[j + 1] - t[j])
        peak = F[i:j + 1].max()
        duration = t[j] - t[i] + (t[i + 1] - t[i])
        hf, ht = hertz(E, nu, R, mass, v_in, mass * g)
        check(abs(peak / hf - 1) <= 5e-3,
              f"bounce {k + 1}: force peak {peak:.3f} N vs Hertz {hf:.3f} N at {v_in:.6f} m/s "
              f"({peak / hf - 1:+.3%}, bound 0.5 %)")
        check(abs(duration / ht - 1) <= 5e-3,
              f"bounce {k + 1}: duration {1e6 * duration:.2f} us vs Hertz {1e6 * ht:.2f} us "
              f"({duration / ht - 1:+.3%}, bound 0.5 %)")
        check(v_out / v_in >= 0.999,
              f"bounce {k + 1}: rebound ratio {v_out / v_in:.6f} >= 0.999")
    total = sum(f[f"energy/{e}"][:] for e in ("kinetic", "elastic", "gravity", "contact"))
    drift = np.abs(total - total[0]).max() / abs(total[0])
    check(drift <= 1e-4, f"total energy within {drift:.2e} of its initial value (bound 1e-4)")
    # For information: the same change against the kinetic energy of a bounce (the energy
    # that moves; the total is mostly m g y with the floor as datum).
    print(f"     total energy change {np.abs(total - total[0]).max() / (0.5 * mass * 0.01):.2e} "
          f"of the kinetic energy at 0.1 m/s")
    hf0, ht0 = hertz(E, nu, R, mass, 0.1, mass * g)
    a = pair.attrs
    check(abs(a["hertz_max_force_N"] / hf0 - 1) <= 1e-9 and abs(a["hertz_duration_s"] / ht0 - 1) <= 1e-9
          and abs(a["hertz_steady_load_N"] / (mass * g) - 1) <= 1e-12,
          f"ffrsim's Hertz {a['hertz_max_force_N']:.6f} N, {1e6 * a['hertz_duration_s']:.4f} us "
          f"under {a['hertz_steady_load_N']:.6f} N vs {hf0:.6f} N, {1e6 * ht0:.4f} us, m g "
          f"{mass * g:.6f} N")
    check(a["body_b"] == "floor" and a["obstacle_shape"] == "plane"
          and np.allclose(pair["obstacle_normal"][:], [0, 1, 0]),
          f"pair group names the obstacle: body_b {a['body_b']}, shape {a['obstacle_shape']}")
    print(f"steps {f.attrs['solver_steps']}, wall {float(f.attrs['wall_time_s']):.2f} s")
check.exit()
