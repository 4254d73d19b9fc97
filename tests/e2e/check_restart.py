"""Restart (issue 13): `ffrsim --restart RESULT.h5` continues a run from the restart record of
its file (the state at the last row on disk) and appends to the same file.

  1. The rigid double pendulums of Sect. 7 (Hertz point contact), tolerances tightened to
     rtol 1e-11 and steps limited to 2 us (a run of several seconds), stopped by SIGTERM at a
     random moment and restarted: the final state equals the uninterrupted run's within 1e-8
     relative (2-norm of the state vector; measured 3e-11 to 3e-9: CVODE restarts at order 1,
     so the two runs differ by their integration errors, ~rtol times a growth factor), the force
     history within 1e-8 of its peak, and the output times are exactly the reference's (no
     gap, no duplicate row, the contact rows of contact_output_interval included).
  2. The Sect. 5 impact (sphere2d_h3, default tolerances rtol 1e-6) killed by SIGKILL at a
     random moment and restarted: rows before the record bit for bit the reference's, the
     same output times, force peak and contact duration within 1e-3 relative (measured
     1e-5: the peak is the largest force over the steps, and the runs step differently after
     the restart; 1e-3 is 3 times below the 0.3 % the Sect. 5 acceptance asks).
     The pair's pressure field at its force peak (/contacts/impact/peak_pressure) is that
     of the restarted file's own force peak (time and force the root's) and within 1e-3 of
     the reference's peak pressure at every point (as the force peak).
  3. A finished run continued with --end-time: rows appended after the old end, status
     completed, end_time_s updated, the pressure field at the force peak kept bit for bit
     (no larger force after the contact); a finished run without --end-time, a file that is
     not a result and --restart with -o are refused with exit code 2.

usage: check_restart.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR
"""
import os
import random
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

from result_checks import Checks, signal_at_fraction

igaprep, ffrsim, source, out = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
check = Checks()
seed = int(time.time())
rng = random.Random(seed)
print(f"random moments from seed {seed}")


def text_of(name, replacements):
    with open(os.path.join(source, "configs", "scenes", name + ".yaml")) as f:
        text = f.read()
    for old, new in replacements:
        assert old in text, old
        text = text.replace(old, new)
    path = os.path.join(out, name + "_restart.yaml")
    with open(path, "w") as f:
        f.write(text)
    return path


def attr(f, name):
    v = f.attrs[name]
    return v.decode() if isinstance(v, bytes) else v


def reference(scene, result):
    if os.path.exists(result):
        os.remove(result)
    t0 = time.monotonic()
    subprocess.run([ffrsim, "-q", scene, "-o", result], check=True)
    return time.monotonic() - t0


def interrupted(scene, result, end_time, fraction, sig):
    if os.path.exists(result):
        os.remove(result)
    signal_at_fraction([ffrsim, "-v", scene, "-o", result], end_time, fraction, sig)
    # A killed run's file keeps HDF5's "open for writing" mark: read with SWMR.
    with h5py.File(result, "r", swmr=sig == signal.SIGKILL) as f:
        return attr(f, "status"), float(f["restart"].attrs["time_s"])


def restart(result, *extra):
    return subprocess.run([ffrsim, "-q", "--restart", result, *extra], capture_output=True,
                          text=True)


# 1. Rigid pendulums, tight tolerances, SIGTERM.
scene = text_of("pendulums_rigid", [
    ("rtol: 1.0e-8", "rtol: 1.0e-11\n  max_step: 2.0e-6"),
    ("atol_position: 1.0e-12", "atol_position: 1.0e-15"),
    ("atol_velocity: 1.0e-9", "atol_velocity: 1.0e-12"),
    ("atol_rotation: 1.0e-11", "atol_rotation: 1.0e-14"),
    ("atol_angular_velocity: 1.0e-8", "atol_angular_velocity: 1.0e-11"),
    ("outputs:", "outputs:\n  progress_interval: 0.05")])
ref = os.path.join(out, "pendulums_reference.h5")
reference(scene, ref)
part = os.path.join(out, "pendulums_restarted.h5")
fraction = rng.uniform(0.1, 0.8)
status, t_record = interrupted(scene, part, 0.175, fraction, signal.SIGTERM)
r = restart(part)
with h5py.File(ref, "r") as a, h5py.File(part, "r") as b:
    ya, yb = a["restart/state"][()], b["restart/state"][()]
    ta, tb = a["time"][()], b["time"][()]
    fa = a["force_elements/impact/tension"][()]
    fb = b["force_elements/impact/tension"][()]
    rel = np.linalg.norm(ya - yb) / np.linalg.norm(ya)
    force = np.max(np.abs(fa - fb)) / np.max(np.abs(fa))
    check(r.returncode == 0 and attr(b, "status") == "completed" and b.attrs["restarts"] == 1,
          f"pendulums: {status} at {100 * fraction:.0f} % of the run (record at t = {t_record:.6g} s), restarted: "
          f"{attr(b, 'status')}")
    check(np.array_equal(ta, tb) and np.all(np.diff(tb) > 0),
          f"pendulums: {len(tb)} rows at exactly the reference's times (no gap, no duplicate)")
    check(rel < 1e-8, f"pendulums: final state within {rel:.2e} relative of the uninterrupted run")
    check(force < 1e-8, f"pendulums: force history within {force:.2e} of its peak")

