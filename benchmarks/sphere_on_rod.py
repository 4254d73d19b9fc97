#!/usr/bin/python3
"""A steel sphere striking the end face of a free steel rod on its axis, against Sears's model.

Issue 27: builds configs/bodies/sphere2d_h3.yaml (r = 1 cm) and rod2d_struck.yaml (radius
5 mm, L = 0.1 m, face graded to 25 um at its centre) with igaprep, runs
configs/scenes/sphere_on_rod.yaml (0.5 m/s) and prints, from the result file, against
Sears's model (a rigid sphere with Hertz's law on a one-dimensional free-free rod whose
reflected waves return every 2 L / c; tests/e2e/check_sphere_on_rod.py, whose integrator is
used here): each contact's start, end, duration and force peak, the sphere's and the rod's
velocities afterwards, momentum and energy drift, steps and wall time (median of --repeat
runs), igaprep's time and nq. The same model on a half-space (an infinitely long rod, no
reflection) shows what the returning wave changes. Then a penalty sweep (--penalties), the
rod with ffrsim's default quasi-static cutoff (4 f_1) instead of the scene's 1 MHz, and the
rod with its face's spans halved (12.5 um, --no-refined to skip it).

usage: benchmarks/sphere_on_rod.py [--build build] [--repeat 3] [--penalties 3e16,1e17,3e17]
                                   [--png out.png] [--text out.txt]
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "e2e"))
from check_sphere_on_rod import GAP, ROD_LENGTH, ROD_RADIUS, V0, sears  # noqa: E402
from result_checks import contact_runs, inertial_velocity, sphere_on_rod_figures  # noqa: E402

STEP = 2e-9  # s, the reference's RK4 step (converged to 1e-5: the check's docstring)


def contacts(t, F):
    """(start, end, peak) of each interval with F > 0, ends at the last rows with force."""
    return [(t[i], t[j], F[i:j + 1].max()) for i, j in contact_runs(F)]


def igaprep_run(igaprep, body, sid):
    start = time.monotonic()
    r = subprocess.run([igaprep, body, "-o", sid], check=True, capture_output=True, text=True)
    wall = time.monotonic() - start
    nq = re.search(r"^\s*nq\s+(\d+)", r.stdout + r.stderr, re.M)
    ndof = re.search(r"^\s*ndof\s+(\d+)", r.stdout + r.stderr, re.M)
    return wall, int(nq.group(1)) if nq else -1, int(ndof.group(1)) if ndof else -1


def measure(result, m, M):
    with h5py.File(result, "r") as f:
        a = f.attrs
        t = f["time"][:]
        F = f["contacts/hit/normal_force"][:]
        # Along the impact, -y (the frame origin: the centre of mass).
        vb, vr = -inertial_velocity(f, "ball")[:, 1], -inertial_velocity(f, "rod")[:, 1]
        energy = f["energy/kinetic"][:] + f["energy/elastic"][:] + f["energy/contact"][:]
        status = a["status"].decode() if isinstance(a["status"], bytes) else a["status"]
        p = m * vb + M * vr
        return dict(status=status, t=t, F=F, vb=vb, contacts=contacts(t, F),
                    begin=float(a["contact_begin_s"]), end=float(a["contact_end_s"]),
                    events=int(a["contact_events"]), v_ball=float(vb[-1]), v_rod=float(vr[-1]),
                    momentum=float(np.abs(p - p[0]).max() / (m * V0)),
                    energy=float(np.abs(energy - energy[0]).max() / energy[0]),
                    steps=int(a["solver_steps"]), wall=float(a["wall_time_s"]))


def variant(q, peak_ref, duration_ref):
    """One line on a variant's run (measure()) against the reference's peak and duration."""
    peak, duration = q["F"].max(), q["end"] - q["begin"]
    return (f"peak {peak:.2f} N ({peak / peak_ref - 1:+.2%}), duration {1e6 * duration:.2f} us "
            f"({duration / duration_ref - 1:+.2%}), events {q['events']}, sphere "
            f"{q['v_ball']:+.5f} m/s, steps {q['steps']}, wall {q['wall']:.2f} s")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--penalties", default="3e16,1e17,3e17")
    ap.add_argument("--no-refined", action="store_true")
    ap.add_argument("--png")
    ap.add_argument("--text")
    args = ap.parse_args()
    igaprep = os.path.join(args.build, "bin", "igaprep")
    ffrsim = os.path.join(args.build, "bin", "ffrsim")
    scene = os.path.join(ROOT, "configs", "scenes", "sphere_on_rod.yaml")
    lines = []
    with tempfile.TemporaryDirectory() as tmp:
        for name in ("sphere2d_h3", "rod2d_struck"):
            wall, nq, ndof = igaprep_run(igaprep, os.path.join(ROOT, "configs", "bodies", f"{name}.yaml"),
                                         os.path.join(tmp, f"{name}.sid.h5"))
            lines.append(f"igaprep {name}: ndof {ndof}, nq {nq}, {wall:.2f} s")
        b = sphere_on_rod_figures(os.path.join(tmp, "sphere2d_h3.sid.h5"),
                                  os.path.join(tmp, "rod2d_struck.sid.h5"), ROD_RADIUS)
        m, M, c, Z, K = b["m"], b["M"], b["c"], b["Z"], b["K"]
        lines.append(f"sphere m = {m:.5f} kg, rod M = {M:.5f} kg (m / M = {m / M:.3f}), c = {c:.1f} m/s, "
                     f"Z = rho c A = {Z:.1f} kg/s, 2 L / c = {2e6 * ROD_LENGTH / c:.2f} us, "
                     f"K = {K:.4e} N/m^1.5, v0 = {V0} m/s")
        out = os.path.join(tmp, "sphere_on_rod.h5")
        walls = []
        for _ in range(args.repeat):
            subprocess.run([ffrsim, "-q", scene, "--sid-path", tmp, "-o", out], check=True)
            res = measure(out, m, M)
            walls.append(res["wall"])
        res["wall"] = statistics.median(walls)
        T = float(res["t"][-1])
        t_ref, F_ref, v_ref = sears(m, K, Z, 2 * ROD_LENGTH / c, V0, GAP, T, STEP)
        t_hs, F_hs, v_hs = sears(m, K, Z, 10 * T, V0, GAP, T, STEP)  # no reflection within T
        ref = contacts(t_ref, F_ref)
        lines.append("")
        lines.append(f"contacts over {T * 1e6:.0f} us ({T * c / (2 * ROD_LENGTH):.1f} round trips): "
                     f"ffrsim {len(res['contacts'])} (contact_events {res['events']}), Sears {len(ref)}")
        for k, ((s, e, p), (rs, re_, rp)) in enumerate(zip(res["contacts"], ref)):
            if k == 0:  # the result's exact first and last touch
                s, e = res["begin"], res["end"]
            lines.append(f"  contact {k + 1}: ffrsim {1e6 * s:7.2f} .. {1e6 * e:7.2f} us, duration "
                         f"{1e6 * (e - s):6.2f} us, peak {p:7.2f} N | Sears {1e6 * rs:7.2f} .. "
                         f"{1e6 * re_:7.2f} us, duration {1e6 * (re_ - rs):6.2f} us, peak {rp:7.2f} N | "
                         f"duration {(e - s) / (re_ - rs) - 1:+.2%}, peak {p / rp - 1:+.2%}")
        hs = contacts(t_hs, F_hs)[0]
        lines.append(f"  half-space (no reflection): {1e6 * hs[0]:.2f} .. {1e6 * hs[1]:.2f} us, "
                     f"duration {1e6 * (hs[1] - hs[0]):.2f} us, peak {hs[2]:.2f} N, sphere leaves at "
                     f"{v_hs[-1]:+.5f} m/s")
        dev = np.abs(res["F"] - np.interp(res["t"], t_ref, F_ref)).max() / F_ref.max()
        lines.append(f"  force history: largest row difference {dev:.2%} of Sears's peak")
        lines.append(f"sphere leaves at {res['v_ball']:+.5f} m/s, Sears {v_ref[-1]:+.5f} m/s "
                     f"({(res['v_ball'] - v_ref[-1]) / V0:+.3%} of v0); rod's centre of mass "
                     f"{res['v_rod']:+.5f} m/s, Sears (momentum) {m * (V0 - v_ref[-1]) / M:+.5f} m/s")
        lines.append(f"momentum drift {res['momentum']:.1e} of m v0, energy drift {res['energy']:.1e} "
                     f"of the initial; status {res['status']}, steps {res['steps']}, wall "
                     f"{res['wall']:.2f} s (median of {args.repeat})")
        lines.append("")
        lines.append("penalty sweep (one run each):")
        text = open(scene).read()
        for p in args.penalties.split(","):
            scene_text, n = re.subn(r"penalty_factor: *[0-9.e+]+", f"penalty_factor: {float(p):.3e}", text)
            assert n == 1
            path = os.path.join(tmp, f"penalty_{p}.yaml")
            open(path, "w").write(scene_text)
            r = os.path.join(tmp, f"penalty_{p}.h5")
            try:
                subprocess.run([ffrsim, "-q", path, "--sid-path", tmp, "-o", r], check=True)
                q = measure(r, m, M)
                lines.append(f"  c_p = {float(p):.0e} N/m^3: {q['status']}, "
                             + variant(q, F_ref.max(), ref[0][1] - ref[0][0]))
            except subprocess.CalledProcessError as err:
                lines.append(f"  c_p = {float(p):.0e} N/m^3: ffrsim failed (exit {err.returncode})")
        scene_text, n = re.subn(r"\n *quasi_static: \{above_hz: [0-9.e+]+\}", "", text)
        assert n == 1
        path = os.path.join(tmp, "qs_default.yaml")
        open(path, "w").write(scene_text)
        r = os.path.join(tmp, "qs_default.h5")
        subprocess.run([ffrsim, "-q", path, "--sid-path", tmp, "-o", r], check=True)
        q = measure(r, m, M)
        lines.append("")
        lines.append("rod with the default quasi-static cutoff (4 f_1, 104 kHz): "
                     + variant(q, F_ref.max(), ref[0][1] - ref[0][0]))
        if not args.no_refined:
            body = open(os.path.join(ROOT, "configs", "bodies", "rod2d_struck.yaml")).read()
            xi = [round(0.0025 * k, 6) for k in range(1, 33)] + [0.09, 0.12, 0.14, 0.16]
            eta = sorted([round(1 - 0.000125 * k, 7) for k in range(1, 33)]
                         + [0.9955, 0.995, 0.994, 0.993, 0.992])
            body, n = re.subn(r"  insert:.*?\ncontact:", f"  insert:\n    - {xi}\n    - {eta}\ncontact:",
                              body, flags=re.S)
            assert n == 1
            fine = os.path.join(tmp, "fine")
            os.makedirs(fine)
            open(os.path.join(fine, "rod.yaml"), "w").write(body)
            wall, nq, ndof = igaprep_run(igaprep, os.path.join(fine, "rod.yaml"),
                                         os.path.join(fine, "rod2d_struck.sid.h5"))
            os.symlink(os.path.join(tmp, "sphere2d_h3.sid.h5"), os.path.join(fine, "sphere2d_h3.sid.h5"))
            r = os.path.join(fine, "r.h5")
            subprocess.run([ffrsim, "-q", scene, "--sid-path", fine, "-o", r], check=True)
            q = measure(r, m, M)
            lines.append("")
            lines.append(f"rod face spans halved (12.5 um; ndof {ndof}, nq {nq}, igaprep {wall:.2f} s): "
                         + variant(q, F_ref.max(), ref[0][1] - ref[0][0]))
    print("\n".join(lines))
    if args.text:
        open(args.text, "w").write("\n".join(lines) + "\n")
    if args.png:
        plot(res, (t_ref, F_ref, v_ref), (t_hs, F_hs, v_hs), args.png)


def plot(res, ref, hs, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4))
    ax.plot(1e6 * res["t"], res["F"], lw=1.2, label="ffrsim")
    ax.plot(1e6 * ref[0], ref[1], "k--", lw=1, label="Sears (1D rod, reflections)")
    ax.plot(1e6 * hs[0], hs[1], ":", color="gray", lw=1, label="Hertz on a half-space (no reflection)")
    ax.set_xlim(0, 100)
    ax.set_xlabel("time (us)")
    ax.set_ylabel("contact force (N)")
    ax.set_title("sphere2d_h3 at 0.5 m/s on rod2d_struck (d = 10 mm, L = 0.1 m)", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    bx.plot(1e6 * res["t"], res["vb"], lw=1.2, label="ffrsim")
    bx.plot(1e6 * ref[0], ref[2], "k--", lw=1, label="Sears")
    bx.plot(1e6 * hs[0], hs[2], ":", color="gray", lw=1, label="half-space")
    bx.set_xlabel("time (us)")
    bx.set_ylabel("sphere velocity along the impact (m/s)")
    bx.legend(fontsize=8)
    bx.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png, dpi=130)


if __name__ == "__main__":
    main()
