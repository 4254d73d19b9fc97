"""Wrong physics never ends as `completed` (issue 13), on the Sect. 5 scene (sphere2d_h3):
  * bodies placed into each other (5 mm, 10 um, coincident centres) are refused before the
    run (exit 2) with the depth in the message;
  * an impact at 1 m/s each, whose contact grows beyond the contact region of sphere2d_h3
    (Hertz contact radius ~0.28 mm against a region of 0.32 mm), stops with exit code 1 and
    a status that says the penetration beyond the edge, the rows so far readable.

usage: check_wrong_physics.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR
"""
import os
import re
import subprocess
import sys

import h5py

from result_checks import Checks

igaprep, ffrsim, source, out = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
check = Checks()
subprocess.run([igaprep, "-q", os.path.join(source, "configs", "bodies", "sphere2d_h3.yaml"),
                "-o", os.path.join(out, "sphere2d_h3.sid.h5")], check=True)
with open(os.path.join(source, "configs", "scenes", "impact2d_h3.yaml")) as f:
    base = f.read()


def scene(name, old, new):
    assert old in base, old
    path = os.path.join(out, name + ".yaml")
    with open(path, "w") as f:
        f.write(base.replace(old, new))
    return path


def run(path, result):
    if os.path.exists(result):
        os.remove(result)
    r = subprocess.run([ffrsim, "-q", path, "-o", result], capture_output=True, text=True)
    return r.returncode, r.stderr.strip()


# The upper sphere's centre at y = 0.02 m touches the lower one (r = 1 cm).
for name, y, depth in (("overlap_5mm", "0.015", 5e-3), ("overlap_10um", "0.01999", 1e-5),
                       ("coincident", "0.0", 2e-2)):
    path = scene(name, "position: [0, 0.02, 0]", f"position: [0, {y}, 0]")
    result = os.path.join(out, name + ".h5")
    rc, err = run(path, result)
    m = re.search(r"start ([0-9.e+-]+) m into each other", err)
    found = float(m.group(1)) if m else float("nan")
    check(rc == 2 and f"{name}.yaml:" in err and "key 'contacts[0]'" in err and
          abs(found / depth - 1.0) < 0.01 and not os.path.exists(result),
          f"{name}: exit {rc}, depth {found:.4g} m (placed {depth:g} m), no result file: {err}")

path = scene("fast", "velocity: [0, 0.1, 0]", "velocity: [0, 1.0, 0]")
with open(path) as f:
    text = f.read().replace("velocity: [0, -0.1, 0]", "velocity: [0, -1.0, 0]")
with open(path, "w") as f:
    f.write(text)
result = os.path.join(out, "fast.h5")
rc, err = run(path, result)
with h5py.File(result, "r") as f:
    status = f.attrs["status"]
    status = status.decode() if isinstance(status, bytes) else status
    rows = f["time"].shape[0]
check(rc == 1 and "beyond the edge of a contact surface" in err,
      f"fast impact: exit {rc}, message: {err}")
check(status.startswith("failed at t = ") and "beyond the edge" in status and rows > 10,
      f"fast impact: result readable, {rows} rows, status '{status[:90]}...'")
check.exit()
