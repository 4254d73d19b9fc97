#!/usr/bin/python3
"""Turns a result file of ffrsim into pictures (PNG), one per question a user asks first:

  RESULT_force.png          contact force of every pair over time, with Hertz's force
                            history where the result has Hertz's values (format 4)
  RESULT_energy.png         kinetic, elastic, contact, gravity and force-element energy and
                            their sum (what the run kept)
  RESULT_penetration.png    largest penetration of every pair (um)
  RESULT_active_points.png  collocation points in contact
  RESULT_stress_lines.png   von Mises stress along the SIDs' stress lines at the force peak,
                            with Hertz's field where the result has it (paper Fig. 10)

Pictures without data (no contact pairs, no stress lines) are skipped. Everything is read
from the file (schemas/result_format.md); nothing is recomputed but Hertz's force history
(m* delta'' = -K delta^(3/2) from the attributes hertz_stiffness_N_m1_5,
hertz_effective_mass_kg, hertz_approach_speed_m_s, by RK4).

usage: benchmarks/plot_result.py RESULT.h5 [-o DIR] [--zoom]
  -o DIR   where to write the PNGs (default: beside the result)
  --zoom   force, penetration and active points over the contact only
"""
import argparse
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def hertz_history(k, m, v, n=4000):
    """Force over time of m delta'' = -k delta^1.5, delta(0) = 0, delta'(0) = v (RK4 until the
    bodies separate)."""
    def f(y):
        d = max(y[0], 0.0)
        return np.array([y[1], -k * d ** 1.5 / m])

    dmax = (5 * m * v * v / (4 * k)) ** 0.4
    dt = 2.95 * dmax / v / n
    y, t, ts, fs = np.array([0.0, v]), 0.0, [0.0], [0.0]
    while True:
        k1 = f(y)
        k2 = f(y + 0.5 * dt * k1)
        k3 = f(y + 0.5 * dt * k2)
        k4 = f(y + dt * k3)
        y = y + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        t += dt
        if y[0] <= 0.0:
            break
        ts.append(t)
        fs.append(k * y[0] ** 1.5)
    ts.append(t)
    fs.append(0.0)
    return np.array(ts), np.array(fs)


def contact_window(f, times):
    a = f.attrs
    begin, end = float(a.get("contact_begin_s", -1)), float(a.get("contact_end_s", -1))
    if begin < 0:
        return times[0], times[-1]
    end = end if end >= 0 else times[-1]
    pad = 0.1 * (end - begin)
    return max(times[0], begin - pad), min(times[-1], end + pad)


def save(fig, path, written):
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    written.append(path)


