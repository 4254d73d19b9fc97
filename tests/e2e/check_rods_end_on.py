"""Acceptance check of two coaxial rods meeting end-on, flat face on flat face (issue 27):
builds configs/bodies/rod2d_100mm.yaml and rod2d_50mm.yaml (axisymmetric steel rods,
radius 2.5 mm, L/d = 20 and 10), runs configs/scenes/rods_end_on.yaml (equal lengths) and
rods_end_on_unequal.yaml (a 50 mm striker on a 100 mm rod) and checks them, read from the
result files, against the one-dimensional wave solution (bar speed c = sqrt(E / rho)):
  * force plateau rho c A v / 2, its mean between the half-plateau crossings (2 us in from
    each, the front's rise) within 3 % (the issue's bound; the 3D rod rings about the plateau
    by +-25 % from the radial inertia of its dispersed front, Pochhammer-Chree, which the
    1D theory has not);
  * contact time 2 L_s / c (L_s the striker's length), between the times the force crosses
    half the plateau on the rise and on the fall, within 1 % (the 3D front and tail are
    dispersed over about a microsecond, so the first and the last touching point are not the
    1D theory's instants; the half-level crossings are), and within 1 % of the same with
    the dispersion of the unloading fronts (front_time, below);
  * afterwards the striker at rest and the struck rod at v L_s / L_t (its mean velocity: the
    Buckens frame origin is the centre of mass), each within 1 % of v;
  * unequal lengths: at 2 L_s / c the 1D faces are both at rest, touching without force until
    the long rod's reflected wave pulls its face away at 2 L_t / c. The striker's unloading
    front passes the faces, dispersed over its 2 L_s of travel (radial inertia): its half
    level, where the force is half the plateau, comes 0.27 us late (Love's theory, Skalak's
    Airy front: front_time). Measured +1.83 % against 1D (bound 3 %), +0.40 % against 1D with
    that dispersion (bound 1 %, the issue's); equal rods: -0.15 % and +0.42 % (their two
    fronts meet, half the plateau is left at a quarter of their height, which comes early).
    The common +0.4 % (0.08-0.16 us) is the penalty's interface layer: nothing separates
    unequal rods while it gives back the energy it holds at the plateau, E / (4 c_p L_s) =
    1.05 % of the striker's kinetic energy, so the striker leaves backwards (-1.8 % of v;
    bound 2.5 %); the struck rod's velocity keeps 1 % (momentum);
  * the struck rod's far end (a sensor on the axisymmetric body): its velocity reaches v / 2
    at front_time(L, 1/2) after the force's half rise within 0.5 % (measured -0.03 %; 1D:
    +1.39 %), and averages v within 1.5 % after 1.5 L / c (-0.82 %: the rod leaves at
    0.9941 v, and the dispersed tail rings);
  * total momentum kept to 1e-10 of m v, one contact event, the contact ended, and every
    collocation point of both faces active on the plateau (none lost at the edge).

  check_rods_end_on.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR
"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from result_checks import Checks, first_rise, inertial_velocity, level_crossings  # noqa: E402

igaprep, ffrsim, source, out = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
check = Checks()
RADIUS = 2.5e-3  # m, both rods (configs/bodies/rod2d_*.yaml)
LENGTHS = {"rod2d_100mm": 0.1, "rod2d_50mm": 0.05}  # m
V = 1.0  # m/s, the striker's speed in both scenes
# s: the force rings about the plateau at the top of the rods' dynamic band (1.75 MHz, the
# highest mode below the scenes' 2 MHz quasi-static cutoff: the step front's Gibbs ringing);
# the contact time is read from the force averaged over one such period.
RINGING_PERIOD = 0.6e-6

bodies = {}
for name, length in LENGTHS.items():
    sid = f"{out}/{name}.sid.h5"
    check.run([igaprep, "-q", f"{source}/configs/bodies/{name}.yaml", "-o", sid])
    with h5py.File(sid, "r") as s:
        rho = float(s["material/density"][()])
        E = float(s["material/youngs_modulus"][()])
        mass = float(s["sid/mass"][()])
    area = np.pi * RADIUS ** 2
    # The SID's mass is the exact geometry's (NURBS): rho A L to round-off.
    check(abs(mass / (rho * area * length) - 1) <= 1e-9,
          f"{name}: mass {mass:.9g} kg = rho pi a^2 L")
    bodies[name] = dict(rho=rho, E=E, mass=mass, length=length, area=area)


def airy(x):
    """Ai(x) from its Maclaurin series (Abramowitz & Stegun 10.4.2-3), for |x| <= 2."""
    f, g, term_f, term_g = 0.0, 0.0, 1.0, x
    for k in range(40):
        f, g = f + term_f, g + term_g
        term_f *= x ** 3 / ((3 * k + 2) * (3 * k + 3))
        term_g *= x ** 3 / ((3 * k + 3) * (3 * k + 4))
    return 0.355028053887817 * f - 0.258819403792807 * g


def airy_level(level):
    """xi with int_xi^inf Ai = level (int_0^inf Ai = 1/3; -0.41 for 1/2, +0.26 for 1/4): where
    Skalak's dispersed step front has risen to `level`; bisection, 20-point Gauss."""
    x, w = np.polynomial.legendre.leggauss(20)

    def tail(xi):  # int_xi^inf Ai = 1/3 - int_0^xi Ai
        return 1 / 3 - xi / 2 * sum(wi * airy(xi / 2 * (x_ + 1)) for x_, wi in zip(x, w))

    lo, hi = -2.0, 2.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if tail(mid) > level else (lo, mid)
    return 0.5 * (lo + hi)


