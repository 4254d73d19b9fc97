"""End-to-end check of bodies designed from their impact (issue 26, schemas/body_design.md):
igaprep derives the model from the body file's `design` block, ffrsim chooses the penalty
factor with `penalty_factor: auto`, and the impacts agree with Hertz, read from the files.

usage: check_designed_impact.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR

1. The paper's Sect. 5 impact designed (configs/bodies/sphere2d_designed.yaml): force peak
   inside the independent elastodynamic reference 146.7-147.0 N (README), force and duration
   within 0.2 % of the hand-made sphere2d_h3's (run here too), with no more ndof (issue 26's
   acceptance); `igaprep BODY.yaml` alone prints the design; the SID's /design holds Hertz's
   contact radius; the penalty used is 2 E* / (pi 0.002 a).
2. Three other impacts, designed by editing material, radius and speed alone, where Hertz's
   quasi-static theory holds (contact time >= 12 periods of the lowest elastic mode:
   benchmarks/design_study.py): force peak and duration within 1 % of Hertz (issue 26).
3. A designed sphere against a rigid plane (partner: plane), Hertz within 1 %.
4. penalty_factor: auto on hand-made bodies: exit 2, one line naming the key.
5. An explicit NURBS patch designed at a chosen contact point: the oblate spheroid of
   configs/bodies/spheroid2d_designed.yaml, pole on pole, against Hertz with the surface's
   radius of curvature there (A^2 / C = 2 cm), within 1 %.
"""
import math
import os
import subprocess
import sys

import h5py

from result_checks import Checks

igaprep, ffrsim, source, out = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
check = Checks()
bodies = os.path.join(source, "configs", "bodies")
scenes = os.path.join(source, "configs", "scenes")


def build(body_file, sid):
    check.run([igaprep, "-q", body_file, "-o", sid])


def simulate(scene_file, result):
    check.run([ffrsim, "-q", scene_file, "--sid-path", out, "-o", result])
    f = h5py.File(result, "r")
    check.status_completed(f)
    return f


def designed_body(name, R, E, nu, rho, v, partner="same"):
    path = os.path.join(out, name + ".yaml")
    with open(path, "w") as f:
        f.write(f"name: {name}\nmodel: axisymmetric\n"
                f"material: {{youngs_modulus: {E!r}, poisson_ratio: {nu!r}, density: {rho!r}}}\n"
                f"geometry: {{type: half_disk, radius: {R!r}}}\n"
                f"design: {{impact: {{partner: {partner}, approach_speed: {v!r}}}}}\n"
                "visualisation: {subdivisions: 0}\n")
    build(path, os.path.join(out, name + ".sid.h5"))


def pair_scene(name, R, v, T):
    path = os.path.join(out, name + "_scene.yaml")
    with open(path, "w") as f:
        f.write(f"name: {name}\nbodies:\n"
                f"  - {{name: lower, sid: {name}.sid.h5, position: [0, 0, 0], velocity: [0, {v / 2!r}, 0]}}\n"
                f"  - {{name: upper, sid: {name}.sid.h5, position: [0, {2 * R!r}, 0], "
                f"orientation: [0, 1, 0, 0], velocity: [0, {-v / 2!r}, 0]}}\n"
                "contacts:\n  - {name: impact, bodies: [lower, upper], penalty_factor: auto}\n"
                f"integrator: {{end_time: {1.25 * T:.6g}, output_interval: {T / 1000:.6g}, "
                f"rtol: 1.0e-6, atol_position: {1e-12 * R / 0.01:.4g}, atol_velocity: {5e-8 * v:.4g}}}\n")
    return path


def hertz_duration(R, E, nu, rho, v, plane=False):
    Es = E / (1 - nu**2) if plane else E / (2 * (1 - nu**2))
    Rs = R if plane else R / 2
    m = rho * 4 / 3 * math.pi * R**3
    ms = m if plane else m / 2
    d = (5 * ms * v * v / (4 * 4 / 3 * Es * math.sqrt(Rs))) ** 0.4
    return 2.94352 * d / v


