#!/usr/bin/python3
"""Reproduces paper Fig. 10: the von Mises stress along the symmetry axis of the Sect. 5
spheres at the moment of maximum contact force, against Hertz's subsurface field (Johnson
eq. 3.72), for the 2D models h3..h6 (and any others named).

For every model it builds the SID (igaprep; the body files name the stress line `axis`),
runs configs/scenes/impact2d_<model>.yaml (ffrsim) and reads everything from the result
file (schemas/result_format.md, /stress_lines): the recovered von Mises stress and Hertz's
field for the contact patch of the simulated force peak. Plotted in Hertz's units (z / a,
sigma / p0), so that the models and Hertz share one picture; the table gives the subsurface
maximum and its depth against Hertz's 0.620 p0 at 0.481 a.

usage: benchmarks/fig10.py [--build build] [--models h3,h4,h5,h6] [--work build/fig10]
                           [--png fig10.png] [--json fig10.json]
"""
import argparse
import json
import os
import subprocess
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"fig10.py: {' '.join(cmd)} failed ({p.returncode}): {p.stderr.strip()}")


def model_run(build, work, model):
    body = os.path.join(ROOT, "configs", "bodies", f"sphere2d_{model}.yaml")
    scene = os.path.join(ROOT, "configs", "scenes", f"impact2d_{model}.yaml")
    sid = os.path.join(work, f"sphere2d_{model}.sid.h5")
    result = os.path.join(work, f"impact2d_{model}.h5")
    run([os.path.join(build, "bin", "igaprep"), "-q", body, "-o", sid])
    run([os.path.join(build, "bin", "ffrsim"), "-q", scene, "--sid-path", work, "-o", result])
    with h5py.File(result, "r") as f, h5py.File(sid, "r") as s:
        g = f["stress_lines/lower/axis"]
        a = g.attrs
        p0, r = float(a["hertz_max_pressure_Pa"]), float(a["hertz_contact_radius_m"])
        return {
            "model": model,
            "ndof": int(s.attrs["ndof"]),
            "nq": int(s.attrs["nq"]),
            "force_vs_hertz_pct": 100 * float(f.attrs["force_vs_hertz"]),
            "peak_time_s": float(f["stress_lines"].attrs["time_s"]),
            "contact_radius_m": r,
            "max_pressure_Pa": p0,
            "von_mises_max_over_p0": float(a["von_mises_interior_max_Pa"]) / p0,
            "depth_over_a": float(a["von_mises_interior_max_distance_m"]) / r,
            "von_mises_vs_hertz_pct": 100 * (float(a["von_mises_interior_max_Pa"])
                                             / float(a["hertz_von_mises_max_Pa"]) - 1),
            "depth_vs_hertz_pct": 100 * (float(a["von_mises_interior_max_distance_m"])
                                         / float(a["hertz_von_mises_max_depth_m"]) - 1),
            "surface_von_mises_over_p0": float(g["von_mises"][0]) / p0,
            "z_over_a": (g["distance"][:] / r).tolist(),
            "von_mises_over_p0": (g["von_mises"][:] / p0).tolist(),
            "hertz_over_p0": (g["hertz_von_mises"][:] / p0).tolist(),
        }


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--models", default="h3,h4,h5,h6")
    p.add_argument("--work", default=os.path.join(ROOT, "build", "fig10"),
                   help="folder for the SID and result files (kept)")
    p.add_argument("--png", default="fig10.png")
    p.add_argument("--json")
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    rows = [model_run(args.build, args.work, m) for m in args.models.split(",")]
    print(f"{'model':6} {'ndof':>6} {'nq':>4} {'F vs Hertz':>10} {'max vM/p0':>9} "
          f"{'vs Hertz':>8} {'z/a':>6} {'vs Hertz':>8} {'surface':>8}")
    for r in rows:
        print(f"{r['model']:6} {r['ndof']:6d} {r['nq']:4d} {r['force_vs_hertz_pct']:+9.2f}% "
              f"{r['von_mises_max_over_p0']:9.4f} {r['von_mises_vs_hertz_pct']:+7.2f}% "
              f"{r['depth_over_a']:6.3f} {r['depth_vs_hertz_pct']:+7.2f}% "
              f"{r['surface_von_mises_over_p0']:8.3f}")
    print("Hertz (nu = 0.3): maximum 0.6200 p0 at z = 0.4809 a; 0.200 p0 at the surface")
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for r in rows:
        ax.plot(r["z_over_a"], r["von_mises_over_p0"],
                label=f"{r['model']}: max {r['von_mises_max_over_p0']:.4f} p0 "
                      f"at {r['depth_over_a']:.3f} a")
    ax.plot(rows[0]["z_over_a"], rows[0]["hertz_over_p0"], "k--", lw=1.2,
            label="Hertz (Johnson eq. 3.72): 0.620 p0 at 0.481 a")
    ax.set_xlabel("depth below the contact point z / a")
    ax.set_ylabel("von Mises stress / p0")
    ax.set_title("Fig. 10: von Mises stress on the symmetry axis at maximum force", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.png, dpi=120)
    print(f"wrote {args.png}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f)
        print(f"wrote {args.json}")


if __name__ == "__main__":
    main()
