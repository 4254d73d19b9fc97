"""Command-line overrides (issue 14, step 1): `--set KEY=VALUE` on both programs changes the
input as if the file said so, is checked against the schema like the file, is recorded in
the output, and a restart applies it again.

  * igaprep sphere2d_h3 --set material.youngs_modulus=1.0e11: the SID has E = 1e11 Pa and
    its /provenance says which override made it.
  * ffrsim impact2d_h3 --set contacts.0.penalty_factor=1.0e15 --set integrator.end_time=4.0e-5:
    the run stops at 40 us, the pair's penalty factor is 1e15 N/m^3, the result's attribute
    `overrides` lists both; continued with --restart to 60 us, it matches a direct run with
    the same overrides (force history within 1e-3 of its peak; without the overrides the
    softer penalty changes the force by several per cent).
  * Bad overrides: a negative penalty factor (schema), an unknown key, an index past the
    end, a malformed argument, --set with --restart: exit code 2, one line naming the
    override.

usage: check_overrides.py IGAPREP FFRSIM SOURCE_DIR OUT_DIR
"""
import os
import subprocess
import sys

import h5py
import numpy as np

from result_checks import Checks

igaprep, ffrsim, source, out = sys.argv[1:5]
os.makedirs(out, exist_ok=True)
check = Checks()
body = os.path.join(source, "configs", "bodies", "sphere2d_h3.yaml")
scene = os.path.join(source, "configs", "scenes", "impact2d_h3.yaml")


def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True)


# igaprep.
sid = os.path.join(out, "sphere2d_h3.sid.h5")
r = run([igaprep, "-q", body, "--set", "material.youngs_modulus=1.0e11", "-o", sid])
check(r.returncode == 0, f"igaprep --set material.youngs_modulus=1.0e11: exit {r.returncode} "
                         f"{r.stderr.strip()}")
with h5py.File(sid, "r") as f:
    check(f["material/youngs_modulus"][()] == 1.0e11, "the SID's E is 1e11 Pa")
    check(f["provenance"].attrs["overrides"] == "material.youngs_modulus=1.0e11\n",
          "the SID records the override")
# The scene's spheres: the body file as it is.
run([igaprep, "-q", body, "-o", sid])

# ffrsim, a run to 40 us continued to 60 us, against a direct run to 60 us.
sets = ["--set", "contacts.0.penalty_factor=1.0e15", "--set", "integrator.end_time=4.0e-5"]
part = os.path.join(out, "part.h5")
r = run([ffrsim, "-q", scene, "--sid-path", out, "-o", part] + sets)
check(r.returncode == 0, f"ffrsim with two overrides: exit {r.returncode} {r.stderr.strip()}")
with h5py.File(part, "r") as f:
    check(abs(f["time"][-1] - 4.0e-5) < 1e-15, f"the run stops at {1e6 * f['time'][-1]:.3f} us")
    check(f["contacts/impact"].attrs["penalty_factor"] == 1.0e15,
          "the pair's penalty factor is 1e15 N/m^3")
    check(f.attrs["overrides"] == "contacts.0.penalty_factor=1.0e15\nintegrator.end_time=4.0e-5\n",
          "the result records the overrides")
r = run([ffrsim, "-q", "--restart", part, "--end-time", "6.0e-5"])
check(r.returncode == 0, f"restarted to 60 us: exit {r.returncode} {r.stderr.strip()}")
direct = os.path.join(out, "direct.h5")
run([ffrsim, "-q", scene, "--sid-path", out, "-o", direct, "--set",
     "contacts.0.penalty_factor=1.0e15", "--set", "integrator.end_time=6.0e-5"])
plain = os.path.join(out, "plain.h5")
run([ffrsim, "-q", scene, "--sid-path", out, "-o", plain, "--set", "integrator.end_time=6.0e-5"])
with h5py.File(part, "r") as a, h5py.File(direct, "r") as b, h5py.File(plain, "r") as c:
    fa, fb, fc = (x["contacts/impact/normal_force"][()] for x in (a, b, c))
    same = fa.shape == fb.shape and np.abs(fa - fb).max() < 1e-3 * fb.max()
    differs = np.abs(fc - fb).max() / fb.max()
    check(same and differs > 1e-2,
          f"restart with the run's overrides: {len(fa)} rows, force within "
          f"{np.abs(fa - fb).max() / fb.max():.1e} of the direct run (without the override: "
          f"{differs:.1e} apart)")

# Bad overrides.
bad = [
    (["--set", "contacts.0.penalty_factor=-1"],
     "--set 'contacts.0.penalty_factor=-1': key 'contacts[0].penalty_factor'"),
    (["--set", "integrator.bogus=1"], "--set 'integrator.bogus=1': key 'integrator.bogus'"),
    (["--set", "nosuch.key=1"], "--set 'nosuch.key=1': there is no key 'nosuch'"),
    (["--set", "contacts.7.penalty_factor=1"], "'contacts' is a list of 1 items"),
    (["--set", "penalty_factor"], "--set 'penalty_factor': expected KEY=VALUE"),
]
for args, expect in bad:
    r = run([ffrsim, scene, "--sid-path", out, "-o", os.path.join(out, "bad.h5")] + args)
    err = r.stderr.strip()
    check(r.returncode == 2 and expect in err and "\n" not in err,
          f"{' '.join(args)}: exit {r.returncode}: {err}")
r = run([igaprep, body, "--set", "material.poisson_ratio=0.7"])
check(r.returncode == 2 and "--set 'material.poisson_ratio=0.7': key 'material.poisson_ratio'"
      in r.stderr, f"igaprep --set material.poisson_ratio=0.7: exit {r.returncode}: "
                   f"{r.stderr.strip()}")
r = run([ffrsim, "--restart", part, "--set", "integrator.end_time=1e-4"])
check(r.returncode == 2 and "--set goes with a scene file" in r.stderr,
      f"--set with --restart: exit {r.returncode}: {r.stderr.strip()}")
check.exit()
