"""End-to-end check of the Sect. 7 rigid reference (configs/scenes/pendulums_rigid.yaml):
runs ffrsim and checks the result file against conservation laws and Hertz.

  check_pendulums_rigid.py FFRSIM SCENE OUT.h5

Bounds and their reasons:
  * every joint's position equations hold to 1e-10 m in every output row (the issue's
    bound; rows are projected onto the joints, so round-off is what remains);
  * total energy (kinetic + gravity + Hertz) drifts by less than 1e-5 of the largest kinetic
    energy over the 175 ms (BDF at rtol 1e-8 with ~700 steps; measured 5e-6);
  * the impact happens (contact_begin_s >= 0) while the left sphere passes below its
    suspension, 150-175 ms (a quarter period of the small-swing mode is 162.7 ms);
  * the contact force peak is within 10 % of Hertz's for two free spheres at the measured
    approach speed (the joints add the rods' and the pivots' share to the effective mass;
    measured +4.7 %), and the contact lasts within 10 % of Hertz's duration;
  * the right pendulum leaves with most of the momentum (an elastic impact of equal spheres
    exchanges the velocities; the rods and pivots leave a share behind): its sphere moves
    at > 90 % of the left sphere's approach speed.
"""
import os
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from result_checks import Checks  # noqa: E402

ffrsim, scene, out = sys.argv[1:4]
subprocess.run([ffrsim, scene, "-q", "-o", out], check=True)
check = Checks()


with h5py.File(out, "r") as f:
    check.status_completed(f)
    worst = max(float(f[f"joints/{j}/violation"][:].max()) for j in f["joints"])
    check(worst <= 1e-10, f"largest joint violation {worst:.3g} m <= 1e-10 m")
    kinetic = f["energy/kinetic"][:]
    total = kinetic + f["energy/gravity"][:] + f["energy/force_elements"][:]
    drift = float(np.abs(total - total[0]).max())
    check(drift <= 1e-5 * kinetic.max(),
          f"energy drift {drift:.3g} J <= 1e-5 x {kinetic.max():.4g} J")
    begin, end = float(f.attrs["contact_begin_s"]), float(f.attrs["contact_end_s"])
    fmax = float(f.attrs["max_contact_force_N"])
    check(0.150 <= begin <= 0.175, f"impact at {1e3 * begin:.3f} ms")
    t = f["time"][:]
    i = int(np.searchsorted(t, begin)) - 1  # last row before the impact
    v = float(f["sensors/sphere_left_centre/velocity"][i, 0] -
              f["sensors/sphere_right_centre/velocity"][i, 0])
    # Hertz (common/mechanics/hertz.h) for two free steel spheres R = 1 cm at approach speed v.
    E, nu, R, rho = 2.11e11, 0.3, 0.01, 7850.0
    Estar = 1.0 / (2.0 * (1.0 - nu * nu) / E)
    K = 4.0 / 3.0 * Estar * np.sqrt(R / 2.0)
    mstar = rho * 4.0 / 3.0 * np.pi * R**3 / 2.0
    dmax = (5.0 * mstar * v * v / (4.0 * K)) ** 0.4
    fh, th = K * dmax**1.5, 2.94352 * dmax / v
    check(abs(fmax / fh - 1.0) < 0.10,
          f"force peak {fmax:.2f} N against Hertz {fh:.2f} N (v = {v:.4f} m/s): "
          f"{100 * (fmax / fh - 1):+.2f} %")
    check(abs((end - begin) / th - 1.0) < 0.10,
          f"contact duration {1e6 * (end - begin):.2f} us against Hertz {1e6 * th:.2f} us")
    vr = float(f["sensors/sphere_right_centre/velocity"][-1, 0])
    check(vr > 0.9 * v, f"right sphere leaves at {vr:.4f} m/s of {v:.4f} m/s")
check.exit()
