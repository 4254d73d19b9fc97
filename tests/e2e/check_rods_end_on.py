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
    1D theory's instants; the half-level crossings are);
  * afterwards the striker at rest and the struck rod at v L_s / L_t (its mean velocity: the
    Buckens frame origin is the centre of mass), each within 1 % of v;
  * unequal lengths: at 2 L_s / c the 1D faces are both at rest, touching without force until
    the long rod's reflected wave pulls its face away at 2 L_t / c. Nothing separates them
    while the penalty's interface layer gives back the energy it holds at the plateau,
    E / (4 c_p L_s) = 1.05 % of the striker's kinetic energy, and while the striker's
    unloading front, dispersed over its travel (3D: its rise grows as (nu^2 a^2 z / c^3)^(1/3),
    ~0.6 us here), reaches a face with no stress to reverse (equal rods' fronts arrive
    together and pull the faces apart: -0.15 %): the force ends late (measured +1.8 %; still
    +1.3 ... +1.4 % with the penalty 3 and 10 times stiffer, benchmarks/rods_end_on.py, so
    the layer is not all of it; a 100 mm striker on a 200 mm rod, tried once: +1.5 %) and the
    striker leaves backwards (measured -1.8 % of v). Bounds there: contact time 3 %, striker
    2.5 % of v; the struck rod's velocity keeps 1 % (momentum).
  * total momentum kept to 1e-10 of m v, one contact event, the contact ended, and every
    collocation point of both faces active on the plateau (none lost at the edge).

  check_rods_end_on.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR
"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from result_checks import Checks, inertial_velocity, level_crossings  # noqa: E402

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
        print(f"     {scene}: steps {f.attrs['solver_steps']}, "
              f"wall {float(f.attrs['wall_time_s']):.2f} s")
check.exit()
