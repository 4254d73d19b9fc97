"""Shared pieces of the end-to-end checks: a check list that prints ok / FAIL per item and
the exit code, commands that must succeed, the result file's status as text (h5py may
return bytes), the bodies' rotations and inertial velocities, and the crossings of a level
by a noisy series."""
import subprocess
import sys

import h5py
import numpy as np


class Checks:
    def __init__(self):
        self.failures = []

    def __call__(self, ok, what):
        print(("ok   " if ok else "FAIL ") + what)
        if not ok:
            self.failures.append(what)

    def status_completed(self, f):
        status = f.attrs["status"]
        status = status.decode() if isinstance(status, bytes) else status
        self(status == "completed", f"status {status}")

    def run(self, cmd, **kwargs):
        """Runs `cmd` (a list); if it exits non-zero, prints its output, records the failure
        and exits. Returns the finished process (output captured as text)."""
        r = subprocess.run(cmd, capture_output=True, text=True, **kwargs)
        if r.returncode != 0:
            print(r.stdout + r.stderr)
            self(False, f"{' '.join(cmd)} exited with {r.returncode}")
            self.exit()
        return r

    def exit(self):
        sys.exit(1 if self.failures else 0)


def rotation(q):
    """The rotation matrix of the unit quaternion q = (w, x, y, z) (the result's
    /bodies/<body>/orientation); q of shape (n, 4) gives n matrices (n, 3, 3)."""
    w, x, y, z = np.moveaxis(np.asarray(q, float), -1, 0)
    return np.moveaxis(np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]), (0, 1), (-2, -1))


def inertial_velocity(f, body):
    """The body frame origin's inertial velocity at every row (n, 3), m/s: the result's
    velocity is in body components (schemas/result_format.md), so R(q) v."""
    v = f[f"bodies/{body}/velocity"][:]
    return np.einsum("nij,nj->ni", rotation(f[f"bodies/{body}/orientation"][:]), v)


def restitution(f):
    """Relative velocity along the initial line of centres, after / before, of a result with
    two free bodies (None otherwise, or where they do not approach)."""
    names = list(f["bodies"].keys())
    if len(names) != 2 or "obstacles:" in f.attrs.get("scene_yaml", ""):
        return None
    v = [inertial_velocity(f, b) for b in names]
    p = [f[f"bodies/{b}/position"][0] for b in names]
    n = (p[1] - p[0]) / np.linalg.norm(p[1] - p[0])
    before, after = (v[1][0] - v[0][0]) @ n, (v[1][-1] - v[0][-1]) @ n
    return float(-after / before) if before < 0 else None


def contact_runs(F):
    """(first, last) row indices of each run of rows with F > 0 (a force or a count of
    active points)."""
    on = np.concatenate([[False], np.asarray(F) > 0, [False]]).astype(int)
    starts = np.flatnonzero(np.diff(on) == 1)
    ends = np.flatnonzero(np.diff(on) == -1) - 1
    return list(zip(starts, ends))


def quasi_static_split(f, body, sid_path):
    """A jointed body's coordinates above its quasi-static cutoff: (quasi-static, held
    dynamic by its joints, the SID's modes at or above the cutoff, the cutoff in Hz), from
    the result's /bodies/<body> attributes and the SID's frequencies; the first two add up
    to the third (schemas/multibody.md "Joints and quasi-static coordinates")."""
    a = f[f"bodies/{body}"].attrs
    cutoff = float(a["quasi_static_cutoff_hz"])
    with h5py.File(sid_path, "r") as s:
        above = int(np.count_nonzero(s["sid/frequencies_hz"][:] >= cutoff))
    return int(a["quasi_static_modes"]), int(a["quasi_static_held_by_joints"]), above, cutoff