def front_time(z, level, c):
    """When a step front that has travelled z (m) along the rods reaches `level` of its
    height: the 1D theory's z / c plus the dispersion of Love's theory (radial inertia,
    omega = c k (1 - nu^2 a^2 k^2 / 4) for long waves), whose step front is Skalak's Airy
    integral int_xi^inf Ai with xi = (z - c t) / (3 beta t)^(1/3), beta = c nu^2 a^2 / 4
    (Graff, "Wave motion in elastic solids", 1975, Sect. 8.1): t = z / c - xi_level
    (3 beta z / c)^(1/3) / c. For z = 0.1 m its half level comes 0.27 us late."""
    nu = 0.3  # the rods' Poisson ratio (configs/bodies/rod2d_*.yaml)
    beta = c * nu * nu * RADIUS ** 2 / 4
    return z / c - airy_level(level) * (3 * beta * z / c) ** (1 / 3) / c


def far_end_arrival(f, rod, force_rise, c):
    """The struck rod's far end (sensor struck_far_end) against the waves: it starts at v
    when the front arrives (a free end doubles the pulse's v / 2) and keeps v on average.
    The front's half level arrives at front_time(L, 1/2): measured from the force's own half
    rise (which holds the penalty layer's rise) to the far end's half velocity, both
    averaged over the ringing period."""
    t = f["time"][:]
    v_end = f["sensors/struck_far_end/velocity"][:, 1]
    arrival = first_rise(t, v_end, 0.5 * V, RINGING_PERIOD)
    travel = rod["length"] / c
    dispersed = front_time(rod["length"], 0.5, c)
    measured = arrival - force_rise
    d = measured / dispersed - 1
    check(abs(d) <= 5e-3, f"far end: v / 2 reached {1e6 * measured:.3f} us after the force's half "
          f"rise; 1D L / c = {1e6 * travel:.3f} us ({measured / travel - 1:+.2%}), with Love's "
          f"dispersion (Airy front) {1e6 * dispersed:.3f} us ({d:+.2%}, bound 0.5 %)")
    after = t >= force_rise + 1.5 * travel
    mean = v_end[after].mean()
    check(abs(mean / V - 1) <= 1.5e-2, f"far end: mean velocity {mean:.4f} m/s after 1.5 L / c, "
          f"1D v = {V} m/s ({mean / V - 1:+.2%}, bound 1.5 %; range {v_end[after].min():.3f} .. "
          f"{v_end[after].max():.3f} m/s)")


