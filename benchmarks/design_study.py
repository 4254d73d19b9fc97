#!/usr/bin/env python3
"""Design study of issue 26 (schemas/body_design.md): designed spheres against Hertz.

For every case of a matrix of impacts (radius, Young's modulus, Poisson's ratio, density,
approach speed, radius ratio), this script writes a body file with only a `design` block
(no hand-made refinement, hierarchy or contact region), builds it with igaprep, runs the
head-on impact of two such spheres (or of the sphere and its partner) with
`penalty_factor: auto` in ffrsim, and reads from the files: the force peak and contact
duration against Hertz (result attributes), ndof and nq (SID attributes), the wall times,
and the lowest elastic frequency f1 of the smaller body, from which the quasi-static figure
T f1 (Hertz's contact time in periods of that mode) says how far Hertz's quasi-static theory
can be trusted: the spheres' inertia makes the force peak exceed Hertz's by about
70 / (T f1)^2 per cent (fitted to this study for T f1 >= 8, faster below; the paper's
Sect. 5 impact, T f1 = 11.2, has an independent elastodynamic reference +0.5 ... +0.7 %
above Hertz), so cases with
T f1 < 12 (an excess above 0.5 %) are also compared with a designed model twice as fine
(N = 24 instead of the default 12, same impact): the discretisation error.

With --solid the same for 3D solid spheres (geometry sphere, 50 normal modes as the paper's
Sect. 6, the default accuracy level N = 2) on a smaller matrix of ten impacts; the finer
comparison (N = 3, about 47,000 ndof and minutes per case) only with --finer.

With --plateau, `penalty_factor: auto` against the plateau of paper Fig. 7 instead: for a
choice of cases (PLATEAU_CASES, each end of the matrix) the impact is run again with
c_p = PLATEAU_FACTOR times auto's (penetration 0.025 % of Hertz's approach instead of
0.2 %), and the force peak and duration at auto's value are reported against that run's.

usage: design_study.py BUILD_DIR OUT_DIR [--solid [--finer]] [--quick] [--json FILE] [--png FILE]
       design_study.py BUILD_DIR OUT_DIR --plateau [--solid] [--json FILE]
       design_study.py --plot-only JSON PNG [--solid]
"""
import json
import math
import os
import subprocess
import sys
import time

import h5py

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
QUASI_STATIC_LIMIT = 12.0  # T f1 below which Hertz's quasi-static theory is doubtful here


SOLID = "--solid" in sys.argv
# Accuracy levels: the default and the finer comparison.
LEVELS = (2, 3) if SOLID else (12, 24)


def body_yaml(name, R, E, nu, rho, v, partner, N):
    partner_text = partner if isinstance(partner, str) else (
        "{radius: %r, youngs_modulus: %r, poisson_ratio: %r, density: %r}" % partner)
    model = "solid" if SOLID else "axisymmetric"
    geometry = "sphere" if SOLID else "half_disk"
    extra = "reduction: {normal_modes: 50}\nvisualisation: {subdivisions: 0}\n" if SOLID else ""
    return f"""name: {name}
model: {model}
material: {{youngs_modulus: {E!r}, poisson_ratio: {nu!r}, density: {rho!r}}}
geometry: {{type: {geometry}, radius: {R!r}}}
design:
  impact: {{partner: {partner_text}, approach_speed: {v!r}}}
  elements_per_contact_radius: {N!r}
{extra}"""


def hertz_time(R1, R2, E1, nu1, E2, nu2, m1, m2, v):
    Es = 1 / ((1 - nu1**2) / E1 + (1 - nu2**2) / E2)
    Rs = R1 * R2 / (R1 + R2)
    ms = m1 * m2 / (m1 + m2)
    K = 4 / 3 * Es * math.sqrt(Rs)
    d = (5 * ms * v * v / (4 * K)) ** 0.4
    return 2.94352 * d / v


def scene_yaml(name, sid_a, sid_b, R1, R2, v, T):
    # The axis of the impact: y for the axisymmetric sections, z for the solids (their
    # contact points at +y and +z).
    def vec(x):
        return f"[0, 0, {x!r}]" if SOLID else f"[0, {x!r}, 0]"
    return f"""name: {name}
bodies:
  - {{name: lower, sid: {sid_a}, position: [0, 0, 0], velocity: {vec(v / 2)}}}
  - {{name: upper, sid: {sid_b}, position: {vec(R1 + R2)}, orientation: [0, 1, 0, 0], velocity: {vec(-v / 2)}}}
contacts:
  - {{name: impact, bodies: [lower, upper], penalty_factor: auto}}
integrator:
  end_time: {1.25 * T:.6g}
  output_interval: {T / 1000:.6g}
  rtol: 1.0e-6
  atol_position: {1e-12 * R1 / 0.01:.4g}
  atol_velocity: {5e-8 * v:.4g}
  atol_rotation: 1.0e-10
  atol_angular_velocity: {5e-6 * v * 0.01 / R1:.4g}
"""


