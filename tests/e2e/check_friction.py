"""Coulomb friction against a rigid obstacle (issue 28; runtime/contact/coulomb_friction.h),
with the coarse 3D steel sphere (sphere3d_coarse, from e2e.impact3d_coarse's folder) thrown
at 60 degrees onto a rigid floor with mu = 0.1 (configs/scenes/oblique_friction.yaml): gross
sliding throughout, where rigid-body impulse theory (benchmarks/oblique_reference.py,
written separately) holds:

  1. the tangential velocity and the spin after the impact within 0.5 % of impulse theory
     (with the run's own normal restitution e; issue 28's bound), the contact point still
     sliding; the tangential force mu times the normal one at the force peak (1e-6: the
     regularisation's share at |v_t| ~ 0.15 m/s >> eps is (eps / v_t)^2 / 2), and so the
     traction field there (peak_pressure/traction) at every point and in its resultant;
  2. the normal force history within 0.5 % of the frictionless run's (issue 28), whose
     datasets carry no friction series; the frictionless run's tangential velocity kept to
     1e-6 relative;
  3. the friction's work (/energy/dissipated) never decreasing, and equal to the kinetic
     energy lost within 2 % (the regularised law's dissipation is evaluated with the body's
     dynamic velocities: the quasi-static coordinates' rates, which carry the contact's
     local deformation, are not in it; measured 0.1 %); the result's friction datasets
     (tangential_force, sticking_points, slipping_points, friction_coefficient), which
     benchmarks/plot_result.py draws (RESULT_friction.png, the traction beside the pressure);
  4. same bits on 1 and 2 threads; a run stopped in the contact and continued with
     --restart ends within 1e-4 of the straight run (the law has no internal state; CVODE
     restarts at order 1);
  5. the same impact between two spheres (oblique_friction_pair.yaml: each sphere meets the
     mid-plane as the ball meets the floor, by symmetry): velocities and spins after it
     within 0.5 % of impulse theory, linear momentum kept, the tangential force and the
     traction field of both roles as above, the normal peak within 0.5 % of the frictionless
     pair's, the friction work as in 3.
  6. a sphere dropped with backspin (backspin_drop.yaml, mu = 0.3): the slip stops during
     the impact and it leaves rolling, backwards, with the velocity and spin of impulse
     theory within 0.5 % and its contact point's slip below 0.1 % of the initial one.
  7. stick anchors (friction_law: anchored): at 20 degrees (local angle of incidence
     Psi_1 = 3.0 < 4 chi, the tangentially compliant regime) the contact point's rebound
     reverses its sign, Psi_2 < -1, where rigid theory and the regularised law give 0: within
     10 % of Maw, Barber and Fawcett's theory (measured +7.0 %; their theory is for
     elastically similar bodies, a steel sphere on a rigid floor is not: Dundurs' beta =
     0.29 couples the normal pressure to tangential displacements); |f_t| <= mu f_n at every
     row, points sticking and slipping, the friction work never decreasing; a restart in
     the contact (the anchors in the restart record) within 5e-3 of the straight run (the
     stick-slip history follows the steps: the rebound angle moved by 0.13 % between anchor
     tolerances of 1e-9 and 1e-8 m, and a restart begins again at order 1; measured 9.4e-4).
     Gross sliding with anchors (60 degrees: within 0.23 % of impulse theory) takes 24,463
     steps, 204 s, and is left to benchmarks/oblique_impacts.py.

usage: check_friction.py FFRSIM SOURCE_DIR SID_DIR OUT_DIR
"""
import math
import os
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from result_checks import Checks, inertial_velocity, rotation  # noqa: E402
from same_bits import differences  # noqa: E402

ffrsim, source, sids, out = sys.argv[1:5]
sys.path.insert(0, os.path.join(source, "benchmarks"))
from oblique_reference import impulse_theory, psi2  # noqa: E402

os.makedirs(out, exist_ok=True)
check = Checks()
scene = os.path.join(source, "configs", "scenes", "oblique_friction.yaml")
MU, VN, VT = 0.1, 0.1, 0.1 * math.tan(math.radians(60.0))


def run(name, *extra, scene=scene):
    path = os.path.join(out, name + ".h5")
    check.run([ffrsim, "-q", scene, "--sid-path", sids, "-o", path, *extra])
    return path