def plot_force(f, t, base, zoom, written):
    if "contacts" not in f or len(f["contacts"]) == 0:
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for pair in f["contacts"]:
        ax.plot(1e6 * t, f["contacts"][pair]["normal_force"][:], label=f"ffrsim: {pair}")
    a = f.attrs
    if "hertz_stiffness_N_m1_5" in a:
        th, fh = hertz_history(a["hertz_stiffness_N_m1_5"], a["hertz_effective_mass_kg"],
                               a["hertz_approach_speed_m_s"])
        t0 = max(float(a["contact_begin_s"]), 0.0)
        ax.plot(1e6 * (th + t0), fh, "k--", lw=1,
                label=f"Hertz: {a['hertz_max_force_N']:.2f} N, {1e6 * a['hertz_duration_s']:.2f} us")
        title = (f"maximum {a['max_contact_force_N']:.3f} N ({100 * a['force_vs_hertz']:+.2f} % "
                 f"from Hertz)")
        if "duration_vs_hertz" in a:
            title += f", duration {100 * a['duration_vs_hertz']:+.2f} %"
        ax.set_title(title, fontsize=10)
    if zoom:
        lo, hi = contact_window(f, t)
        ax.set_xlim(1e6 * lo, 1e6 * hi)
    ax.set_xlabel("time [us]")
    ax.set_ylabel("contact force [N]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, base + "_force.png", written)


def plot_energy(f, t, base, written):
    if "energy" not in f:
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    total = np.zeros_like(t)
    for name in ("kinetic", "elastic", "contact", "gravity", "force_elements"):
        if name not in f["energy"]:
            continue
        e = f["energy"][name][:]
        total = total + e
        if np.any(e != 0):
            ax.plot(1e6 * t, e, label=name)
    ax.plot(1e6 * t, total, "k", lw=1.5, label=f"sum (change {total[-1] - total[0]:+.3g} J)")
    ax.set_xlabel("time [us]")
    ax.set_ylabel("energy [J]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, base + "_energy.png", written)


def plot_pair_series(f, t, base, zoom, written, name, scale, ylabel, suffix):
    if "contacts" not in f or len(f["contacts"]) == 0:
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for pair in f["contacts"]:
        ax.plot(1e6 * t, scale * f["contacts"][pair][name][:], label=pair)
    if zoom:
        lo, hi = contact_window(f, t)
        ax.set_xlim(1e6 * lo, 1e6 * hi)
    ax.set_xlabel("time [us]")
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, base + suffix, written)


def plot_stress_lines(f, base, written):
    if "stress_lines" not in f:
        return
    lines = [(b, l) for b in f["stress_lines"] for l in f["stress_lines"][b]]
    if not lines:
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    hertz_drawn = False
    for b, l in lines:
        g = f["stress_lines"][b][l]
        z = g["distance"][:]
        ax.plot(1e3 * z, 1e-6 * g["von_mises"][:], label=f"ffrsim: {b}/{l}")
        if "hertz_von_mises" in g and not hertz_drawn:
            a = g.attrs
            ax.plot(1e3 * z, 1e-6 * g["hertz_von_mises"][:], "k--", lw=1,
                    label=f"Hertz (a = {1e3 * a['hertz_contact_radius_m']:.4f} mm, "
                          f"p0 = {1e-9 * a['hertz_max_pressure_Pa']:.3f} GPa)")
            hertz_drawn = True
    s = f["stress_lines"].attrs
    ax.set_title(f"von Mises stress at the force peak ({s['contact_force_N']:.2f} N, "
                 f"t = {1e6 * s['time_s']:.2f} us)", fontsize=10)
    ax.set_xlabel("distance along the line [mm]")
    ax.set_ylabel("von Mises stress [MPa]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, base + "_stress_lines.png", written)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("result")
    p.add_argument("-o", "--out", help="folder for the PNGs (default: beside the result)")
    p.add_argument("--zoom", action="store_true", help="contact plots over the contact only")
    args = p.parse_args()
    try:
        f = h5py.File(args.result, "r")
    except OSError as e:
        print(f"plot_result.py: {args.result}: {e}", file=sys.stderr)
        return 2
    if f.attrs.get("format") not in ("ffriga-result", b"ffriga-result"):
        print(f"plot_result.py: {args.result}: not a result file of ffrsim", file=sys.stderr)
        return 2
    stem = os.path.splitext(os.path.basename(args.result))[0]
    folder = args.out or os.path.dirname(os.path.abspath(args.result))
    os.makedirs(folder, exist_ok=True)
    base = os.path.join(folder, stem)
    t = f["time"][:]
    written = []
    with f:
        plot_force(f, t, base, args.zoom, written)
        plot_energy(f, t, base, written)
        plot_pair_series(f, t, base, args.zoom, written, "max_penetration", 1e6,
                         "largest penetration [um]", "_penetration.png")
        plot_pair_series(f, t, base, args.zoom, written, "active_points", 1,
                         "collocation points in contact", "_active_points.png")
        plot_stress_lines(f, base, written)
    for w in written:
        print(w)
    return 0


if __name__ == "__main__":
    sys.exit(main())
