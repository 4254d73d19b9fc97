"""Acceptance check of the energy-conserving Sect. 5 impact (quasi-static high modes,
runtime/bodies/quasi_static_modes.h): builds the body, runs its impact2d scene with the
default treatment and checks the result file against the elastodynamic reference.

  check_energy_conserving_impact.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR MODEL   (MODEL: h3, g3)

Reference values (issue 11): an independent full elastodynamic FE solution of the same
impact (axisymmetric, quadratic elements, converged in mesh, time step and penalty;
implicit time integration) rebounds at 1.0000, peaks at 146.7-147.0 N and lasts 82.66 us.
Bounds (the issue's acceptance):
  * coefficient of restitution (rebound / approach speed of the centres) >= 0.998;
  * impulse (trapezoidal integral of the contact-force rows, every 0.1 us) within 0.2 % of
    2 m* v = m v_rel for two equal spheres; the rows' quadrature error is ~1e-6 here;
  * force peak (root attribute max_contact_force_N) within 0.3 % of 146.7-147.0 N and
    within 1 % of Hertz's (common/mechanics/hertz.h, 146.013 N);
  * contact duration (contact_end_s - contact_begin_s, each the midpoint of the step where
    the contact began or ended: within one step, < 0.1 us) within 0.3 % of 82.66 us;
  * total energy (kinetic + elastic + penalty) constant to 1e-4 of the initial kinetic
    energy (no damping is left; BDF's own dissipation at rtol 1e-6: measured 6e-6 to 1e-5).
"""
import os
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from result_checks import Checks  # noqa: E402

igaprep, ffrsim, source, out, model = sys.argv[1:6]
os.makedirs(out, exist_ok=True)
sid = f"{out}/sphere2d_{model}.sid.h5"
result = f"{out}/impact2d_{model}_conserving.h5"
subprocess.run([igaprep, "-q", f"{source}/configs/bodies/sphere2d_{model}.yaml", "-o", sid],
               check=True)
subprocess.run([ffrsim, "-q", f"{source}/configs/scenes/impact2d_{model}.yaml", "--sid-path", out,
                "-o", result], check=True)
check = Checks()


with h5py.File(result, "r") as f:
    check.status_completed(f)
    with h5py.File(sid, "r") as s:
        mass = float(s["sid/mass"][()])
    t = f["time"][:]
    F = f["contacts/impact/normal_force"][:]
    # Velocities are stored in body components; the upper body is turned (axis -y), so the
    # inertial closing speed is v_lower + v_upper(body) with both components taken along y.
    vl = f["bodies/lower/velocity"][:, 1]
    vu = f["bodies/upper/velocity"][:, 1]
    approach = vl[0] + vu[0]
    rebound = -(vl[-1] + vu[-1])
    e = rebound / approach
    check(e >= 0.998, f"coefficient of restitution {e:.6f} >= 0.998")
    impulse = np.trapz(F, t)
    ideal = mass * approach  # 2 m* v with m* = m / 2
    check(abs(impulse / ideal - 1) <= 2e-3,
          f"impulse {impulse:.6e} N s vs 2 m* v = {ideal:.6e} ({impulse / ideal - 1:+.4%}, bound 0.2 %)")
    peak = float(f.attrs["max_contact_force_N"])
    lo, hi = 146.7 * (1 - 3e-3), 147.0 * (1 + 3e-3)
    check(lo <= peak <= hi, f"force peak {peak:.3f} N within 0.3 % of 146.7-147.0 N [{lo:.2f}, {hi:.2f}]")
    hertz = 146.013
    check(abs(peak / hertz - 1) <= 1e-2, f"force peak vs Hertz {peak / hertz - 1:+.3%} (bound 1 %)")
    duration = float(f.attrs["contact_end_s"]) - float(f.attrs["contact_begin_s"])
    check(abs(duration / 82.66e-6 - 1) <= 3e-3,
          f"contact duration {duration * 1e6:.3f} us vs 82.66 us ({duration / 82.66e-6 - 1:+.3%}, bound 0.3 %)")
    E = f["energy/kinetic"][:] + f["energy/elastic"][:] + f["energy/contact"][:]
    drift = (E.max() - E.min()) / E[0]
    check(drift <= 1e-4, f"energy drift {drift:.2e} of the initial energy (bound 1e-4)")
    print(f"steps {f.attrs['solver_steps']}, wall {float(f.attrs['wall_time_s']):.2f} s")
check.exit()