rough = run("rough")
smooth = run("smooth", "--set", "contacts.0.friction_coefficient=0")
with h5py.File(os.path.join(sids, "sphere3d_coarse.sid.h5"), "r") as s:
    mass = float(s["sid/mass"][()])
    R = float(s["geometry/radius"][()])
inertia = 0.4 * mass * R * R  # the solid sphere's (the SID's inertia agrees to its mesh)

with h5py.File(rough, "r") as f, h5py.File(smooth, "r") as g:
    check.status_completed(f)
    v = inertial_velocity(f, "ball")[-1]
    w = f["bodies/ball/angular_velocity"][-1]  # body components: turned by pi about x
    e = v[2] / VN  # the rebound's normal speed over the approach's
    vt_ref, w_ref, vc_ref = impulse_theory(VN, VT, 0.0, R, mass, inertia, MU, e)
    d = v[0] / vt_ref - 1
    check(abs(d) <= 5e-3, f"tangential velocity after {v[0]:.6f} m/s, impulse theory "
          f"{vt_ref:.6f} m/s ({d:+.3%}, bound 0.5 %; restitution {e:.5f})")
    spin = abs(w[1])
    d = spin / w_ref - 1
    check(abs(d) <= 5e-3, f"spin after {spin:.4f} rad/s, impulse theory {w_ref:.4f} rad/s "
          f"({d:+.3%}, bound 0.5 %)")
    check(vc_ref > 0 and v[0] - R * spin > 0, "the contact point slides to the end (gross sliding)")
    pair = f["contacts/impact"]
    check(abs(float(pair.attrs["friction_coefficient"]) - MU) == 0.0
          and float(pair.attrs["slip_velocity_m_s"]) == 1e-6,
          "pair attributes friction_coefficient 0.1, slip_velocity_m_s 1e-6 (the default)")
    Fn, Ft = pair["normal_force"][:], pair["tangential_force"][:]
    i = int(np.argmax(Fn))
    ratio = np.linalg.norm(Ft[i]) / Fn[i]
    check(abs(ratio / MU - 1) <= 1e-6, f"tangential / normal force at the peak {ratio:.8f} (mu 0.1)")
    check(int(pair["slipping_points"][i]) > 0 and int(pair["sticking_points"][:].max()) == 0,
          f"every active point slips: {int(pair['slipping_points'][i])} at the peak, none sticks")
    # The traction field beside the pressure at the force peak: |t_i| = mu p_i at every
    # point (gross slip), tangential, against the sliding (+x), and its resultant mu times
    # the normal one.
    pk = pair["peak_pressure"]
    p, t, nrm, wt = pk["pressure"][:], pk["traction"][:], pk["normal"][:], pk["weight"][:]
    on = p > 0
    err = np.max(np.abs(np.linalg.norm(t[on], axis=1) / (MU * p[on]) - 1))
    tn = np.max(np.abs(np.sum(t[on] * nrm[on], axis=1)) / p[on])
    check(err <= 1e-6 and tn <= 1e-12 and bool(np.all(t[on, 0] < 0)) and
          bool(np.all(t[~on] == 0)) and pk["traction"].attrs["unit"] == "Pa",
          f"peak traction field: |t| = mu p at {int(on.sum())} points to {err:.1e} (bound 1e-6), "
          f"normal share {tn:.1e}, against the sliding, zero off contact")
    Ft_peak = np.linalg.norm((t * wt[:, None]).sum(axis=0))
    Fn_peak = np.linalg.norm(((p * wt)[:, None] * nrm).sum(axis=0))
    d = Ft_peak / (MU * Fn_peak) - 1
    check(abs(d) <= 1e-6 and abs(Fn_peak / float(pk.attrs["normal_force_N"]) - 1) <= 1e-12,
          f"peak traction resultant {Ft_peak:.4f} N = mu x {Fn_peak:.3f} N ({d:+.1e})")

    # 2. Against the frictionless run.
    sp = g["contacts/impact"]
    check("tangential_force" not in sp and "friction_coefficient" not in sp.attrs
          and "traction" not in sp["peak_pressure"],
          "the frictionless run has no friction series")
    peak, peak0 = float(f.attrs["max_contact_force_N"]), float(g.attrs["max_contact_force_N"])
    d = peak / peak0 - 1
    check(abs(d) <= 5e-3, f"normal force peak {peak:.3f} N, frictionless {peak0:.3f} N "
          f"({d:+.3%}, bound 0.5 %)")
    dur, dur0 = float(f.attrs["contact_duration_s"]), float(g.attrs["contact_duration_s"])
    d = dur / dur0 - 1
    check(abs(d) <= 5e-3, f"contact {1e6 * dur:.2f} us, frictionless {1e6 * dur0:.2f} us ({d:+.3%})")
    v0 = inertial_velocity(g, "ball")[-1]
    check(abs(v0[0] / VT - 1) <= 1e-6, f"frictionless: tangential velocity kept ({v0[0] / VT - 1:+.1e})")

    # 3. Friction work.
    W = f["energy/dissipated"][:]
    check(bool(np.all(np.diff(W) >= 0.0)), f"friction work never decreases (final {W[-1]:.4e} J)")
    en = f["energy"]
    kin_loss = (en["kinetic"][0] + en["elastic"][0] + en["contact"][0]) - \
        (en["kinetic"][-1] + en["elastic"][-1] + en["contact"][-1])
    d = W[-1] / kin_loss - 1
    check(abs(d) <= 2e-2, f"friction work {W[-1]:.5e} J against the energy lost {kin_loss:.5e} J "
          f"({d:+.2%}, bound 2 %: the quasi-static coordinates' share is not in it)")