def run_case(build, out, case, N, penalty_scale=None):
    """One impact: returns the figures as a dict. With penalty_scale, the impact is run
    again with that multiple of auto's c_p, and its figures come back under 'plateau'."""
    R, E, nu, rho, v, ratio = (case[k] for k in ("R", "E", "nu", "rho", "v", "ratio"))
    tag = f"{case['name']}_N{N:g}"
    d = os.path.join(out, tag)
    os.makedirs(d, exist_ok=True)
    R2 = R * ratio
    partner = "same" if ratio == 1 else (R2, E, nu, rho)
    bodies = [("a", R, "same" if ratio == 1 else (R2, E, nu, rho))]
    if ratio != 1:
        bodies.append(("b", R2, (R, E, nu, rho)))
    t_pre = 0.0
    for b, radius, p in bodies:
        path = os.path.join(d, b + ".yaml")
        with open(path, "w") as f:
            f.write(body_yaml(tag + b, radius, E, nu, rho, v, p, N))
        t0 = time.perf_counter()
        subprocess.run([os.path.join(build, "bin", "igaprep"), "-q", path, "-o",
                        os.path.join(d, b + ".sid.h5")], check=True)
        t_pre = max(t_pre, time.perf_counter() - t0)
    m1 = rho * 4 / 3 * math.pi * R**3
    m2 = rho * 4 / 3 * math.pi * R2**3
    T = hertz_time(R, R2, E, nu, E, nu, m1, m2, v)
    sid_b = "b.sid.h5" if ratio != 1 else "a.sid.h5"
    with open(os.path.join(d, "scene.yaml"), "w") as f:
        f.write(scene_yaml(tag, "a.sid.h5", sid_b, R, R2, v, T))
    t0 = time.perf_counter()
    subprocess.run([os.path.join(build, "bin", "ffrsim"), "-q", os.path.join(d, "scene.yaml"),
                    "-o", os.path.join(d, "result.h5")], check=True)
    t_sim = time.perf_counter() - t0
    row = dict(case=case["name"], N=N, igaprep_s=t_pre, ffrsim_s=t_sim)
    with h5py.File(os.path.join(d, "result.h5"), "r") as f:
        a = f.attrs
        row.update(force=float(a["max_contact_force_N"]), hertz_force=float(a["hertz_max_force_N"]),
                   force_vs_hertz=float(a["force_vs_hertz"]),
                   duration=float(a["contact_duration_s"]),
                   duration_vs_hertz=float(a["duration_vs_hertz"]), steps=int(a["solver_steps"]),
                   penalty=float(f["contacts/impact"].attrs["penalty_factor"]))
    f1 = 0.0
    for b, _, _ in bodies:
        with h5py.File(os.path.join(d, b + ".sid.h5"), "r") as s:
            row.setdefault("ndof", int(s.attrs["ndof"]))
            row.setdefault("nq", int(s.attrs["nq"]))
            row.setdefault("contact_radius", float(s["design/contact_radius"][()]))
            f1 = max(f1, float(s["sid/frequencies_hz"][:].min()))
    row["T_f1"] = T * f1
    if penalty_scale:
        row["plateau"] = rerun_stiffer(build, d, row["penalty"] * penalty_scale)
    return row


def rerun_stiffer(build, d, penalty):
    """The impact of directory d again with c_p = penalty (N/m^3): its force peak, duration,
    steps and wall time."""
    t0 = time.perf_counter()
    subprocess.run([os.path.join(build, "bin", "ffrsim"), "-q", os.path.join(d, "scene.yaml"),
                    "-o", os.path.join(d, "result_plateau.h5"),
                    "--set", f"contacts.0.penalty_factor={penalty!r}"], check=True)
    wall = time.perf_counter() - t0
    with h5py.File(os.path.join(d, "result_plateau.h5"), "r") as f:
        a = f.attrs
        return dict(penalty=float(f["contacts/impact"].attrs["penalty_factor"]),
                    force=float(a["max_contact_force_N"]),
                    duration=float(a["contact_duration_s"]), steps=int(a["solver_steps"]),
                    ffrsim_s=wall)