def against_hertz(f, what, limit):
    a = f.attrs
    check(abs(a["force_vs_hertz"]) <= limit and abs(a["duration_vs_hertz"]) <= limit,
          f"{what}: force peak {a['max_contact_force_N']:.5g} N {100 * a['force_vs_hertz']:+.3f} %, "
          f"duration {1e6 * a['contact_duration_s']:.4g} us {100 * a['duration_vs_hertz']:+.3f} % "
          f"from Hertz (limit {100 * limit:g} %)")


# 1. The paper's impact, designed, against the hand-made model and the references.
body = os.path.join(bodies, "sphere2d_designed.yaml")
shown = check.run([igaprep, body]).stdout
check("design (derived from the body file's 'design' block)" in shown
      and "contact radius a = sqrt(R* delta)" in shown and "levels: 7" in shown,
      "igaprep BODY.yaml prints the design and its reasons (7 levels here)")
designed_sid = os.path.join(out, "sphere2d_designed.sid.h5")
build(body, designed_sid)
build(os.path.join(bodies, "sphere2d_h3.yaml"), os.path.join(out, "sphere2d_h3.sid.h5"))
with h5py.File(designed_sid, "r") as s, h5py.File(os.path.join(out, "sphere2d_h3.sid.h5"), "r") as h:
    E, nu = s["material/youngs_modulus"][()], s["material/poisson_ratio"][()]
    a = s["design/contact_radius"][()]
    check(s["design/contact_radius"].attrs["units"] == "m", "/design/contact_radius in m")
    # Hertz: delta = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5), a = sqrt(R* delta).
    m = s["sid/mass"][()]
    Es, Rs = E / (2 * (1 - nu**2)), 0.005
    delta = (15 * (m / 2) * 0.2**2 / (16 * Es * math.sqrt(Rs))) ** 0.4
    check(abs(a / math.sqrt(Rs * delta) - 1) < 1e-9, f"/design/contact_radius {a:.6g} m = sqrt(R* delta)")
    check(s["design/finest_element"][()] <= a / 12, "finest element <= a / 12 (the default)")
    ndof, ndof_h3 = int(s.attrs["ndof"]), int(h.attrs["ndof"])
    check(ndof <= ndof_h3, f"ndof {ndof} <= sphere2d_h3's {ndof_h3}")
info = check.run([igaprep, "--info", designed_sid]).stdout
check("design               contact radius 0.000167779 m, N = 12" in info,
      "igaprep --info shows the design")
f = simulate(os.path.join(scenes, "impact2d_designed.yaml"), os.path.join(out, "designed.h5"))
h3 = simulate(os.path.join(scenes, "impact2d_h3.yaml"), os.path.join(out, "h3.h5"))
F, T = f.attrs["max_contact_force_N"], f.attrs["contact_duration_s"]
F3, T3 = h3.attrs["max_contact_force_N"], h3.attrs["contact_duration_s"]
check(146.7 <= F <= 147.0, f"force peak {F:.3f} N inside the elastodynamic reference 146.7-147.0 N")
check(abs(F / F3 - 1) <= 0.002 and abs(T / T3 - 1) <= 0.002,
      f"against sphere2d_h3: force {100 * (F / F3 - 1):+.3f} %, duration {100 * (T / T3 - 1):+.3f} % "
      "(limit 0.2 %)")
cp = f["contacts/impact"].attrs["penalty_factor"]
expected = 2 / ((2 * (1 - nu**2) / E) * math.pi * 0.002 * a)
check(abs(cp / expected - 1) < 1e-12, f"penalty_factor: auto used {cp:.6g} N/m^3 = 2 E* / (pi 0.002 a)")
f.close()
h3.close()

# 2. Other spheres, designed by editing material, radius and speed alone.
for name, R, E, nu, rho, v in (("steel_slow", 0.01, 2.11e11, 0.3, 7850.0, 0.01),
                               ("glass", 0.02, 6.3e10, 0.22, 2500.0, 0.05),
                               ("polymer", 0.02, 2.0e10, 0.35, 1800.0, 0.05)):
    designed_body(name, R, E, nu, rho, v)
    with simulate(pair_scene(name, R, v, hertz_duration(R, E, nu, rho, v)),
                  os.path.join(out, name + ".h5")) as r:
        against_hertz(r, f"{name} (r = {R} m, E = {E:g} Pa, {v} m/s)", 0.01)