# The plot script draws the friction's history and the traction beside the pressure.
pictures = os.path.join(out, "pictures")
r = subprocess.run([sys.executable, os.path.join(source, "benchmarks", "plot_result.py"), rough,
                    "-o", pictures], capture_output=True, text=True)
check(r.returncode == 0 and os.path.isfile(os.path.join(pictures, "rough_friction.png"))
      and os.path.isfile(os.path.join(pictures, "rough_pressure.png")),
      f"plot_result.py: exit {r.returncode}, rough_friction.png and rough_pressure.png "
      f"{r.stderr.strip()[-200:]}")

# 4. Threads and restart.
one = run("rough_1thread", "--threads", "1")
two = run("rough_2threads", "--threads", "2")
n, differ = differences(one, two, ("wall_time_s", "phase_before_contact_wall_s",
                                   "phase_during_contact_wall_s", "phase_after_contact_wall_s"))
check(not differ and n > 0, f"1 and 2 threads: {n} datasets and attributes equal bit for bit"
      + (f"; differ: {', '.join(differ[:6])}" if differ else ""))
part = run("rough_part", "--set", "integrator.end_time=5e-5")
r = subprocess.run([ffrsim, "-q", "--restart", part, "--end-time", "1e-4"], capture_output=True,
                   text=True)
check(r.returncode == 0, f"--restart in the contact: exit {r.returncode} {r.stderr.strip()}")
with h5py.File(part, "r") as f, h5py.File(rough, "r") as g:
    a, b = inertial_velocity(f, "ball")[-1], inertial_velocity(g, "ball")[-1]
    wa, wb = f["bodies/ball/angular_velocity"][-1], g["bodies/ball/angular_velocity"][-1]
    d = max(np.linalg.norm(a - b) / np.linalg.norm(b), np.linalg.norm(wa - wb) / np.linalg.norm(wb))
    check(d <= 1e-4, f"restarted at 50 us: velocity and spin at the end within {d:.1e} of the "
          "straight run (bound 1e-4)")
    d = abs(f["energy/dissipated"][-1] / g["energy/dissipated"][-1] - 1)
    check(d <= 1e-4, f"restarted: friction work within {d:.1e} (bound 1e-4)")

# 5. Two bodies: the same impact, mirrored, between two spheres (oblique_friction_pair.yaml).
pair_scene = os.path.join(source, "configs", "scenes", "oblique_friction_pair.yaml")