for scene, striker, struck in (("rods_end_on", "rod2d_100mm", "rod2d_100mm"),
                               ("rods_end_on_unequal", "rod2d_50mm", "rod2d_100mm")):
    s, r = bodies[striker], bodies[struck]
    c = np.sqrt(s["E"] / s["rho"])
    plateau = s["rho"] * c * s["area"] * V / 2
    duration = 2 * s["length"] / c
    result = f"{out}/{scene}.h5"
    check.run([ffrsim, "-q", f"{source}/configs/scenes/{scene}.yaml", "--sid-path", out,
               "-o", result])
    with h5py.File(result, "r") as f:
        check.status_completed(f)
        t = f["time"][:]
        pair = f["contacts/faces"]
        F = pair["normal_force"][:]
        active = pair["active_points"][:]
        rise, fall = level_crossings(t, F, 0.5 * plateau, RINGING_PERIOD)
        d = (fall - rise) / duration - 1
        bound = 1e-2 if striker == struck else 3e-2
        check(abs(d) <= bound, f"{scene}: contact time {1e6 * (fall - rise):.3f} us between the "
              f"half-plateau crossings, 2 L_s/c = {1e6 * duration:.3f} us ({d:+.2%}, bound "
              f"{bound:.0%})")
        # The unloading fronts have travelled 2 L_s. Unequal rods: the striker's passes the
        # faces, the force falls with it, half at its half level. Equal rods: both rods'
        # fronts arrive together and each takes p off, half the plateau is left at a quarter
        # of their height.
        level = 0.25 if striker == struck else 0.5
        dispersed = front_time(2 * s["length"], level, c)
        d = (fall - rise) / dispersed - 1
        check(abs(d) <= 1e-2, f"{scene}: contact time against 1D with Love's dispersion of the "
              f"unloading fronts {1e6 * dispersed:.3f} us ({d:+.2%}, bound 1 %)")
        window = (t >= rise + 2e-6) & (t <= fall - 2e-6)
        mean = F[window].mean()
        d = mean / plateau - 1
        check(abs(d) <= 3e-2, f"{scene}: plateau mean {mean:.2f} N, rho c A v / 2 = "
              f"{plateau:.2f} N ({d:+.2%}, bound 3 %; range {F[window].min():.0f} .. "
              f"{F[window].max():.0f} N)")
        points = int(active[window].min())
        check(points == int(active.max()) and points > 0,
              f"{scene}: all {points} collocation points of both faces active on the plateau")
        check(int(f.attrs["contact_events"]) == 1 and F[-1] == 0.0,
              f"{scene}: one contact event ({int(f.attrs['contact_events'])}), ended at the end")
        # Along the axis (y), the Buckens frame origin: the centre of mass.
        va, vb = inertial_velocity(f, "striker")[:, 1], inertial_velocity(f, "struck")[:, 1]
        p = s["mass"] * va + r["mass"] * vb
        drift = np.abs(p - p[0]).max() / (s["mass"] * V)
        check(drift <= 1e-10, f"{scene}: momentum kept to {drift:.1e} of m v (bound 1e-10)")
        expected = V * s["length"] / r["length"]
        bound = 1e-2 if striker == struck else 2.5e-2
        check(abs(va[-1]) <= bound * V, f"{scene}: striker leaves at {va[-1]:+.5f} m/s, "
              f"wave solution 0 ({va[-1] / V:+.2%} of v, bound {bound:.1%})")
        check(abs(vb[-1] - expected) <= 1e-2 * V,
              f"{scene}: struck rod leaves at {vb[-1]:+.5f} m/s, wave solution v L_s / L_t = "
              f"{expected:.3f} m/s ({(vb[-1] - expected) / V:+.2%} of v, bound 1 %)")
        if "sensors" in f:
            far_end_arrival(f, s, rise, c)
        print(f"     {scene}: steps {f.attrs['solver_steps']}, "
              f"wall {float(f.attrs['wall_time_s']):.2f} s")
check.exit()