# 3. Against a rigid plane.
R, E, nu, rho, v = 0.005, 7.0e10, 0.33, 2700.0, 0.05
designed_body("wall_ball", R, E, nu, rho, v, partner="plane")
T = hertz_duration(R, E, nu, rho, v, plane=True)
scene = os.path.join(out, "wall_scene.yaml")
with open(scene, "w") as s:
    s.write("name: wall\nbodies:\n"
            f"  - {{name: ball, sid: wall_ball.sid.h5, position: [0, {R!r}, 0], orientation: [0, 1, 0, 0], "
            f"velocity: [0, {-v!r}, 0]}}\n"
            "obstacles:\n  - {name: wall, plane: {point: [0, 0, 0], normal: [0, 1, 0]}}\n"
            "contacts:\n  - {name: impact, bodies: [ball, wall], penalty_factor: auto}\n"
            f"integrator: {{end_time: {1.25 * T:.6g}, output_interval: {T / 1000:.6g}, rtol: 1.0e-6, "
            f"atol_position: {5e-13:.4g}, atol_velocity: {5e-8 * v:.4g}}}\n")
with simulate(scene, os.path.join(out, "wall.h5")) as r:
    against_hertz(r, "aluminium sphere r = 5 mm on a rigid wall at 0.05 m/s", 0.01)

# 4. auto needs a designed body.
bad = os.path.join(out, "auto_hand_made.yaml")
with open(os.path.join(scenes, "impact2d_h3.yaml")) as s:
    text = s.read().replace("penalty_factor: 1.0e17", "penalty_factor: auto")
with open(bad, "w") as s:
    s.write(text)
r = subprocess.run([ffrsim, bad, "--sid-path", out, "-o", os.path.join(out, "bad.h5")],
                   capture_output=True, text=True)
check(r.returncode == 2 and "penalty_factor" in r.stderr and "designed body" in r.stderr
      and r.stderr.count("\n") == 1, f"auto on hand-made bodies: exit {r.returncode}, {r.stderr.strip()}")
check(not os.path.exists(os.path.join(out, "bad.h5")), "and no result file")

# 5. An explicit NURBS patch (an oblate spheroid) designed at its pole.
sid = os.path.join(out, "spheroid2d_designed.sid.h5")
build(os.path.join(bodies, "spheroid2d_designed.yaml"), sid)
with h5py.File(sid, "r") as s:
    Rs = s["design/surface_radius"][()]
    check(abs(Rs / (0.01**2 / 0.005) - 1) < 1e-9, f"/design/surface_radius {Rs:.9g} m = A^2 / C")
    normal = s["design/contact_normal"][()]
    check(abs(normal[1] - 1) < 1e-12, "/design/contact_normal is +y at the pole")
    m = s["sid/mass"][()]
    check(abs(m / (7850 * 4 / 3 * math.pi * 0.01**2 * 0.005) - 1) < 1e-6,
          f"the spheroid's mass {m:.6g} kg")
    # No reduction.normal_modes in the file: every fixed-interface mode below 25 / T.
    T_design, cutoff = s["design/hertz_duration"][()], s["design/mode_cutoff_hz"][()]
    check(abs(cutoff * T_design / 25 - 1) < 1e-12 and s.attrs["normal_modes"] >= 1,
          f"normal modes: {s.attrs['normal_modes']} below 25 / T = {cutoff:.4g} Hz")
    F_design = s["design/hertz_max_force"][()]
with simulate(os.path.join(scenes, "impact2d_spheroids.yaml"), os.path.join(out, "spheroids.h5")) as r:
    against_hertz(r, "oblate spheroids 10 x 5 mm (explicit NURBS) pole on pole at 0.05 m/s", 0.01)
    # The design's mass is density x quadrature volume, ffrsim's the SID's (from M): the
    # same to ~1e-11.
    check(abs(r.attrs["hertz_max_force_N"] / F_design - 1) < 1e-9,
          "ffrsim's Hertz reference is the design's (/design/hertz_max_force)")
check.exit()
