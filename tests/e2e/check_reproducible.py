"""Same input, same bits (issue 13): igaprep run twice and with 1 and 2 OpenMP threads gives
SID files whose datasets are equal bit for bit, and so does ffrsim on the 2D impact and on a
short 3D impact (whose contact loop runs in parallel: 3D contact sides have more than 128
collocation points). Attributes are compared too, except the measured times.

usage: check_reproducible.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR
"""
import os
import sys

import h5py

from result_checks import Checks
from same_bits import differences

igaprep, ffrsim, source, out = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
check = Checks()


def same_bits(a, b, what, ignore=()):
    n, differ = differences(a, b, ignore)
    check(not differ and n > 0,
          f"{what}: {n} datasets and attributes equal bit for bit"
          + (f"; differ: {', '.join(differ[:8])}" if differ else ""))


# igaprep: an axisymmetric body (2D assembly), the rod (3D, markers) and the 3D sphere
# (CHOLMOD supernodal, hundreds of constraint modes, degenerate eigenspaces of the sphere).
for stem, twice in (("sphere2d_h3", True), ("rod", True), ("sphere3d_coarse", False)):
    body = os.path.join(source, "configs", "bodies", stem + ".yaml")
    runs = [("2", "a"), ("1", "a")] + ([("2", "b")] if twice else [])
    for threads, tag in runs:
        check.run([igaprep, "-q", "--threads", threads, body, "-o",
                   os.path.join(out, f"{stem}_{threads}{tag}.sid.h5")])
    same_bits(os.path.join(out, f"{stem}_2a.sid.h5"), os.path.join(out, f"{stem}_1a.sid.h5"),
              f"igaprep {stem}, 2 threads against 1")
    if twice:
        same_bits(os.path.join(out, f"{stem}_2a.sid.h5"), os.path.join(out, f"{stem}_2b.sid.h5"),
                  f"igaprep {stem}, two runs on 2 threads")

# ffrsim: the scenes find their SID by name in the output folder.
for stem in ("sphere2d_h3", "sphere3d_coarse"):
    os.replace(os.path.join(out, f"{stem}_2a.sid.h5"), os.path.join(out, f"{stem}.sid.h5"))


def scene_copy(name, end_time):
    """The scene with a shorter end time (the 3D run: 10 us of contact, a few seconds)."""
    with open(os.path.join(source, "configs", "scenes", name + ".yaml")) as f:
        text = f.read()
    if end_time:
        assert "end_time: 1.0e-4" in text, name
        text = text.replace("end_time: 1.0e-4", f"end_time: {end_time}")
    path = os.path.join(out, name + ".yaml")
    with open(path, "w") as f:
        f.write(text)
    return path


for scene, end_time, twice in (("impact2d_h3", None, True), ("impact3d_coarse", "1.0e-5", False)):
    path = scene_copy(scene, end_time)
    runs = [("2", "a"), ("1", "a")] + ([("2", "b")] if twice else [])
    for threads, tag in runs:
        check.run([ffrsim, "-q", "--threads", threads, path, "--sid-path", out, "-o",
                   os.path.join(out, f"{scene}_{threads}{tag}.h5")])
    a = os.path.join(out, f"{scene}_2a.h5")
    with h5py.File(a, "r") as f:
        rows = f["time"].shape[0]
        peak = float(f.attrs["max_contact_force_N"])
    check(rows > 10 and peak > 1.0, f"ffrsim {scene}: {rows} rows, contact force up to {peak:.3f} N")
    same_bits(a, os.path.join(out, f"{scene}_1a.h5"), f"ffrsim {scene}, 2 threads against 1")
    if twice:
        same_bits(a, os.path.join(out, f"{scene}_2b.h5"), f"ffrsim {scene}, two runs on 2 threads")

# Flushes (by rows and by wall time) must not change what the file holds at the end: the
# 2D impact flushed after every row against flushed every 100 rows. A flush right after the
# last row once left the restart record with the figures of the step before.
with open(os.path.join(source, "configs", "scenes", "impact2d_h3.yaml")) as f:
    text = f.read()
assert "flush_rows: 100" in text
path = os.path.join(out, "impact2d_h3_flushing.yaml")
with open(path, "w") as f:
    f.write(text.replace("flush_rows: 100", "flush_rows: 1\n  flush_interval: 1.0e-9"))
check.run([ffrsim, "-q", "--threads", "2", path, "--sid-path", out, "-o",
           os.path.join(out, "impact2d_h3_flushing.h5")])
same_bits(os.path.join(out, "impact2d_h3_2a.h5"), os.path.join(out, "impact2d_h3_flushing.h5"),
          "ffrsim impact2d_h3 flushed after every row against every 100 rows",
          ignore=("/@scene_path", "/@scene_yaml"))  # the two scenes differ in their flushes

check.exit()