def cases(quick):
    """The matrix: around the paper's impact, each quantity varied over the issue's range,
    and combinations of them."""
    base = dict(R=0.01, E=2.11e11, nu=0.3, rho=7850.0, v=0.2, ratio=1)
    out = [dict(base, name="paper")]
    if quick:
        return out
    if SOLID:
        return out + [dict(base, name="R0.001", R=0.001), dict(base, name="v0.01", v=0.01),
                      dict(base, name="v5", v=5.0), dict(base, name="ratio2", ratio=2),
                      dict(name="alu_R0.005_v1", R=0.005, E=7.0e10, nu=0.33, rho=2700.0, v=1.0, ratio=1),
                      dict(name="glass_R0.02_v0.05", R=0.02, E=6.3e10, nu=0.22, rho=2500.0, v=0.05, ratio=1),
                      dict(name="carbide_R0.05_v2", R=0.05, E=4.0e11, nu=0.24, rho=8000.0, v=2.0, ratio=1),
                      dict(name="polymer_R0.02_v0.05", R=0.02, E=2.0e10, nu=0.35, rho=1800.0, v=0.05, ratio=1),
                      dict(name="nu0.2_rho4500", R=0.01, E=2.11e11, nu=0.2, rho=4500.0, v=0.5, ratio=1)]
    for R in (0.001, 0.003, 0.03, 0.1):
        out.append(dict(base, name=f"R{R:g}", R=R))
    for E in (2e10, 7e10, 4e11):
        out.append(dict(base, name=f"E{E:g}", E=E))
    for nu in (0.2, 0.25, 0.35):
        out.append(dict(base, name=f"nu{nu:g}", nu=nu))
    for rho in (1800.0, 2700.0, 4500.0, 8000.0):
        out.append(dict(base, name=f"rho{rho:g}", rho=rho))
    for v in (0.01, 0.05, 1.0, 5.0, 20.0):
        out.append(dict(base, name=f"v{v:g}", v=v))
    for ratio in (2, 5):
        out.append(dict(base, name=f"ratio{ratio}", ratio=ratio))
    materials = [("alu", 7.0e10, 0.33, 2700.0), ("glass", 6.3e10, 0.22, 2500.0),
                 ("carbide", 4.0e11, 0.24, 8000.0), ("polymer", 2.0e10, 0.35, 1800.0)]
    for mname, E, nu, rho in materials:
        for R, v in ((0.001, 0.5), (0.005, 1.0), (0.02, 0.05), (0.05, 2.0)):
            out.append(dict(name=f"{mname}_R{R:g}_v{v:g}", R=R, E=E, nu=nu, rho=rho, v=v, ratio=1))
        out.append(dict(name=f"{mname}_ratio3", R=0.005, E=E, nu=nu, rho=rho, v=0.3, ratio=3))
    return out


def run_matrix(build, out, quick):
    """Runs every case (and the finer model where T f1 < 12), printing a row each."""
    rows = []
    print(f"{'case':>22} {'a um':>8} {'T f1':>6} {'70/Tf1^2':>8} {'ndof':>6} {'nq':>4} "
          f"{'force':>8} {'dur':>8} {f'N={LEVELS[1]} vs N={LEVELS[0]}':>17} {'steps':>6} "
          f"{'pre s':>6} {'sim s':>6}")
    for case in cases(quick):
        r = run_case(build, out, case, LEVELS[0])
        if r["T_f1"] < QUASI_STATIC_LIMIT and (not SOLID or "--finer" in sys.argv):
            fine = run_case(build, out, case, LEVELS[1])
            r["finer_force"] = fine["force"] / r["force"] - 1
            r["finer_duration"] = fine["duration"] / r["duration"] - 1
            finer = f"{100 * r['finer_force']:+7.3f} {100 * r['finer_duration']:+7.3f} %"
        else:
            finer = ""
        rows.append(r)
        print(f"{r['case']:>22} {1e6 * r['contact_radius']:8.1f} {r['T_f1']:6.1f} "
              f"{70 / r['T_f1']**2:7.3f}% {r['ndof']:6d} "
              f"{r['nq']:4d} {100 * r['force_vs_hertz']:+7.3f}% {100 * r['duration_vs_hertz']:+7.3f}% "
              f"{finer:>17} {r['steps']:6d} {r['igaprep_s']:6.2f} {r['ffrsim_s']:6.2f}", flush=True)
    return rows


# --plateau: auto's c_p against PLATEAU_FACTOR times it, on cases from each end of the
# matrix (the paper's, the fastest, the softest and stiffest materials, unequal radii).
PLATEAU_FACTOR = 8.0
PLATEAU_CASES = (("paper", "v5", "carbide_R0.05_v2", "polymer_R0.02_v0.05", "ratio2") if SOLID else
                 ("paper", "v20", "v0.01", "carbide_R0.05_v2", "polymer_R0.001_v0.5", "ratio5",
                  "glass_ratio3"))