pair_rough = run("pair_rough", scene=pair_scene)
pair_smooth = run("pair_smooth", "--set", "contacts.0.friction_coefficient=0", scene=pair_scene)
with h5py.File(pair_rough, "r") as f, h5py.File(pair_smooth, "r") as g:
    check.status_completed(f)
    lo, up = inertial_velocity(f, "lower"), inertial_velocity(f, "upper")
    e = (up[-1, 2] - lo[-1, 2]) / (2 * VN)
    vt_ref, w_ref, _ = impulse_theory(VN, VT, 0.0, R, mass, inertia, MU, e)
    d = max(abs(up[-1, 0] / vt_ref - 1), abs(-lo[-1, 0] / vt_ref - 1))
    check(d <= 5e-3, f"pair: tangential velocities after {lo[-1, 0]:+.6f}, {up[-1, 0]:+.6f} m/s, "
          f"impulse theory -+{vt_ref:.6f} m/s (largest {d:.3%}, bound 0.5 %; restitution {e:.5f})")
    spins = [abs(f[f"bodies/{b}/angular_velocity"][-1, 1]) for b in ("lower", "upper")]
    d = max(abs(w / w_ref - 1) for w in spins)
    check(d <= 5e-3, f"pair: spins after {spins[0]:.4f}, {spins[1]:.4f} rad/s, impulse theory "
          f"{w_ref:.4f} rad/s (largest {d:.3%}, bound 0.5 %)")
    drift = np.abs(lo + up - (lo[0] + up[0])).max() / (2 * VN)
    check(drift <= 1e-9, f"pair: linear momentum kept to {drift:.1e} of m v_n (bound 1e-9: the "
          "friction forces are equal and opposite)")
    pair = f["contacts/impact"]
    Fn, Ft = pair["normal_force"][:], pair["tangential_force"][:]
    i = int(np.argmax(Fn))
    ratio = np.linalg.norm(Ft[i]) / Fn[i]
    check(abs(ratio / MU - 1) <= 1e-6 and int(pair["sticking_points"][:].max()) == 0,
          f"pair: tangential / normal force at the peak {ratio:.8f} (mu 0.1), no point sticks")
    pk = pair["peak_pressure"]
    t, wt, role, fac = pk["traction"][:], pk["weight"][:], pk["role"][:], pk.attrs["role_factor"]
    sign = np.where(role == 0, 1.0, -1.0)
    Ft_peak = fac * ((sign * wt)[:, None] * t).sum(axis=0)
    check(bool(np.all(t[role == 0, 0] >= 0)) and bool(np.all(t[role == 1, 0] <= 0))
          and abs(np.linalg.norm(Ft_peak) / (MU * float(pk.attrs["normal_force_N"])) - 1) <= 1e-6,
          f"pair: peak traction of both roles against their sliding, resultant "
          f"{np.linalg.norm(Ft_peak):.4f} N = mu x normal")
    peak, peak0 = float(f.attrs["max_contact_force_N"]), float(g.attrs["max_contact_force_N"])
    d = peak / peak0 - 1
    check(abs(d) <= 5e-3, f"pair: normal force peak {peak:.3f} N, frictionless {peak0:.3f} N "
          f"({d:+.3%}, bound 0.5 %)")
    W = f["energy/dissipated"][:]
    en = f["energy"]
    loss = sum(en[k][0] - en[k][-1] for k in ("kinetic", "elastic", "contact"))
    d = W[-1] / loss - 1
    check(bool(np.all(np.diff(W) >= 0.0)) and abs(d) <= 2e-2,
          f"pair: friction work {W[-1]:.5e} J against the energy lost {loss:.5e} J ({d:+.2%}, "
          "bound 2 % as above)")
# 6. Backspin: dropped onto the floor spinning, the sphere leaves rolling (backspin_drop.yaml).
spin_scene = os.path.join(source, "configs", "scenes", "backspin_drop.yaml")
dropped = run("backspin", scene=spin_scene)
with h5py.File(dropped, "r") as f:
    check.status_completed(f)
    v = inertial_velocity(f, "ball")[-1]
    w_in = rotation(f["bodies/ball/orientation"][-1:])[0] @ f["bodies/ball/angular_velocity"][-1]
    W0, MU3 = -10.0, 0.3  # rad/s about y (inertial), as the scene
    e = v[2] / VN
    vt_ref, w_ref, vc_ref = impulse_theory(VN, 0.0, W0, R, mass, inertia, MU3, e)
    check(abs(vc_ref) <= 1e-12, f"impulse theory: the slip stops, the sphere rolls off at "
          f"{vt_ref:+.6f} m/s, {w_ref:+.4f} rad/s")
    d = max(abs(v[0] / vt_ref - 1), abs(w_in[1] / w_ref - 1))
    check(d <= 5e-3, f"backspin: leaves at {v[0]:+.6f} m/s, spin {w_in[1]:+.4f} rad/s about y "
          f"(largest difference {d:.3%} from impulse theory, bound 0.5 %)")
    vc = v[0] - R * w_in[1]
    check(abs(vc) <= 1e-3 * abs(R * W0), f"backspin: rolling, the contact point slips at "
          f"{vc:+.2e} m/s after the impact against {R * abs(W0):.2f} m/s before (bound 0.1 %)")
    pair = f["contacts/impact"]
    ratio = np.linalg.norm(pair["tangential_force"][:], axis=1) / \
        np.maximum(pair["normal_force"][:], 1e-300)
    check(int(pair["sticking_points"][:].max()) > 0 and float(ratio.max()) <= MU3,
          f"backspin: points stick ({int(pair['sticking_points'][:].max())} at most), "
          f"|f_t| / f_n at most {ratio.max():.6f} <= mu")

