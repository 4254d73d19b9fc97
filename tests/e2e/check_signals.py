"""Batch-scheduler signals (issue 13), on a ~10 s run of the Sect. 5 impact (sphere2d_h3 with
steps limited to 6 ns; the result flushed by wall time only: flush_interval 1 s, flush_rows
too large to matter):
  * SIGTERM and SIGHUP at a random moment (a random fraction of the run, told by its
    progress lines, so that the moment is inside the run on any machine): exit code 1, the file opens, its status says
    which signal and when, and it holds every row up to then, equal bit for bit to the rows
    of the uninterrupted run (same input, same bits);
  * SIGKILL at a random moment: the file opens with SWMR (h5py's swmr=True; status still
    `running`), its rows are a prefix of the uninterrupted run's, and it holds every row that
    had been computed one flush interval (plus 0.5 s of margin for a slow step) before the
    kill, as told by the progress lines on stderr; a reader without SWMR is refused with
    HDF5's "already open for write" (the mark of a file killed in SWMR mode, README);
    `plot_result.py --follow` on it draws its last flush and stops by itself (exit code 1:
    no ffrsim writes it any more);
  * SIGTERM while loading (sent before ffrsim starts, with the signal blocked by the
    launcher: it is pending until ffrsim installs its handler): exit code 1 and a message.
The random moments are printed (seeded from the clock).

usage: check_signals.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR
"""
import os
import random
import re
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

from result_checks import Checks, signal_at_fraction, slow_impact_scene

igaprep, ffrsim, source, out = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
check = Checks()
FLUSH_INTERVAL = 1.0
subprocess.run([igaprep, "-q", os.path.join(source, "configs", "bodies", "sphere2d_h3.yaml"),
                "-o", os.path.join(out, "sphere2d_h3.sid.h5")], check=True)
scene = slow_impact_scene(source, out, FLUSH_INTERVAL, 0.1)


def rows_of(path, swmr=False):
    with h5py.File(path, "r", swmr=swmr) as f:
        status = f.attrs["status"]
        status = status.decode() if isinstance(status, bytes) else status
        return status, f["time"][()], f["contacts/impact/normal_force"][()]


def start(result, preexec=None):
    return subprocess.Popen([ffrsim, "-v", scene, "-o", result], stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True, preexec_fn=preexec)


# The uninterrupted reference.
t0 = time.monotonic()
ref = os.path.join(out, "reference.h5")
r = subprocess.run([ffrsim, "-q", scene, "-o", ref])
wall = time.monotonic() - t0
status, ref_t, ref_f = rows_of(ref)
check(r.returncode == 0 and status == "completed" and len(ref_t) == 1001,
      f"reference: {status}, {len(ref_t)} rows in {wall:.1f} s")
seed = int(time.time())
rng = random.Random(seed)
print(f"random moments from seed {seed}")


def prefix_of_reference(t, f, what):
    n = len(t)
    same = n <= len(ref_t) and np.array_equal(t, ref_t[:n]) and np.array_equal(f, ref_f[:n])
    check(same, f"{what}: its {n} rows equal the reference's first {n}, bit for bit")


for sig in (signal.SIGTERM, signal.SIGHUP, signal.SIGKILL):
    name = signal.Signals(sig).name
    result = os.path.join(out, f"{name}.h5")
    fraction = rng.uniform(0.4 if sig == signal.SIGKILL else 0.1, 0.8)  # a kill after > 3 s
    rc, lines = signal_at_fraction([ffrsim, "-v", scene, "-o", result], 1e-4, fraction, sig)
    status, t, f = rows_of(result, swmr=sig == signal.SIGKILL)
    moment = f"at {100 * fraction:.0f} % of the run"
    if sig != signal.SIGKILL:
        m = re.match(rf"interrupted by {name} at t = ([0-9.e+-]+) s", status)
        t_stop = float(m.group(1)) if m else -1.0
        expected = int(np.floor(t_stop / 1e-7 * (1 + 1e-12))) + 1 if m else -1
        check(rc == 1 and m is not None, f"{name} {moment}: exit {rc}, status '{status}'")
        check(len(t) == expected and t[-1] <= t_stop,
              f"{name}: {len(t)} rows, every output up to t = {t_stop:.6g} s ({expected})")
    else:
        # Nothing can be done at a kill; what was flushed must be readable: every row older
        # than the flush interval (plus 0.5 s of margin for a slow step) at the kill.
        killed_at = next(arrival for arrival, sim in lines if sim is None)
        older = [sim for arrival, sim in lines
                 if sim is not None and arrival <= killed_at - FLUSH_INTERVAL - 0.5]
        needed = max(older) if older else 0.0
        check(status == "running" and needed > 0.0 and t[-1] >= needed * (1 - 1e-12),
              f"SIGKILL {moment}: status '{status}', {len(t)} rows up to t = {t[-1]:.6g} s, at "
              f"least up to {needed:.6g} s (computed {FLUSH_INTERVAL} + 0.5 s before the kill)")
    prefix_of_reference(t, f, name)
    if sig == signal.SIGKILL:
        try:
            h5py.File(result, "r").close()
            refused = "opened"
        except OSError as e:
            refused = str(e)
        check("already open for write" in refused,
              f"SIGKILL: a reader without SWMR is refused: {refused}")
        # Following the killed run's file stops by itself: no ffrsim writes it.
        plots = os.path.join(out, "killed_plots")
        r = subprocess.run([sys.executable, os.path.join(source, "benchmarks", "plot_result.py"),
                            result, "-o", plots, "--follow", "0.2"], capture_output=True,
                           text=True, timeout=60)
        check(r.returncode == 1 and "no ffrsim writes it" in r.stderr
              and os.path.exists(os.path.join(plots, "SIGKILL_force.png")),
              f"SIGKILL: plot_result.py --follow stops: exit {r.returncode}, {r.stderr.strip()}")


# SIGTERM before ffrsim runs: blocked by the launcher, pending, delivered at the handler.
def block_sigterm():
    signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGTERM})


result = os.path.join(out, "loading.h5")
proc = start(result, preexec=block_sigterm)
proc.send_signal(signal.SIGTERM)
err = proc.stderr.read()
rc = proc.wait()
check(rc == 1 and "interrupted by SIGTERM while loading the scene" in err
      and not os.path.exists(result), f"SIGTERM while loading: exit {rc}, {err.strip()}")
check.exit()
