"""Acceptance check of the surface fields at the force peak (issue 27) with Gauss
collocation (configs/bodies/sphere2d_h3_gauss.yaml, contact.collocation: gauss): builds the
flagship sphere so, runs configs/scenes/impact2d_h3_gauss.yaml and checks, read from the
result file, against Hertz at the recorded peak force F (two equal spheres: R* = R/2,
E* = E / (2 (1 - nu^2)), a = (3 F R* / (4 E*))^(1/3), p0 = 3 F / (2 pi a^2)):
  * the contact pressure at the collocation points, RMS of (p_i - p0 (1 - r^2/a^2)^(1/2)) / p0
    over every point with r < 0.9 a: within 3 % (the issue's bound; measured 1.2 %);
  * the von Mises stress on the symmetry axis under the contact point against Hertz's
    (/stress_lines/<sphere>/axis, hertz_von_mises): within 10 % at every depth of the line,
    the surface included (the issue's bound; measured within 1.7 %). The paper's Botella
    points give +231 % at the surface and +119 % at 1 um (README "Surface fields");
  * the force peak within 1 % of Hertz (measured +0.63 %, inside the elastodynamic
    reference 146.7-147.0 N of benchmarks/quasi_static.py) and the duration within 2 %.

  check_surface_fields.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR
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
sid = os.path.join(out, "sphere2d_h3_gauss.sid.h5")
check.run([igaprep, "-q", os.path.join(source, "configs", "bodies", "sphere2d_h3_gauss.yaml"),
           "-o", sid])
result = os.path.join(out, "impact2d_h3_gauss.h5")
check.run([ffrsim, "-q", os.path.join(source, "configs", "scenes", "impact2d_h3_gauss.yaml"),
           "--sid-path", out, "-o", result])
with h5py.File(sid, "r") as s:
    E = float(s["material/youngs_modulus"][()])
    nu = float(s["material/poisson_ratio"][()])
    R = float(s["geometry/radius"][()])
    note = s["contact_surfaces/contact"].attrs["collocation_note"]
check(str(note).startswith("Gauss-Legendre"), f"SID collocation: {note}")
with h5py.File(result, "r") as f:
    check.status_completed(f)
    a = f.attrs
    d = float(a["force_vs_hertz"])
    check(abs(d) <= 1e-2, f"force peak {float(a['max_contact_force_N']):.3f} N ({d:+.2%} of "
          "Hertz, bound 1 %)")
    d = float(a["duration_vs_hertz"])
    check(abs(d) <= 2e-2, f"contact duration {d:+.2%} of Hertz (bound 2 %)")
    field = f["contacts/impact/peak_pressure"]
    F = float(field.attrs["normal_force_N"])
    Es, Rs = E / (2 * (1 - nu * nu)), R / 2
    radius = (3 * F * Rs / (4 * Es)) ** (1 / 3)
    p0 = 3 * F / (2 * np.pi * radius ** 2)
    r = np.abs(field["position"][:, 0])
    p = field["pressure"][:]
    inside = r < 0.9 * radius
    hertz = p0 * np.sqrt(1 - (r[inside] / radius) ** 2)
    rms = float(np.sqrt(np.mean(((p[inside] - hertz) / p0) ** 2)))
    check(rms <= 3e-2, f"pressure: RMS {rms:.2%} of p0 over the {int(inside.sum())} points with "
          f"r < 0.9 a (a = {1e6 * radius:.1f} um, bound 3 %)")
    for body in ("lower", "upper"):
        line = f[f"stress_lines/{body}/axis"]
        depth, vm, hz = line["distance"][:], line["von_mises"][:], line["hertz_von_mises"][:]
        rel = vm / hz - 1
        worst = int(np.argmax(np.abs(rel)))
        check(np.abs(rel).max() <= 0.10,
              f"{body}/axis: von Mises within {abs(rel[worst]):.2%} of Hertz at every depth "
              f"(worst at {1e6 * depth[worst]:.0f} um; surface {rel[0]:+.2%}, 1 um "
              f"{rel[np.argmin(np.abs(depth - 1e-6))]:+.2%}; bound 10 %)")
    print(f"     steps {a['solver_steps']}, wall {float(a['wall_time_s']):.2f} s")
check.exit()