# 2. The Sect. 5 impact, SIGKILL (the record is what the last flush left), with its
#    visualisation frames.
subprocess.run([igaprep, "-q", os.path.join(source, "configs", "bodies", "sphere2d_h3.yaml"),
                "-o", os.path.join(out, "sphere2d_h3.sid.h5")], check=True)
scene = text_of("impact2d_h3", [("flush_rows: 100", "flush_rows: 50\n  flush_interval: 0.2\n"
                                                   "  progress_interval: 0.05")])
ref = os.path.join(out, "impact_reference.h5")
reference(scene, ref)
part = os.path.join(out, "impact_restarted.h5")
fraction = rng.uniform(0.3, 0.8)
status, t_record = interrupted(scene, part, 1e-4, fraction, signal.SIGKILL)
with h5py.File(part, "r", swmr=True) as f:
    rows_before = int(f["restart"].attrs["rows"])
r = restart(part)  # clears the mark (no ffrsim holds the writer lock any more)
with h5py.File(ref, "r") as a, h5py.File(part, "r") as b:
    ta, tb = a["time"][()], b["time"][()]
    fa = a["contacts/impact/normal_force"][()]
    fb = b["contacts/impact/normal_force"][()]
    same_prefix = np.array_equal(fa[:rows_before], fb[:rows_before])
    peak = b.attrs["max_contact_force_N"] / a.attrs["max_contact_force_N"] - 1.0
    da = a.attrs["contact_end_s"] - a.attrs["contact_begin_s"]
    db = b.attrs["contact_end_s"] - b.attrs["contact_begin_s"]
    check(r.returncode == 0 and attr(b, "status") == "completed",
          f"impact: '{status}' killed at {100 * fraction:.0f} % of the run, record at t = {t_record:.6g} s "
          f"({rows_before} rows), restarted: {attr(b, 'status')}")
    check(np.array_equal(ta, tb) and same_prefix,
          f"impact: {len(tb)} rows at the reference's times, the first {rows_before} bit for bit")
    check(abs(peak) < 1e-3 and abs(db / da - 1.0) < 1e-3,
          f"impact: force peak {peak:+.2e}, contact duration {db / da - 1.0:+.2e} relative to the "
          f"uninterrupted run")
    ga, gb = a["contacts/impact/peak_pressure"], b["contacts/impact/peak_pressure"]
    dp = np.max(np.abs(ga["pressure"][()] - gb["pressure"][()])) / np.max(ga["pressure"][()])
    check(gb.attrs["normal_force_N"] == b.attrs["max_contact_force_N"]
          and gb.attrs["time_s"] == b.attrs["max_contact_force_time_s"] and dp < 1e-3,
          f"impact: pressure field at the restarted run's own force peak, within {dp:.1e} of the "
          f"reference's peak pressure")
    # Visualisation frames (issue 12): the frames after the record were dropped and written
    # again, the ones before kept bit for bit; the XDMF file names every frame.
    fa_t, fb_t = a["visualisation/time"][()], b["visualisation/time"][()]
    kept = int(np.sum(fa_t <= t_record))
    pa, pb = a["visualisation/lower/points"], b["visualisation/lower/points"]
    check(np.array_equal(fa_t, fb_t) and np.array_equal(pa[:kept], pb[:kept]),
          f"impact: {len(fb_t)} frames at the reference's times, the first {kept} bit for bit")
    with open(part[:-3] + ".xdmf") as x:
        n_frames = x.read().count("<Time Value=")
    check(n_frames == len(fb_t), f"impact: the XDMF file names {n_frames} frames")

# 3. Continue a finished run; refusals.
with h5py.File(ref, "r") as f:
    g = f["contacts/impact/peak_pressure"]
    field = {k: g[k][()] for k in g} | dict(g.attrs)
r = restart(ref, "--end-time", "1.5e-4")
with h5py.File(ref, "r") as f:
    g = f["contacts/impact/peak_pressure"]
    after = {k: g[k][()] for k in g} | dict(g.attrs)
    check(field.keys() == after.keys()
          and all(np.array_equal(field[k], after[k]) for k in field),
          "finished run continued: the pressure field at the force peak kept bit for bit")
    t = f["time"][()]
    check(r.returncode == 0 and attr(f, "status") == "completed" and abs(t[-1] - 1.5e-4) < 1e-15
          and len(t) == 1501 and np.all(np.diff(t) > 0) and f.attrs["end_time_s"] == 1.5e-4,
          f"finished run continued to 1.5e-4 s: {len(t)} rows, status {attr(f, 'status')}")
r = restart(ref)
check(r.returncode == 2 and "nothing to continue" in r.stderr,
      f"finished run without --end-time: exit {r.returncode}: {r.stderr.strip()}")
r = restart(os.path.join(out, "sphere2d_h3.sid.h5"))
check(r.returncode == 2 and "not a result file" in r.stderr,
      f"a SID file: exit {r.returncode}: {r.stderr.strip()}")
r = subprocess.run([ffrsim, "--restart", ref, "-o", part], capture_output=True, text=True)
check(r.returncode == 2 and "--restart takes the result file only" in r.stderr,
      f"--restart with -o: exit {r.returncode}: {r.stderr.strip()}")
check.exit()