def run_plateau(build, out):
    """Auto's force peak and duration against the stiffer penalty's, a row per case."""
    rows = []
    print(f"{'case':>22} {'T f1':>6} {'c_p auto':>10} {'force':>8} {'dur':>8} "
          f"{'vs x' + format(PLATEAU_FACTOR, 'g') + ': force':>16} {'dur':>8} {'steps':>11} "
          f"{'sim s':>11}")
    chosen = [c for c in cases(False) if c["name"] in PLATEAU_CASES]
    for case in chosen:
        r = run_case(build, out, case, LEVELS[0], penalty_scale=PLATEAU_FACTOR)
        p = r["plateau"]
        r["auto_vs_plateau_force"] = r["force"] / p["force"] - 1
        r["auto_vs_plateau_duration"] = r["duration"] / p["duration"] - 1
        rows.append(r)
        print(f"{r['case']:>22} {r['T_f1']:6.1f} {r['penalty']:10.3e} "
              f"{100 * r['force_vs_hertz']:+7.3f}% {100 * r['duration_vs_hertz']:+7.3f}% "
              f"{100 * r['auto_vs_plateau_force']:+15.3f}% {100 * r['auto_vs_plateau_duration']:+7.3f}% "
              f"{r['steps']:5d}/{p['steps']:5d} {r['ffrsim_s']:5.1f}/{p['ffrsim_s']:5.1f}",
              flush=True)
    print(f"{len(rows)} cases: auto's force peak within "
          f"{100 * max(abs(r['auto_vs_plateau_force']) for r in rows):.3f} % and duration within "
          f"{100 * max(abs(r['auto_vs_plateau_duration']) for r in rows):.3f} % of "
          f"{PLATEAU_FACTOR:g} x auto's c_p")
    return rows


def summarise(rows):
    trusted = [r for r in rows if r["T_f1"] >= QUASI_STATIC_LIMIT]
    doubtful = [r for r in rows if "finer_force" in r]
    print(f"{len(rows)} cases; {len(trusted)} with T f1 >= {QUASI_STATIC_LIMIT:g}: largest "
          f"|force - Hertz| {100 * max(abs(r['force_vs_hertz']) for r in trusted):.3f} %, "
          f"|duration - Hertz| {100 * max(abs(r['duration_vs_hertz']) for r in trusted):.3f} %"
          if trusted else f"{len(rows)} cases, none with T f1 >= {QUASI_STATIC_LIMIT:g}")
    if doubtful:
        print(f"{len(doubtful)} with T f1 < {QUASI_STATIC_LIMIT:g} against N = {LEVELS[1]}: "
              f"largest |force(N={LEVELS[1]}) - force(N={LEVELS[0]})| "
              f"{100 * max(abs(r['finer_force']) for r in doubtful):.3f} %, "
              f"duration {100 * max(abs(r['finer_duration']) for r in doubtful):.3f} %")
    print(f"largest wall times: igaprep {max(r['igaprep_s'] for r in rows):.2f} s, "
          f"ffrsim {max(r['ffrsim_s'] for r in rows):.2f} s; largest ndof "
          f"{max(r['ndof'] for r in rows)}, nq {max(r['nq'] for r in rows)}")


def plot(rows, png_path):
    """Force peak and duration against Hertz over T f1, with the fitted inertia excess."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4.5))
    x = [r["T_f1"] for r in rows]
    ax.semilogx(x, [100 * r["force_vs_hertz"] for r in rows], "o", label="force peak")
    ax.semilogx(x, [100 * r["duration_vs_hertz"] for r in rows], "s", label="duration")
    xs = sorted(x)
    ax.semilogx(xs, [70 / t**2 for t in xs], "k--", lw=0.8, label="70 / (T f1)^2")
    ax.axvline(QUASI_STATIC_LIMIT, color="grey", lw=0.8)
    ax.axhspan(-1, 1, color="green", alpha=0.08)
    ax.set_xlabel("Hertz contact time x lowest elastic frequency, T f1")
    ax.set_ylabel(f"designed {'3D' if SOLID else 'axisymmetric'} model against Hertz, %")
    ax.legend()
    fig.tight_layout()
    fig.savefig(png_path, dpi=120)


def main():
    """design_study.py BUILD OUT [...]: run the matrix; design_study.py --plot-only JSON PNG
    [--solid]: draw a committed result again."""
    if "--plot-only" in sys.argv:
        k = sys.argv.index("--plot-only")
        with open(sys.argv[k + 1]) as f:
            plot(json.load(f), sys.argv[k + 2])
        return
    build, out = sys.argv[1], sys.argv[2]
    json_path = sys.argv[sys.argv.index("--json") + 1] if "--json" in sys.argv else None
    png_path = sys.argv[sys.argv.index("--png") + 1] if "--png" in sys.argv else None
    if "--plateau" in sys.argv:
        rows = run_plateau(build, out)
    else:
        rows = run_matrix(build, out, "--quick" in sys.argv)
        summarise(rows)
    if json_path:
        with open(json_path, "w") as f:
            json.dump(rows, f, indent=1)
    if png_path:
        plot(rows, png_path)


if __name__ == "__main__":
    main()
