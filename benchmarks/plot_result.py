#!/usr/bin/python3
"""Turns a result file of ffrsim into pictures (PNG), one per question a user asks first:

  RESULT_force.png          contact force of every pair over time, with Hertz's force
                            history where the result has Hertz's values (format 4 on)
  RESULT_energy.png         kinetic, elastic, contact, gravity and force-element energy and
                            their sum (what the run kept)
  RESULT_penetration.png    largest penetration of every pair (um)
  RESULT_active_points.png  collocation points in contact
  RESULT_friction.png       pairs with friction: |tangential force| against mu times the
                            normal force (the slip limit) over time
  RESULT_stress_lines.png   von Mises stress along the SIDs' stress lines at the force peak,
                            with Hertz's field where the result has it (paper Fig. 10)
  RESULT_pressure.png       contact pressure at the collocation points at each pair's force
                            peak against the distance from the contact axis (axisymmetric
                            bodies: the radius), with Hertz's p0 sqrt(1 - r^2/a^2) where the
                            stress lines hold Hertz's a and p0 for the same force; with
                            friction also the tangential traction |t| (crosses)

Pictures without data (no contact pairs, no stress lines) are skipped. Everything is read
from the file (schemas/result_format.md); nothing is recomputed but Hertz's force history
(m* delta'' = -K delta^(3/2) from the attributes hertz_stiffness_N_m1_5,
hertz_effective_mass_kg, hertz_approach_speed_m_s, by RK4).

A running result (ffrsim writes it in HDF5's SWMR mode, schemas/result_format.md) is read
with SWMR: `--follow` redraws the pictures every few seconds from the rows flushed so far
and stops once the run's status leaves `running` (completed, interrupted or failed) or no
ffrsim writes the file any more (a killed run: exit code 1); the stress lines appear once a
contact was seen.

usage: benchmarks/plot_result.py RESULT.h5 [-o DIR] [--zoom] [--follow [SECONDS]]
  -o DIR            where to write the PNGs (default: beside the result)
  --zoom            force, penetration and active points over the contact only
  --follow SECONDS  redraw every SECONDS (default 5) until the run has ended
"""
import argparse
import os
import sys
import time

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


def figure(f, name, default=None):
    """A figure of the run: the root attribute, or while the run goes (the root's figures
    are written at its end) the restart record's figure_NAME of the last flush."""
    if name in f.attrs:
        return f.attrs[name]
    record = f["restart"].attrs if "restart" in f else {}
    return record.get("figure_" + name, default)


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def contact_window(f, times):
    begin, end = float(figure(f, "contact_begin_s", -1)), float(figure(f, "contact_end_s", -1))
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


def finish_time_plot(fig, ax, f, t, zoom, ylabel, path, written):
    """Labels, grid and legend of a plot over time (zoomed to the contact if asked), saved."""
    if zoom:
        lo, hi = contact_window(f, t)
        ax.set_xlim(1e6 * lo, 1e6 * hi)
    ax.set_xlabel("time [us]")
    ax.set_ylabel(ylabel)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, path, written)


def plot_force(f, t, base, zoom, written):
    if "contacts" not in f or len(f["contacts"]) == 0:
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for pair in f["contacts"]:
        ax.plot(1e6 * t, f["contacts"][pair]["normal_force"][:len(t)], label=f"ffrsim: {pair}")
    a = f.attrs
    if "hertz_stiffness_N_m1_5" in a:
        th, fh = hertz_history(a["hertz_stiffness_N_m1_5"], a["hertz_effective_mass_kg"],
                               a["hertz_approach_speed_m_s"])
        t0 = max(float(figure(f, "contact_begin_s", -1)), 0.0)
        ax.plot(1e6 * (th + t0), fh, "k--", lw=1,
                label=f"Hertz: {a['hertz_max_force_N']:.2f} N, {1e6 * a['hertz_duration_s']:.2f} us")
        peak = float(figure(f, "max_contact_force_N", 0.0))
        title = (f"maximum {peak:.3f} N ({100 * (peak / a['hertz_max_force_N'] - 1):+.2f} % "
                 f"from Hertz)")
        if "duration_vs_hertz" in a:
            title += f", duration {100 * a['duration_vs_hertz']:+.2f} %"
        if text(a.get("status", "")) == "running":
            title += ", so far"
        ax.set_title(title, fontsize=10)
    finish_time_plot(fig, ax, f, t, zoom, "contact force [N]", base + "_force.png", written)


