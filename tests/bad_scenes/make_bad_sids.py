"""Writes the damaged SIDs of the bad scenes sid_nan_mass, sid_inf_mass and sid_nan_phi:
copies of a tiny real SID (a half-disk, 3 x 2 elements of degree 2 x 1, two free-free modes,
no visualisation mesh: 32 kB) with one value made NaN or infinite in place.

usage: /usr/bin/python3 make_bad_sids.py IGAPREP [OUT_DIR]   (default: this folder)

Needs numpy and h5py (Debian python3-numpy, python3-h5py). The files are committed; run this
again only if the SID format changes (then the cases' messages stay as they are).
"""
import os
import shutil
import subprocess
import sys
import tempfile

import h5py
import numpy as np

TINY_BODY = """\
name: tiny
model: axisymmetric
material: {youngs_modulus: 2.11e11, poisson_ratio: 0.3, density: 7850}
geometry: {type: half_disk, radius: 0.01}
refinement: {insert_knots: [1, 1]}
contact: {face: eta_max, region: [[0.0, 0.5]]}
markers: [{name: centre, parameters: [0.0, 0.5]}]
reduction: {method: modal, normal_modes: 2}
visualisation: {subdivisions: 0}
"""

# file -> (dataset, index or None for a scalar, value)
DAMAGE = {
    "sid_nan_mass.sid.h5": ("sid/mass", None, np.nan),
    "sid_inf_mass.sid.h5": ("sid/mass", None, np.inf),
    "sid_nan_phi.sid.h5": ("body/Phi", (5, 1), np.nan),
}


def main():
    igaprep = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) > 2 else os.path.dirname(os.path.abspath(__file__))
    with tempfile.TemporaryDirectory() as tmp:
        body = os.path.join(tmp, "tiny.yaml")
        with open(body, "w") as f:
            f.write(TINY_BODY)
        sid = os.path.join(tmp, "tiny.sid.h5")
        subprocess.run([igaprep, "-q", body, "-o", sid], check=True)
        for name, (dataset, index, value) in DAMAGE.items():
            path = os.path.join(out, name)
            shutil.copyfile(sid, path)
            with h5py.File(path, "r+") as f:
                data = f[dataset]
                if index is None:
                    data[()] = value
                else:
                    data[index] = value
            print("wrote", path)


if __name__ == "__main__":
    main()
