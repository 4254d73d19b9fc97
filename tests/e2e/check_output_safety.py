"""Inputs are never overwritten and outputs are checked before any work (issue 13): for both
programs, -o onto an input (the same path, another spelling, a symbolic link), into a folder
that does not exist, or onto a folder is refused with exit code 2 and one line naming -o and
the path, and the input is left byte for byte as it was; igaprep refuses a body whose size
estimate exceeds --max-memory.

usage: check_output_safety.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR
"""
import os
import shutil
import subprocess
import sys

from result_checks import Checks

igaprep, ffrsim, source, out = sys.argv[1:5]
shutil.rmtree(out, ignore_errors=True)
os.makedirs(out)
os.chdir(out)
check = Checks()
shutil.copy(os.path.join(source, "configs", "bodies", "sphere2d_h3.yaml"), "body.yaml")
shutil.copy(os.path.join(source, "configs", "scenes", "impact2d_h3.yaml"), "scene.yaml")
subprocess.run([igaprep, "-q", "body.yaml", "-o", "sphere2d_h3.sid.h5"], check=True)
os.symlink("scene.yaml", "link_to_scene.yaml")
os.symlink("sphere2d_h3.sid.h5", "link_to_sid.h5")


def snapshot():
    files = ("body.yaml", "scene.yaml", "sphere2d_h3.sid.h5")
    return {f: (open(f, "rb").read(), os.stat(f).st_mtime_ns) for f in files}


def refused(cmd, expected, what):
    before = snapshot()
    r = subprocess.run(cmd, capture_output=True, text=True)
    err = r.stderr.strip()
    check(r.returncode == 2 and expected in err and "\n" not in err and snapshot() == before,
          f"{what}: exit {r.returncode}, inputs unchanged: {err}")


refused([ffrsim, "scene.yaml", "-o", "scene.yaml"], "-o scene.yaml is the scene file",
        "ffrsim -o onto its scene")
refused([ffrsim, "scene.yaml", "-o", "./../" + os.path.basename(out) + "/scene.yaml"],
        "is the scene file", "ffrsim -o onto its scene, another spelling")
refused([ffrsim, "scene.yaml", "-o", "link_to_scene.yaml"], "is the scene file",
        "ffrsim -o onto a link to its scene")
refused([ffrsim, "scene.yaml", "-o", "sphere2d_h3.sid.h5"],
        "-o sphere2d_h3.sid.h5 is a SID file of the scene", "ffrsim -o onto its SID")
refused([ffrsim, "scene.yaml", "-o", "link_to_sid.h5"], "is a SID file of the scene",
        "ffrsim -o onto a link to its SID")
refused([ffrsim, "scene.yaml", "-o", "missing/result.h5"], "the folder 'missing' does not exist",
        "ffrsim -o into a missing folder")
refused([ffrsim, "scene.yaml", "-o", "."], "is a folder", "ffrsim -o onto a folder")
refused([igaprep, "body.yaml", "-o", "body.yaml"], "-o body.yaml is the body file",
        "igaprep -o onto its body file")
refused([igaprep, "body.yaml", "-o", "missing/body.sid.h5"], "the folder 'missing' does not exist",
        "igaprep -o into a missing folder")
refused([igaprep, "body.yaml", "-o", "."], "is a folder", "igaprep -o onto a folder")
# The size limit: sphere2d_h3 needs ~0.01 GiB by the estimate (preproc/geometry/size_estimate.h).
refused([igaprep, "body.yaml", "--max-memory", "0.001", "-o", "small.sid.h5"],
        "key 'refinement': the refined body has", "igaprep over --max-memory")
refused([igaprep, "body.yaml", "--max-memory", "lots", "-o", "small.sid.h5"],
        "--max-memory expects a number of GiB > 0", "igaprep --max-memory not a number")
r = subprocess.run([igaprep, "-q", "body.yaml", "--max-memory", "1", "-o", "ok.sid.h5"])
check(r.returncode == 0 and os.path.exists("ok.sid.h5"), "igaprep within --max-memory 1 GiB")
check.exit()