def plot_energy(f, t, base, written):
    if "energy" not in f:
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    total = np.zeros_like(t)
    for name in ("kinetic", "elastic", "contact", "gravity", "force_elements"):
        if name not in f["energy"]:
            continue
        e = f["energy"][name][:len(t)]
        total = total + e
        if np.any(e != 0):
            ax.plot(1e6 * t, e, label=name)
    if len(t):
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
        ax.plot(1e6 * t, scale * f["contacts"][pair][name][:len(t)], label=pair)
    finish_time_plot(fig, ax, f, t, zoom, ylabel, base + suffix, written)


def plot_friction(f, t, base, zoom, written):
    """|tangential_force| against mu times normal_force of every pair with friction."""
    pairs = [p for p in f.get("contacts", {}) if "tangential_force" in f["contacts"][p]]
    if not pairs:
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for pair in pairs:
        g = f["contacts"][pair]
        mu = float(g.attrs["friction_coefficient"])
        line, = ax.plot(1e6 * t, np.linalg.norm(g["tangential_force"][:len(t)], axis=1),
                        label=f"{pair}: |tangential force|")
        ax.plot(1e6 * t, mu * g["normal_force"][:len(t)], "--", lw=1, color=line.get_color(),
                label=f"{pair}: mu x normal force (mu = {mu:g}): the slip limit")
    finish_time_plot(fig, ax, f, t, zoom, "force [N]", base + "_friction.png", written)


def plot_stress_lines(f, base, written):
    if "stress_lines" not in f or f["stress_lines"].attrs["time_s"] < 0:  # no contact yet
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


def hertz_patch(f, force):
    """Hertz's (a, p0) from the stress lines recorded at the same force, else None."""
    if "stress_lines" not in f or f["stress_lines"].attrs["contact_force_N"] != force:
        return None
    for b in f["stress_lines"]:
        for l in f["stress_lines"][b]:
            a = f["stress_lines"][b][l].attrs
            if "hertz_contact_radius_m" in a and np.isfinite(a["hertz_contact_radius_m"]):
                return a["hertz_contact_radius_m"], a["hertz_max_pressure_Pa"]
    return None


