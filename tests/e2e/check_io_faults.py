"""Full disks and file size limits (issue 33), made for real on the Sect. 5 impact
(sphere2d_h3, its flagship scene with frames for ParaView: a result of about 20 MB):

  * ffrsim under a file size limit (RLIMIT_FSIZE, `ulimit -f`, with SIGXFSZ ignored so that
    writes fail with EFBIG) of 30, 55 and 80 % of the uninterrupted result's size, and, when
    the test runs as root and may mount, on a tmpfs of 45 and 70 % of it: exit code 1, one
    line on stderr naming the file and the limit; the file opens with h5py (without SWMR:
    it was closed), its status says `failed at t = ...`, and it holds every row of its last
    flush (as many as the restart record says, at least one flush of 100 rows), equal bit
    for bit to the uninterrupted run's first rows. `ffrsim --restart` without the limit (the
    tmpfs made larger) then ends `completed` with exactly the uninterrupted run's output
    times, its force peak and contact duration within 1e-3 relative (e2e.restart's bound
    for this impact: the runs step differently after the restart; measured ~1e-5) and its
    final state within 1e-4 relative (measured 2e-6: CVODE restarts at order 1).
  * igaprep under a file size limit of 5 MB (the SID has 17 MB) and on a tmpfs of 4 MB:
    exit code 1, one line naming the SID and the reason, no SID and no temporary file left.
No signal ends either program (before issue 33: SIGSEGV at exit, exit code 139).

usage: check_io_faults.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR
"""
import glob
import os
import resource
import shutil
import signal
import subprocess
import sys
import tempfile

import h5py
import numpy as np

from result_checks import Checks

igaprep, ffrsim, source, out = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
check = Checks()
sid = os.path.join(out, "sphere2d_h3.sid.h5")
check.run([igaprep, "-q", os.path.join(source, "configs", "bodies", "sphere2d_h3.yaml"), "-o", sid])
scene = os.path.join(source, "configs", "scenes", "impact2d_h3.yaml")
SERIES = ("time", "contacts/impact/normal_force", "bodies/lower/q", "bodies/upper/qdot",
          "energy/kinetic")


def size_limit(nbytes):
    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (nbytes, nbytes))
    return limit


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


reference = os.path.join(out, "reference.h5")
check.run([ffrsim, "-q", scene, "--sid-path", out, "-o", reference])
ref_size = os.path.getsize(reference)
with h5py.File(reference, "r") as f:
    ref = {k: f[k][()] for k in SERIES}
    ref_state = f["restart/state"][()]
    ref_peak = f.attrs["max_contact_force_N"]
    ref_duration = f.attrs["contact_duration_s"]
print(f"uninterrupted result: {ref_size / 2**20:.1f} MiB, {len(ref['time'])} rows")


def failed_run(result, what, preexec=None):
    """ffrsim stopped by a full disk or a size limit: its exit, message and file."""
    r = subprocess.run([ffrsim, "-q", scene, "--sid-path", out, "-o", result],
                       capture_output=True, text=True, preexec_fn=preexec)
    lines = r.stderr.strip().splitlines()
    check(r.returncode == 1 and len(lines) == 1 and result in lines[0] and what in lines[0],
          f"{os.path.basename(result)}: exit {r.returncode}, {len(lines)} line(s): "
          f"{r.stderr.strip()}")
    try:
        with h5py.File(result, "r") as f:
            status = text(f.attrs["status"])
            rows = {k: f[k][()] for k in SERIES}
            record = int(f["restart"].attrs["rows"])
    except OSError as e:
        check(False, f"{os.path.basename(result)} opens with h5py: {e}")
        return
    n = len(rows["time"])
    check(status.startswith("failed at t = ") and what in status, f"  status '{status}'")
    same = all(np.array_equal(rows[k], ref[k][:n]) for k in SERIES)
    check(n >= 100 and n == record and same,
          f"  {n} rows (restart record: {record}), equal bit for bit to the uninterrupted run's")


def restarted(result, preexec=None):
    r = subprocess.run([ffrsim, "-q", "--restart", result], capture_output=True, text=True,
                       preexec_fn=preexec)
    with h5py.File(result, "r") as f:
        status = text(f.attrs["status"])
        t = f["time"][()]
        state = f["restart/state"][()]
        peak = f.attrs["max_contact_force_N"]
        duration = f.attrs["contact_duration_s"]
    state_error = np.linalg.norm(state - ref_state) / np.linalg.norm(ref_state)
    check(r.returncode == 0 and status == "completed" and np.array_equal(t, ref["time"]),
          f"  restarted: exit {r.returncode}, {status}, {len(t)} rows at the reference's times")
    check(abs(peak / ref_peak - 1) < 1e-3 and abs(duration / ref_duration - 1) < 1e-3
          and state_error < 1e-4,
          f"  force peak {peak / ref_peak - 1:+.2e}, duration {duration / ref_duration - 1:+.2e}, "
          f"final state {state_error:.2e} (relative to the uninterrupted run)")


# File size limits.
for fraction in (0.3, 0.55, 0.8):
    limit = int(fraction * ref_size)
    result = os.path.join(out, f"limit_{int(100 * fraction)}.h5")
    failed_run(result, "file size limit", size_limit(limit))
    restarted(result)

# igaprep under a size limit.
sid_dir = os.path.join(out, "sid_limit")
shutil.rmtree(sid_dir, ignore_errors=True)
os.makedirs(sid_dir)


def igaprep_fails(folder, what, preexec=None):
    target = os.path.join(folder, "sphere2d_h3.sid.h5")
    r = subprocess.run([igaprep, "-q", os.path.join(source, "configs", "bodies", "sphere2d_h3.yaml"),
                        "-o", target], capture_output=True, text=True, preexec_fn=preexec)
    lines = r.stderr.strip().splitlines()
    left = sorted(os.listdir(folder))
    check(r.returncode == 1 and len(lines) == 1 and target in lines[0] and what in lines[0]
          and not left, f"igaprep {what}: exit {r.returncode}, {r.stderr.strip()}; "
          f"left in the folder: {left or 'nothing'}")


igaprep_fails(sid_dir, "File too large", size_limit(5 * 2**20))

# A full tmpfs (root only: the test mounts it).
mount = tempfile.mkdtemp(prefix="tmpfs_", dir=out)
mounted = False
if os.geteuid() == 0:
    m = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=4m", "tmpfs", mount],
                       capture_output=True, text=True)
    mounted = m.returncode == 0
    if not mounted:
        print(f"tmpfs part skipped: mount failed: {m.stderr.strip()}")
else:
    print("tmpfs part skipped: not root")
try:
    if mounted:
        igaprep_fails(mount, "No space left on device")
        for fraction in (0.45, 0.7):
            size_kib = int(fraction * ref_size / 1024)
            subprocess.run(["mount", "-o", f"remount,size={size_kib}k", mount], check=True)
            result = os.path.join(mount, f"tmpfs_{int(100 * fraction)}.h5")
            failed_run(result, "disk full")
            subprocess.run(["mount", "-o", f"remount,size={4 * ref_size // 1024}k", mount],
                           check=True)
            restarted(result)
            for f in glob.glob(os.path.join(mount, "*")):
                os.remove(f)
finally:
    if mounted:
        subprocess.run(["umount", mount])
    os.rmdir(mount)
check.exit()
