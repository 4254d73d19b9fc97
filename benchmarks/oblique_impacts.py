#!/usr/bin/env python3
"""Oblique impacts with friction (issue 28): the coarse 3D steel sphere
(configs/scenes/oblique_friction.yaml, mu = 0.1) thrown onto a rigid floor at angles of
incidence theta from 2 to 85 degrees (v_n = 0.1 m/s, v_t = v_n tan theta, no spin), against
the independent references of benchmarks/oblique_reference.py:

  * rigid-body impulse theory: the tangential velocity and spin after the impact (gross
    sliding for tan theta >= mu (1 + e) (1 + m R^2 / I) = 0.7, rolling below);
  * Maw, Barber and Fawcett's compliant theory (method of dimensionality reduction):
    the local angle of reflection Psi_2 against the local angle of incidence Psi_1
    (Psi = 2 (1 - nu) v_c / ((2 - nu) mu v_n), v_c the contact point's slip velocity),
    negative below Psi_1 ~ 4 chi where rigid theory has the point rolling (Psi_2 = 0).

The table gives ffrsim's Psi_2 next to both, the tangential velocity and spin against
impulse theory, steps and wall time; the PNG draws Psi_2 over Psi_1. --law anchored runs
the scene with friction_law: anchored (stick anchors: the compliant regime), else the
regularised law; --plot-only draws one or two JSON files (each its law's points).

usage: oblique_impacts.py BUILD_DIR OUT_DIR [--law anchored] [--json FILE] [--png FILE] [--quick]
       oblique_impacts.py --plot-only JSON [JSON2] PNG
"""
import json
import math
import os
import subprocess
import sys
import time

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(REPO, "tests", "e2e"))
from oblique_reference import chi_of, impulse_theory, psi2  # noqa: E402
from result_checks import inertial_velocity, rotation  # noqa: E402

MU, VN = 0.1, 0.1
SCENE = os.path.join(REPO, "configs", "scenes", "oblique_friction.yaml")


def run(build, out, theta, law):
    vt = VN * math.tan(math.radians(theta))
    path = os.path.join(out, f"theta{theta:g}_{law}.h5")
    t0 = time.perf_counter()
    subprocess.run([os.path.join(build, "bin", "ffrsim"), "-q", SCENE, "--sid-path",
                    os.path.join(build, "tests", "e2e"), "-o", path,
                    "--set", f"bodies.0.velocity=[{vt!r}, 0, {-VN!r}]",
                    "--set", f"contacts.0.friction_law={law}"], check=True)
    wall = time.perf_counter() - t0
    with h5py.File(path, "r") as f:
        v = inertial_velocity(f, "ball")[-1]
        R_q = rotation(f["bodies/ball/orientation"][-1])
        w = R_q @ f["bodies/ball/angular_velocity"][-1]  # inertial
        steps = int(f.attrs["solver_steps"])
    return dict(theta=theta, vt=vt, v_after=v.tolist(), w_after=w.tolist(), steps=steps,
                wall_s=wall)


