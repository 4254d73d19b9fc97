"""Acceptance check of rigid contact targets (issue 27), with the coarse 3D steel sphere
(sphere3d_coarse, from e2e.impact3d_coarse's folder):
  1. thrown at 0.1 m/s onto a rigid cylinder of radius 2 cm across its path
     (configs/scenes/ball_on_cylinder.yaml), against Hertz's elliptical contact of a sphere
     on a rigid cylinder, computed here (and ffrsim's own elliptical reference against it);
  2. the Sect. 6 head-on impact (configs/scenes/impact3d_coarse.yaml) with the upper sphere
     frozen (a rigid body with its exact NURBS surface from the SID), against ffrsim's own
     Hertz figures, which take a frozen sphere as rigid (E = infinity): force and duration
     within 2 % (the coarse model's +1.05 % on a plane), no stress lines for the frozen body.

Hertz, elliptical (Johnson, Contact Mechanics, Sect. 4.2; Love's displacements of the
pressure p0 (1 - x^2/a^2 - y^2/b^2)^(1/2) on a half-space, b <= a, e^2 = 1 - b^2/a^2):
the gap of the bodies is A x^2 + B y^2 with A = 1 / (2 R'), B = 1 / (2 R'') (R' = r along
the cylinder's axis, R'' = (1/r + 1/R_c)^-1 across it), and contact closes it where
  delta = b p0 K(e) / E*,
  A = b p0 (K - E) / (e^2 a^2 E*),   B = b p0 ((a^2 / b^2) E - K) / (e^2 a^2 E*),
  P = 2/3 pi a b p0,
K, E the complete elliptic integrals of the first and second kind (modulus e), E* = E /
(1 - nu^2) against a rigid body. B / A fixes b / a; then P = C delta^(3/2) with C from the
formulas, and the impact of a mass m at v on this law peaks at
  P_max = C^(2/5) (5/4 m v^2)^(3/5),  lasting 2.9432 (5 m v^2 / (4 C))^(2/5) / v.
Checked here against the spheres' law: at R_c -> infinity C is 4/3 E* sqrt(r) (to 1e-9).

Bounds: force peak and duration within 2 % of this reference (the coarse 3D sphere is
+1.05 % above Hertz on a plane and +0.82 % against itself: its contact elements are 0.13 x
0.09 mm, configs/bodies/sphere3d_coarse.yaml); the rebound speed within 1 % of the approach
speed (no damping: quasi-static high modes); the pair let go at the end.

  check_rigid_targets.py FFRSIM SOURCE_DIR SID_DIR OUT_DIR
"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from result_checks import Checks, inertial_velocity  # noqa: E402

ffrsim, source, sids, out = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
check = Checks()
CYLINDER_RADIUS = 0.02  # m, configs/scenes/ball_on_cylinder.yaml
V = 0.1                 # m/s, the sphere's speed there

theta, weights = np.polynomial.legendre.leggauss(400)
theta = 0.25 * np.pi * (theta + 1)  # Gauss-Legendre on [0, pi/2]: smooth integrands, e < 1
weights = 0.25 * np.pi * weights


def elliptic_KE(e):
    s = 1 - (e * np.sin(theta)) ** 2
    return float(np.sum(weights / np.sqrt(s))), float(np.sum(weights * np.sqrt(s)))


def hertz_constant(A, B, Estar):
    """C of P = C delta^(3/2) for the gap A x^2 + B y^2 (A <= B), by bisection on b / a."""
    if B / A - 1 < 1e-12:  # circular
        return 4.0 / 3.0 * Estar * np.sqrt(1 / (2 * A))
    lo, hi = 1e-6, 1 - 1e-12  # k = b / a; B / A falls as k rises to 1
    for _ in range(200):
        k = 0.5 * (lo + hi)
        e = np.sqrt(1 - k * k)
        K, E = elliptic_KE(e)
        ratio = (E / k ** 2 - K) / (K - E)
        lo, hi = (k, hi) if ratio > B / A else (lo, k)
    k = 0.5 * (lo + hi)
    e2 = 1 - k * k
    K, E = elliptic_KE(np.sqrt(e2))
    delta = 1.0  # P / delta^(3/2) does not depend on delta: take delta = 1
    a = np.sqrt(delta * (K - E) / (A * K * e2))
    b = k * a
    p0 = delta * Estar / (b * K)
    return 2.0 / 3.0 * np.pi * a * b * p0


with h5py.File(os.path.join(sids, "sphere3d_coarse.sid.h5"), "r") as s:
    mass = float(s["sid/mass"][()])
    Emod = float(s["material/youngs_modulus"][()])
    nu = float(s["material/poisson_ratio"][()])
    r = float(s["geometry/radius"][()])
Estar = Emod / (1 - nu * nu)
sphere_law = 4.0 / 3.0 * Estar * np.sqrt(r)
near_plane = hertz_constant(1 / (2 * r), 1 / (2 * r) * (1 + 1e-6), Estar)
check(abs(near_plane / sphere_law - 1) <= 1e-6,
      f"reference: the elliptical law tends to the spheres' ({near_plane / sphere_law - 1:+.1e})")
C = hertz_constant(1 / (2 * r), 0.5 * (1 / r + 1 / CYLINDER_RADIUS), Estar)
delta_max = (5 * mass * V ** 2 / (4 * C)) ** 0.4
force_ref = C * delta_max ** 1.5
duration_ref = 2.9432 * delta_max / V
print(f"     Hertz, elliptical: C = {C:.6g} N/m^1.5 ({C / sphere_law:.4f} of a plane's), "
      f"peak {force_ref:.3f} N, duration {1e6 * duration_ref:.2f} us")

result = os.path.join(out, "ball_on_cylinder.h5")
check.run([ffrsim, "-q", os.path.join(source, "configs", "scenes", "ball_on_cylinder.yaml"),
           "--sid-path", sids, "-o", result])
with h5py.File(result, "r") as f:
    check.status_completed(f)
    pair = f["contacts/impact"]
    check(pair.attrs["obstacle_shape"] == "cylinder" and "obstacle_axis" in pair,
          "the pair records its cylinder (obstacle_shape, obstacle_axis)")
    # ffrsim's own reference (runtime/report/hertz_reference.cc: Johnson's relative
    # curvatures, std::comp_ellint_*) against the one computed here (bisection, quadrature).
    check(abs(float(pair.attrs["hertz_curvature_A_1_m"]) * 2 * r - 1) <= 1e-12 and
          abs(float(pair.attrs["hertz_curvature_B_1_m"]) / (0.5 * (1 / r + 1 / CYLINDER_RADIUS)) - 1)
          <= 1e-12, "ffrsim's relative curvatures: 1 / (2 r) along the axis, (1 / r + 1 / R_c) / 2 across")
    fh = float(pair.attrs["hertz_max_force_N"])
    check(abs(fh / force_ref - 1) <= 1e-5,
          f"ffrsim's elliptical Hertz peak {fh:.4f} N against {force_ref:.4f} N computed here "
          f"({fh / force_ref - 1:+.1e}; bound 1e-5: the quadrature's and bisection's accuracy)")
    F = pair["normal_force"][:]
    peak = float(F.max())
    d = peak / force_ref - 1
    check(abs(d) <= 2e-2, f"force peak {peak:.3f} N, Hertz {force_ref:.3f} N ({d:+.2%}, bound 2 %)")
    duration = float(f.attrs["contact_end_s"] - f.attrs["contact_begin_s"])
    d = duration / duration_ref - 1
    check(abs(d) <= 2e-2, f"contact {1e6 * duration:.2f} us, Hertz {1e6 * duration_ref:.2f} us "
          f"({d:+.2%}, bound 2 %)")
    vz = inertial_velocity(f, "ball")[-1, 2]
    check(abs(-vz / V - 1) <= 1e-2, f"rebound {-vz:.5f} m/s, {-vz / V:.5f} of the approach "
          "(bound: within 1 %)")
    check(F[-1] == 0.0 and int(f.attrs["contact_events"]) == 1, "one contact, ended at the end")

# 2. A frozen NURBS sphere as the target.
scene = open(os.path.join(source, "configs", "scenes", "impact3d_coarse.yaml")).read()
upper = scene.index("  - name: upper")
frozen = scene[:upper] + scene[upper:].replace("    sid: sphere3d_coarse.sid.h5\n",
                                                 "    sid: sphere3d_coarse.sid.h5\n    frozen: true\n", 1)
assert frozen != scene
path = os.path.join(out, "impact3d_frozen.yaml")
open(path, "w").write(frozen)
result = os.path.join(out, "impact3d_frozen.h5")
check.run([ffrsim, "-q", path, "--sid-path", sids, "-o", result])
with h5py.File(result, "r") as f:
    check.status_completed(f)
    a = f.attrs
    # Hertz with the frozen sphere rigid: E* twice the two flexible spheres', so the force
    # peak (2^(2/5) = 1.32 times) and duration (2^(-2/5)) of the two-flexible impact move.
    fh, th = float(a["hertz_max_force_N"]), float(a["hertz_duration_s"])
    check(abs(fh / 146.013 / 2 ** 0.4 - 1) <= 1e-3,
          f"Hertz with a rigid partner: {fh:.3f} N = 2^(2/5) x 146.013 N (the flexible pair's)")
    d = float(a["max_contact_force_N"]) / fh - 1
    check(abs(d) <= 2e-2, f"frozen target: force peak {float(a['max_contact_force_N']):.3f} N "
          f"({d:+.2%} of Hertz, bound 2 %)")
    d = float(a["contact_duration_s"]) / th - 1
    check(abs(d) <= 2e-2, f"frozen target: contact {1e6 * float(a['contact_duration_s']):.2f} us "
          f"({d:+.2%} of Hertz, bound 2 %)")
    lines = list(f["stress_lines"].keys()) if "stress_lines" in f else []
    check(lines == ["lower"], f"stress lines only for the flexible sphere: {lines}")
check.exit()
