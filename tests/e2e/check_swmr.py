"""Reading a running result (issue 33): ffrsim writes its result in HDF5's single-writer/
multiple-reader mode. On a ~10 s run of the Sect. 5 impact (sphere2d_h3 with steps limited
to 6 ns, flushed every 0.5 s of wall time):

  * a reader opens the running file with h5py's swmr=True twenty times, at random moments
    between 5 and 90 % of the run (told by its progress lines): never an error, status
    `running`, the output times never fewer than at the poll before and growing over the
    polls, and every poll's rows a prefix of the finished file's, bit for bit;
  * the README's way of looking at it, `benchmarks/plot_result.py RESULT.h5 --follow 1`,
    started with the run: it redraws while the run goes (at least three times with status
    `running`), stops by itself once the status is `completed`, exit code 0, and leaves
    the six pictures;
  * while it runs, a second ffrsim is refused (exit code 2, naming the process that writes
    the file): `--restart` of the running file and `-o` onto it (the writer lock: HDF5
    gives its own lock up in SWMR mode);
  * the finished file opens without SWMR too.
The random moments are printed (seeded from the clock).

usage: check_swmr.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR
"""
import os
import random
import re
import subprocess
import sys
import threading
import time

import h5py
import numpy as np

from result_checks import Checks, slow_impact_scene

igaprep, ffrsim, source, out = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
check = Checks()
END = 1e-4
check.run([igaprep, "-q", os.path.join(source, "configs", "bodies", "sphere2d_h3.yaml"),
           "-o", os.path.join(out, "sphere2d_h3.sid.h5")])
scene = slow_impact_scene(source, out, 0.5, 0.05)
result = os.path.join(out, "watched.h5")
if os.path.exists(result):
    os.remove(result)

seed = int(time.time())
rng = random.Random(seed)
moments = sorted(rng.uniform(0.05, 0.9) for _ in range(20))
print(f"random moments from seed {seed}: " + ", ".join(f"{100 * m:.0f} %" for m in moments))

run = subprocess.Popen([ffrsim, "-v", scene, "-o", result], stdout=subprocess.DEVNULL,
                       stderr=subprocess.PIPE, text=True)
progress = [0.0]


def read_progress():
    for line in run.stderr:
        m = re.match(r"ffrsim: t = ([0-9.e+-]+) s", line)
        if m:
            progress[0] = float(m.group(1))


reader = threading.Thread(target=read_progress)
reader.start()
while not os.path.exists(result):
    time.sleep(0.01)
plots = os.path.join(out, "plots")
follow = subprocess.Popen([sys.executable, os.path.join(source, "benchmarks", "plot_result.py"),
                           result, "-o", plots, "--follow", "1"],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)

polls, errors, second = [], [], []
for m in moments:
    while progress[0] < m * END and run.poll() is None:
        time.sleep(0.005)
    if run.poll() is not None:
        break
    try:
        with h5py.File(result, "r", swmr=True) as f:
            status = f.attrs["status"]
            polls.append((status.decode() if isinstance(status, bytes) else status,
                          f["time"][()], f["contacts/impact/normal_force"][()]))
    except Exception as e:  # noqa: BLE001 (any error is the failure)
        errors.append(f"at {100 * m:.0f} %: {e}")
    if not second:  # a second writer, once
        for cmd in ([ffrsim, "-q", "--restart", result], [ffrsim, "-q", scene, "-o", result]):
            r = subprocess.run(cmd, capture_output=True, text=True)
            second.append((cmd[2], r.returncode, r.stderr.strip()))
rc = run.wait()
reader.join()
try:
    follow_out, follow_err = follow.communicate(timeout=60)
except subprocess.TimeoutExpired:
    follow.kill()
    follow_out, follow_err = follow.communicate()
    follow_err += " (killed: still running 60 s after the run)"
check(rc == 0, f"the watched run: exit {rc}")
check(len(polls) == 20 and not errors,
      f"{len(polls)} polls with swmr=True while the run went, errors: {errors or 'none'}")
for option, rc2, message in second:
    check(rc2 == 2 and f"process {run.pid}" in message and "being written" in message,
          f"a second ffrsim ({option}) while the run goes: exit {rc2}, {message}")
check(len(second) == 2, "both second writers tried")
with h5py.File(result, "r") as f:  # the finished file: no SWMR needed
    final_status = f.attrs["status"]
    final_t = f["time"][()]
    final_f = f["contacts/impact/normal_force"][()]
counts = [len(t) for _, t, _ in polls]
check(all(s == "running" for s, _, _ in polls), "every poll: status running")
check(all(a <= b for a, b in zip(counts, counts[1:])) and counts and counts[-1] > counts[0],
      f"output times never fewer, growing over the polls: {counts}")
prefix = all(np.array_equal(t, final_t[:len(t)]) and np.array_equal(fn, final_f[:len(fn)])
             for _, t, fn in polls)
check(prefix, "every poll's rows are a prefix of the finished file's, bit for bit")
check(final_status == "completed" and len(final_t) == 1001,
      f"the finished file opens without SWMR: {final_status}, {len(final_t)} rows")
running = [l for l in follow_out.splitlines() if l.startswith("running:")]
done = [l for l in follow_out.splitlines() if l.startswith("completed:")]
pngs = [p for p in follow_out.splitlines() if p.endswith(".png") and os.path.exists(p)]
check(follow.returncode == 0 and len(running) >= 3 and len(done) == 1 and len(pngs) == 6,
      f"plot_result.py --follow: exit {follow.returncode}, {len(running)} redraws while running, "
      f"then '{done[0] if done else follow_err.strip()}', {len(pngs)} pictures")
check.exit()