def main():
    if "--plot-only" in sys.argv:  # oblique_impacts.py --plot-only JSON [JSON2] PNG
        files = sys.argv[sys.argv.index("--plot-only") + 1:]
        sets = []
        for name in files[:-1]:
            with open(name) as f:
                sets.append(json.load(f))
        plot(sets, files[-1])
        return
    law = sys.argv[sys.argv.index("--law") + 1] if "--law" in sys.argv else "regularised"
    args = [a for a in sys.argv[1:] if not a.startswith("--") and a != law]
    build, out = args[0], args[1]
    os.makedirs(out, exist_ok=True)
    with h5py.File(os.path.join(build, "tests", "e2e", "sphere3d_coarse.sid.h5"), "r") as s:
        m = float(s["sid/mass"][()])
        R = float(s["geometry/radius"][()])
        nu = float(s["material/poisson_ratio"][()])
    I = 0.4 * m * R * R
    chi = chi_of(nu, 0.4)
    scale = 2.0 * (1.0 - nu) / ((2.0 - nu) * MU * VN)  # Psi per unit slip velocity
    thetas = [5, 20, 45] if "--quick" in sys.argv else [2, 5, 10, 15, 20, 25, 30, 35, 40, 50,
                                                        60, 70, 85]
    print(f"# chi = {chi:.4f} (nu = {nu}), mu = {MU}, v_n = {VN} m/s; gross sliding for "
          f"tan theta >= {MU * 2 * (1 + m * R * R / I):.3f}")
    print(f"{'theta':>6} {'Psi1':>7} {'Psi2':>8} {'MBF':>8} {'rigid':>8} {'vt/imp':>9} "
          f"{'w/imp':>9} {'steps':>6} {'wall s':>7}")
    rows = []
    for th in thetas:
        r = run(build, out, th, law)
        vx, vz = r["v_after"][0], r["v_after"][2]
        e = vz / VN
        wy = r["w_after"][1]
        vc1, vc2 = r["vt"], vx - R * wy
        vt_i, w_i, vc_i = impulse_theory(VN, r["vt"], 0.0, R, m, I, MU, e)
        r.update(psi1=scale * vc1, psi2=scale * vc2, psi2_rigid=scale * vc_i,
                 psi2_mbf=psi2(scale * vc1, nu, 0.4, MU, VN)[0],
                 vt_vs_impulse=vx / vt_i - 1, w_vs_impulse=wy / w_i - 1 if w_i else float("nan"),
                 restitution=e)
        rows.append(r)
        print(f"{th:6g} {r['psi1']:7.3f} {r['psi2']:+8.4f} {r['psi2_mbf']:+8.4f} "
              f"{r['psi2_rigid']:+8.4f} {100 * r['vt_vs_impulse']:+8.3f}% "
              f"{100 * r['w_vs_impulse']:+8.3f}% {r['steps']:6d} {r['wall_s']:7.2f}", flush=True)
    if "--json" in sys.argv:
        with open(sys.argv[sys.argv.index("--json") + 1], "w") as f:
            json.dump(dict(chi=chi, nu=nu, mu=MU, v_n=VN, law=law, rows=rows), f, indent=1)
    if "--png" in sys.argv:
        plot([dict(chi=chi, nu=nu, law=law, rows=rows)], sys.argv[sys.argv.index("--png") + 1])


def plot(sets, png):
    """Psi_2 over Psi_1 up to 12 chi (beyond, gross sliding follows the line Psi_1 - 4 chi),
    one set of points per law."""
    chi, nu = sets[0]["chi"], sets[0]["nu"]
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    top = 12.0 * chi
    xs = np.linspace(0.05, top, 48)
    ax.plot(xs, [psi2(x, nu, 0.4, MU, VN)[0] for x in xs], "k-", lw=1,
            label="Maw-Barber-Fawcett (MDR)")
    ax.plot(xs, np.maximum(xs - 4 * chi, 0.0), "k--", lw=0.8, label="rigid-body theory")
    for d, marker in zip(sets, "os"):
        shown = [r for r in d["rows"] if r["psi1"] <= top]
        ax.plot([r["psi1"] for r in shown], [r["psi2"] for r in shown], marker, mfc="none",
                label=f"ffrsim ({d.get('law', 'regularised')} friction)")
    ax.axhline(0, color="grey", lw=0.5)
    ax.set_xlim(0, top)
    ax.set_xlabel("local angle of incidence Psi_1")
    ax.set_ylabel("local angle of reflection Psi_2")
    ax.set_title(f"steel sphere on a rigid floor, mu = {MU}, chi = {chi:.3f}")
    ax.legend()
    fig.tight_layout()
    fig.savefig(png, dpi=120)

if __name__ == "__main__":
    main()
