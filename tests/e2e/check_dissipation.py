"""The energy that damping takes out, /energy/dissipated (issue 29, item 2): the time
integral of the power of the bodies' modal damping (qdot^T De qdot) and of the force
elements' dampers (c l'^2), accumulated by ffrsim over each step on CVODE's interpolant.
Runs two scenes of tests/e2e/scenes/ and checks, from the result files:
  * damped_oscillator.yaml (a rigid mass on a spring-damper, zeta = 0.05, rtol 1e-10):
    the dissipated energy at every row against the exact damped oscillation,
    1/2 k x0^2 - (1/2 k x^2 + 1/2 m v^2), within 1e-6 of the initial energy 1/2 k x0^2
    (measured 3e-7 at the end: the integrator's error at rtol 1e-10; 4e-4 at 1e-6), and
    kinetic + gravity + spring + dissipated constant to 1e-6 of it;
  * damped_impact2d.yaml (the Sect. 5 impact with 2 % modal damping below 1 MHz, rtol
    1e-7): kinetic + elastic + contact + dissipated constant to 5e-6 of the initial energy
    (measured 0.4 ... 1.5e-6 over step sequences; the same scene undamped drifts by 8.6e-7,
    BDF's own error), while the dissipated energy is 1.2e-4 of it: without it the balance
    misses by 24 times the bound.

  check_dissipation.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR
"""
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from result_checks import Checks  # noqa: E402

igaprep, ffrsim, source, out = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
check = Checks()
scenes = f"{source}/tests/e2e/scenes"


def energies(f, names):
    return sum(f[f"energy/{n}"][:] for n in names), f["energy/dissipated"][:]


# A damped oscillator: k, c, m and the release of tests/e2e/scenes/damped_oscillator.yaml.
k, c, m = 400.0, 2.0, 1.0
x0 = -0.25 - (-0.2 - m * 9.81 / k)      # m, from the equilibrium
w = np.sqrt(k / m)
zeta = c / (2 * m * w)
wd = w * np.sqrt(1 - zeta * zeta)
result = f"{out}/damped_oscillator.h5"
check.run([ffrsim, "-q", f"{scenes}/damped_oscillator.yaml", "-o", result])
with h5py.File(result, "r") as f:
    check.status_completed(f)
    t = f["time"][:]
    mech, dissipated = energies(f, ("kinetic", "gravity", "force_elements"))
decay, s = np.exp(-zeta * w * t), zeta / np.sqrt(1 - zeta * zeta)
x = x0 * decay * (np.cos(wd * t) + s * np.sin(wd * t))
v = -x0 * decay * w * w / wd * np.sin(wd * t)
exact = 0.5 * k * x0 ** 2 - (0.5 * k * x * x + 0.5 * m * v * v)
E0 = 0.5 * k * x0 ** 2
d = np.abs(dissipated - exact).max() / E0
check(d <= 1e-6, f"oscillator: dissipated {dissipated[-1]:.9f} J at {t[-1]} s, exact "
      f"{exact[-1]:.9f} J; largest row difference {d:.1e} of 1/2 k x0^2 (bound 1e-6)")
d = np.abs(mech + dissipated - mech[0]).max() / E0
check(d <= 1e-6, f"oscillator: kinetic + gravity + spring + dissipated kept to {d:.1e} of "
      f"1/2 k x0^2 (bound 1e-6; the mechanical energy fell by {(mech[0] - mech[-1]) / E0:.3f})")

sid = f"{out}/sphere2d_h3.sid.h5"
check.run([igaprep, "-q", f"{source}/configs/bodies/sphere2d_h3.yaml", "-o", sid])
result = f"{out}/damped_impact2d.h5"
check.run([ffrsim, "-q", f"{scenes}/damped_impact2d.yaml", "--sid-path", out, "-o", result])
with h5py.File(result, "r") as f:
    check.status_completed(f)
    mech, dissipated = energies(f, ("kinetic", "elastic", "contact"))
E0 = mech[0]
d = np.abs(mech + dissipated - E0).max() / E0
check(dissipated[-1] >= 1e-4 * E0 and d <= 5e-6,
      f"damped impact: kinetic + elastic + contact + dissipated kept to {d:.1e} of the initial "
      f"energy (bound 5e-6), the dissipated {dissipated[-1] / E0:.2e} of it, the mechanical "
      f"loss {(E0 - mech[-1]) / E0:.2e}")
check.exit()
