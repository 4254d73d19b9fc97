"""benchmarks/plot_result.py turns a real result file (the e2e.impact2d_h3 run's) into its
six PNGs (force against Hertz, energies, penetration, active points, stress lines, contact
pressure), each a
picture that is not blank; a file that is not a result gets exit code 2.

usage: check_plot_result.py SOURCE_DIR RESULT.h5 OUT_DIR
"""
import os
import subprocess
import sys

import matplotlib.image
import numpy as np

from result_checks import Checks

source, result, out = sys.argv[1:4]
check = Checks()
script = os.path.join(source, "benchmarks", "plot_result.py")
r = subprocess.run([sys.executable, script, result, "-o", out, "--zoom"], capture_output=True,
                   text=True)
check(r.returncode == 0, f"plot_result.py exited with {r.returncode} {r.stderr.strip()}")
stem = os.path.splitext(os.path.basename(result))[0]
for kind in ("force", "energy", "penetration", "active_points", "stress_lines", "pressure"):
    png = os.path.join(out, f"{stem}_{kind}.png")
    if not os.path.exists(png):
        check(False, f"{os.path.basename(png)} written")
        continue
    image = matplotlib.image.imread(png)[:, :, :3]
    drawn = 1.0 - np.all(image > 0.99, axis=2).mean()
    check(png in r.stdout and drawn > 0.02, f"{os.path.basename(png)}: {100 * drawn:.1f} % drawn")
bad = subprocess.run([sys.executable, script, os.path.join(source, "tests", "bad_scenes",
                                                           "version_mismatch.sid.h5")],
                     capture_output=True, text=True)
check(bad.returncode == 2 and "not a result file" in bad.stderr,
      f"a SID file is refused: exit {bad.returncode}, {bad.stderr.strip()}")
check.exit()