# 7. Stick anchors: the compliant regime's sign reversal, and gross sliding as before.
with h5py.File(os.path.join(sids, "sphere3d_coarse.sid.h5"), "r") as s:
    nu = float(s["material/poisson_ratio"][()])
psi_scale = 2.0 * (1.0 - nu) / ((2.0 - nu) * MU * VN)  # Psi per unit slip velocity (m/s)
anchored = ("--set", "contacts.0.friction_law=anchored")
vt20 = VN * math.tan(math.radians(20.0))
at20 = ("--set", f"bodies.0.velocity=[{vt20!r}, 0, {-VN!r}]")
a20 = run("anchored_20", *anchored, *at20)
with h5py.File(a20, "r") as f:
    check.status_completed(f)
    pair = f["contacts/impact"]
    check(pair.attrs["friction_law"] == "anchored"
          and float(pair.attrs["stick_relaxation_time_s"]) == 1e-9,
          "pair attributes friction_law anchored, stick_relaxation_time_s 1e-9 (the default)")
    v = inertial_velocity(f, "ball")[-1]
    w = rotation(f["bodies/ball/orientation"][-1]) @ f["bodies/ball/angular_velocity"][-1]
    psi1, psi2_run = psi_scale * vt20, psi_scale * (v[0] - R * w[1])
    psi2_mbf = psi2(psi1, nu, 0.4, MU, VN)[0]
    d = psi2_run / psi2_mbf - 1
    check(psi2_run < -1.0 and abs(d) <= 0.10,
          f"20 degrees: Psi_1 = {psi1:.3f}, the rebound reversed: Psi_2 = {psi2_run:+.4f}, "
          f"Maw-Barber-Fawcett {psi2_mbf:+.4f} ({d:+.2%}, bound 10 %; rigid theory 0)")
    Fn, Ft = pair["normal_force"][:], np.linalg.norm(pair["tangential_force"][:], axis=1)
    check(bool(np.all(Ft <= MU * Fn * (1 + 1e-12) + 1e-12)),
          f"|f_t| <= mu f_n at every row (largest ratio {np.max(Ft / np.maximum(Fn, 1e-300)):.6f})")
    stick, slip = int(pair["sticking_points"][:].max()), int(pair["slipping_points"][:].max())
    check(stick > 0 and slip > 0, f"points stick ({stick} at most) and slip ({slip} at most)")
    W = f["energy/dissipated"][:]
    check(bool(np.all(np.diff(W) >= 0.0)) and W[-1] > 0,
          f"anchored: friction work never decreases (final {W[-1]:.4e} J)")
    v_end, w_end = v, f["bodies/ball/angular_velocity"][-1]
part = run("anchored_20_part", *anchored, *at20, "--set", "integrator.end_time=5e-5")
r = subprocess.run([ffrsim, "-q", "--restart", part, "--end-time", "1e-4"], capture_output=True,
                   text=True)
check(r.returncode == 0, f"anchored --restart in the contact: exit {r.returncode} {r.stderr.strip()}")
with h5py.File(part, "r") as f:
    a, wa = inertial_velocity(f, "ball")[-1], f["bodies/ball/angular_velocity"][-1]
    d = max(np.linalg.norm(a - v_end) / np.linalg.norm(v_end),
            np.linalg.norm(wa - w_end) / np.linalg.norm(w_end))
    check(d <= 5e-3, f"anchored, restarted at 50 us (points sticking): velocity and spin at the "
          f"end within {d:.1e} of the straight run (bound 5e-3)")
check.exit()