def sphere_on_rod_figures(sphere_sid, rod_sid, rod_radius):
    """What the one-dimensional sphere-on-rod models need, read from the SIDs: the sphere's
    mass m and radius R, the rod's mass M, density rho, E and nu, its bar speed
    c = sqrt(E / rho), impedance Z = rho c pi a^2, and Hertz's K = 4/3 E* sqrt(R) with
    E* = E / (2 (1 - nu^2)) (sphere and rod of the rod's material)."""
    with h5py.File(sphere_sid, "r") as s:
        m, R = float(s["sid/mass"][()]), float(s["geometry/radius"][()])
    with h5py.File(rod_sid, "r") as s:
        M = float(s["sid/mass"][()])
        rho, E = float(s["material/density"][()]), float(s["material/youngs_modulus"][()])
        nu = float(s["material/poisson_ratio"][()])
    c = np.sqrt(E / rho)
    return dict(m=m, R=R, M=M, rho=rho, E=E, nu=nu, c=c, Z=rho * c * np.pi * rod_radius ** 2,
                K=4.0 / 3.0 * E / (2 * (1 - nu * nu)) * np.sqrt(R))


def moving_mean(t, F, window):
    """F(t) averaged over `window` (s) at every row (rows equally spaced; a centred moving
    mean, which smooths a ringing of that period)."""
    k = max(1, int(round(window / (t[1] - t[0]))))
    return np.convolve(F, np.ones(k) / k, mode="same")


def first_rise(t, F, level, window):
    """The first time F(t), averaged over `window` (moving_mean), rises through `level`,
    linearly interpolated between rows (s)."""
    F = moving_mean(t, F, window)
    i = int(np.argmax(F >= level))
    return t[i - 1] + (level - F[i - 1]) / (F[i] - F[i - 1]) * (t[i] - t[i - 1])


def level_crossings(t, F, level, window):
    """The first time the series F(t), averaged over `window` (s; a moving mean that smooths
    a ringing of that period), rises through `level` and the last time it falls through it,
    linearly interpolated between rows (s)."""
    rise = first_rise(t, F, level, window)
    F = moving_mean(t, F, window)
    above = F >= level
    j = len(F) - 1 - int(np.argmax(above[::-1]))
    fall = t[j] + (F[j] - level) / (F[j] - F[j + 1]) * (t[j + 1] - t[j])
    return rise, fall


def signal_at_fraction(cmd, end_time, fraction, sig):
    """Runs `cmd` (an ffrsim run with -v, so that it prints progress lines), sends `sig` as
    soon as the run has passed `fraction` of `end_time` (a random moment of the run on any
    machine, loaded or not) and waits for it. Returns the exit code and the progress as
    (arrival time, simulated time) pairs, the moment of the signal as (time, None)."""
    import re
    import subprocess
    import threading
    import time

    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    lines = []

    def read():
        sent = False
        for line in proc.stderr:
            m = re.match(r"ffrsim: t = ([0-9.e+-]+) s", line)
            if not m:
                continue
            lines.append((time.monotonic(), float(m.group(1))))
            if not sent and float(m.group(1)) >= fraction * end_time:
                lines.append((time.monotonic(), None))
                proc.send_signal(sig)
                sent = True

    reader = threading.Thread(target=read)
    reader.start()
    rc = proc.wait()
    reader.join()
    return rc, lines


def slow_impact_scene(source, out, flush_interval, progress_interval):
    """The Sect. 5 impact (impact2d_h3 on sphere2d_h3 in OUT) as a ~10 s run: steps limited
    to 6 ns, the result flushed by wall time only (every `flush_interval` s; flush_rows too
    large to matter), progress lines every `progress_interval` s. Returns the scene's path."""
    import os
    with open(os.path.join(source, "configs", "scenes", "impact2d_h3.yaml")) as f:
        text = f.read()
    for old, new in (("  rtol: 1.0e-6", "  rtol: 1.0e-6\n  max_step: 6.0e-9"),
                     ("  flush_rows: 100", f"  flush_rows: 1000000\n  flush_interval: {flush_interval}\n"
                      f"  progress_interval: {progress_interval}")):
        assert old in text, old
        text = text.replace(old, new)
    scene = os.path.join(out, "long.yaml")
    with open(scene, "w") as f:
        f.write(text)
    return scene