def plot_pressure(f, base, written):
    pairs = [p for p in f.get("contacts", {}) if "peak_pressure" in f["contacts"][p]
             and f["contacts"][p]["peak_pressure"].attrs["time_s"] >= 0]
    if not pairs:
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for pair in pairs:
        g = f["contacts"][pair]["peak_pressure"]
        x, p, w = g["position"][()], g["pressure"][()], g["weight"][()]
        body = f["contacts"][pair].attrs["body_a"]
        if f["bodies"][body].attrs["model"] == "axisymmetric":
            r = np.abs(x[:, 0])
        else:  # about the axis through the pressure's centre along the resultant
            n = g["normal"][()]
            c = (p * w) @ x / max(np.sum(p * w), 1e-300)
            e = np.sum((p * w)[:, None] * n, axis=0)
            e = e / max(np.linalg.norm(e), 1e-300)
            d = x - c
            r = np.linalg.norm(d - np.outer(d @ e, e), axis=1)
        for role in sorted(set(g["role"][()])):
            m = g["role"][()] == role
            line, = ax.plot(1e3 * r[m], 1e-6 * p[m], "o", ms=4, mfc="none",
                            label=f"ffrsim: {pair}, role {role} "
                                  f"({g.attrs['normal_force_N']:.2f} N, "
                                  f"t = {1e6 * g.attrs['time_s']:.2f} us)")
            if "traction" in g:  # a pair with friction: |t| beside p, the same colour
                t = np.linalg.norm(g["traction"][()][m], axis=1)
                ax.plot(1e3 * r[m], 1e-6 * t, "x", ms=4, color=line.get_color(),
                        label=f"ffrsim: {pair}, role {role}, tangential traction |t|")
        patch = hertz_patch(f, g.attrs["normal_force_N"])
        if patch:
            a, p0 = patch
            s = np.linspace(0, a, 200)
            ax.plot(1e3 * s, 1e-6 * p0 * np.sqrt(1 - (s / a) ** 2), "k--", lw=1,
                    label=f"Hertz (a = {1e3 * a:.4f} mm, p0 = {1e-9 * p0:.3f} GPa)")
            ax.set_xlim(0, 2e3 * a)
    ax.set_title("contact pressure at each pair's force peak (c_p max(0, -g_n))", fontsize=10)
    ax.set_xlabel("distance from the contact axis [mm]")
    ax.set_ylabel("pressure, traction [MPa]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, base + "_pressure.png", written)


def open_result(path, swmr):
    """The result file, read with SWMR if asked (a running result); a file being closed by
    ffrsim (its final figures, a few milliseconds) is tried again."""
    for attempt in range(20):
        try:
            return h5py.File(path, "r", swmr=swmr)
        except OSError:
            if attempt == 19 or not os.path.exists(path):
                raise
            time.sleep(0.25)


def rows(f):
    """The output times every series has on disk: a reader of a running result sees each
    dataset as of the writer's last flush of it, so one may be a flush ahead of another.
    Series are the extendable datasets (unlimited first dimension); fixed-size ones (an
    obstacle's point and normal) are not rows."""
    n = f["time"].shape[0]
    for group in ("contacts", "energy"):
        if group in f:
            for name, obj in f[group].items():
                items = obj.values() if isinstance(obj, h5py.Group) else [obj]
                for d in items:
                    if isinstance(d, h5py.Dataset) and d.ndim >= 1 and d.maxshape[0] is None:
                        n = min(n, d.shape[0])
    return f["time"][:n]


def draw(f, base, zoom):
    t = rows(f)
    written = []
    plot_force(f, t, base, zoom, written)
    plot_energy(f, t, base, written)
    plot_pair_series(f, t, base, zoom, written, "max_penetration", 1e6,
                     "largest penetration [um]", "_penetration.png")
    plot_pair_series(f, t, base, zoom, written, "active_points", 1,
                     "collocation points in contact", "_active_points.png")
    plot_friction(f, t, base, zoom, written)
    plot_stress_lines(f, base, written)
    plot_pressure(f, base, written)
    return t, written


def writer_alive(path):
    """Whether a process holds ffrsim's writer lock on the file (a record lock on one byte
    at 2^62, runtime/output/writer_lock.h): False once the writing ffrsim is gone, however
    it ended."""
    import fcntl
    import struct
    try:
        with open(path, "rb") as f:
            request = struct.pack("hhqqi", fcntl.F_WRLCK, os.SEEK_SET, 1 << 62, 1, 0)
            answer = fcntl.fcntl(f.fileno(), fcntl.F_GETLK, request)
            return struct.unpack("hhqqi", answer)[0] != fcntl.F_UNLCK
    except OSError:
        return True  # no record locks here: cannot tell


def follow(path, base, zoom, interval):
    """Redraws every `interval` seconds until the status leaves `running`. A reading that
    fails (the few milliseconds in which ffrsim writes its final figures) is tried again at
    the next redraw; ten failures in a row end it with the error. A run whose status stays
    `running` with no ffrsim writing it (killed) ends it at the second redraw that sees so."""
    failures = 0
    orphaned = 0
    while True:
        try:
            with open_result(path, swmr=True) as f:
                status = text(f.attrs.get("status", ""))
                t, written = draw(f, base, zoom)
            failures = 0
        except (OSError, KeyError, RuntimeError) as e:
            failures += 1
            if failures == 10:
                print(f"plot_result.py: {path}: {e}", file=sys.stderr)
                return 1
            time.sleep(interval)
            continue
        last = f"{t[-1]:.6g} s" if len(t) else "-"
        print(f"{status}: {len(t)} rows up to t = {last}, {len(written)} pictures", flush=True)
        if status != "running":
            for w in written:
                print(w)
            return 0
        orphaned = 0 if writer_alive(path) else orphaned + 1
        if orphaned == 2:
            print(f"plot_result.py: {path}: status 'running' but no ffrsim writes it (killed?); "
                  f"the pictures show its last flush", file=sys.stderr)
            return 1
        time.sleep(interval)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("result")
    p.add_argument("-o", "--out", help="folder for the PNGs (default: beside the result)")
    p.add_argument("--zoom", action="store_true", help="contact plots over the contact only")
    p.add_argument("--follow", nargs="?", const=5.0, type=float, metavar="SECONDS",
                   help="redraw every SECONDS (default 5) until the run has ended")
    args = p.parse_args()
    if args.follow is not None and not args.follow > 0:
        print(f"plot_result.py: --follow expects seconds > 0, found {args.follow}", file=sys.stderr)
        return 2
    try:
        f = open_result(args.result, swmr=True)
    except OSError:
        try:  # files of result format 4 and older are not SWMR files
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
    if args.follow is not None:
        f.close()
        return follow(args.result, base, args.zoom, args.follow)
    with f:
        _, written = draw(f, base, args.zoom)
    for w in written:
        print(w)
    return 0


if __name__ == "__main__":
    sys.exit(main())
