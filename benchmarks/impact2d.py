#!/usr/bin/python3
"""Reproduces paper Sect. 5 (two axisymmetric steel spheres, 0.1 m/s each, 0.1 ms).

For every 2D model (configs/scenes/impact2d_{h,g}{3..6}.yaml) it builds the SID file with
igaprep, runs ffrsim --repeat times and prints: maximum contact force and contact duration
against Hertz (the result file's attributes, computed by ffrsim from common/hertz.h), and the median wall time
of the time integration (root attribute wall_time_s) with the hierarchical/global ratio
(paper Fig. 9). --sweep runs the penalty-factor sweep of Fig. 7 on one model; --plot writes
the force history against Hertz (Fig. 8) as a PNG.

usage: benchmarks/impact2d.py [--build build] [--repeat 3] [--models h3,g3,...]
                              [--sweep h3] [--plot out.png] [--json out.json]
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile

import h5py
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run_scene(build, scene, sid_dir, out, penalty=None):
    path = scene
    if penalty is not None:
        text = open(scene).read()
        text = re.sub(r"penalty_factor: .*", f"penalty_factor: {penalty:.6g}", text)
        fd, path = tempfile.mkstemp(suffix=".yaml", dir=sid_dir)
        with os.fdopen(fd, "w") as f:
            f.write(text)
    p = subprocess.run([os.path.join(build, "bin", "ffrsim"), path, "--sid-path", sid_dir,
                        "-o", out], capture_output=True, text=True)
    if p.returncode != 0:
        return {"error": p.stderr.strip()}
    r = {}
    with h5py.File(out, "r") as f:  # the result file's headline attributes (format 4)
        a = f.attrs
        if "hertz_max_force_N" in a:
            r["hertz_force_N"] = float(a["hertz_max_force_N"])
            r["hertz_duration_us"] = 1e6 * float(a["hertz_duration_s"])
            r["force_error_pct"] = 100 * float(a["force_vs_hertz"])
            if "duration_vs_hertz" in a:
                r["duration_error_pct"] = 100 * float(a["duration_vs_hertz"])
        r["wall_time_s"] = float(a["wall_time_s"])
        pair = list(f["contacts"].keys())[0]
        r["time"] = f["time"][:].tolist()
        r["normal_force"] = f["contacts"][pair]["normal_force"][:].tolist()
        r["max_force_N"] = float(a["max_contact_force_N"])  # over the steps, not the rows
    return r


def hertz_curve(fmax, duration, n=400):
    """Hertz force history by integrating m* d'' = -K d^1.5 (shape only: scaled to fmax)."""
    # Dimensionless: x'' = -x^1.5 from (0, 1); scale to the printed fmax and duration.
    dt, x, v, xs = 1e-4, 0.0, 1.0, [0.0]
    while True:
        a1 = -max(x, 0) ** 1.5
        xh, vh = x + 0.5 * dt * v, v + 0.5 * dt * a1
        a2 = -max(xh, 0) ** 1.5
        x, v = x + dt * vh, v + dt * a2
        if x <= 0:
            break
        xs.append(x)
    f = np.array(xs) ** 1.5
    t = np.linspace(0, duration, len(f))
    return t, f / f.max() * fmax


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--models", default="h3,h4,h5,h6,g3,g4,g5,g6")
    ap.add_argument("--sweep", default=None, help="model for the penalty sweep, e.g. h3")
    ap.add_argument("--plot", default=None)
    ap.add_argument("--json", default=None)
    a = ap.parse_args()
    sid_dir = tempfile.mkdtemp(prefix="impact2d_")
    models = a.models.split(",")
    results = {}
    summary = {}
    print(f"{'model':6} {'F_max N':>9} {'Hertz N':>9} {'dF %':>7} {'T us':>7} {'dT %':>7} "
          f"{'wall s (median of %d)' % a.repeat:>22}")
    for m in models:
        body = os.path.join(ROOT, "configs", "bodies", f"sphere2d_{m}.yaml")
        subprocess.run([os.path.join(a.build, "bin", "igaprep"), "-q", body, "-o",
                        os.path.join(sid_dir, f"sphere2d_{m}.sid.h5")], check=True)
        scene = os.path.join(ROOT, "configs", "scenes", f"impact2d_{m}.yaml")
        runs = [run_scene(a.build, scene, sid_dir, os.path.join(sid_dir, f"r_{m}.h5"))
                for _ in range(a.repeat)]
        if "error" in runs[0]:
            print(f"{m:6} failed: {runs[0]['error']}")
            continue
        r = runs[0]
        r["wall_median_s"] = statistics.median(x["wall_time_s"] for x in runs)
        results[m] = r
        print(f"{m:6} {r['max_force_N']:9.3f} {r.get('hertz_force_N', float('nan')):9.3f} "
              f"{r.get('force_error_pct', float('nan')):+7.2f} "
              f"{r.get('hertz_duration_us', float('nan')) * (1 + r.get('duration_error_pct', 0) / 100):7.2f} "
              f"{r.get('duration_error_pct', float('nan')):+7.2f} {r['wall_median_s']:22.3f}")
    for n in "3456":
        if f"h{n}" in results and f"g{n}" in results:
            print(f"nlvl = {n}: wall time hierarchical / global = "
                  f"{results['h' + n]['wall_median_s'] / results['g' + n]['wall_median_s']:.2f}")
    if a.sweep:
        print(f"\npenalty sweep (paper Fig. 7) on {a.sweep}; penalty factor in N/m^3")
        scene = os.path.join(ROOT, "configs", "scenes", f"impact2d_{a.sweep}.yaml")
        sweep = []
        # Beyond 3e18 N/m^3 the equations are so stiff that one run takes many minutes.
        for cp in [1e15, 3e15, 1e16, 3e16, 1e17, 3e17, 1e18, 3e18]:
            r = run_scene(a.build, scene, sid_dir, os.path.join(sid_dir, "sweep.h5"), cp)
            if "error" in r:
                print(f"  cp = {cp:.0e}: failed: {r['error']}")
                continue
            sweep.append((cp, r.get("force_error_pct", float("nan"))))
            print(f"  cp = {cp:.0e}: F_max = {r['max_force_N']:.3f} N "
                  f"({r.get('force_error_pct', float('nan')):+.2f} % from Hertz), "
                  f"wall {r['wall_time_s']:.2f} s")
        summary["sweep"] = {"model": a.sweep, "penalty_N_per_m3": [c for c, _ in sweep],
                            "force_error_pct": [e for _, e in sweep]}
        if a.plot and sweep:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
            fig, ax = plt.subplots(figsize=(6, 4))
            ax.semilogx([c for c, _ in sweep], [e for _, e in sweep], "o-")
            ax.axhline(0.0, color="k", lw=0.8)
            ax.set_xlabel("penalty factor c_p [N/m³]")
            ax.set_ylabel("max. force − Hertz [%]")
            ax.set_title(f"Penalty sweep, sphere2d_{a.sweep} (paper Fig. 7)")
            fig.tight_layout()
            out = os.path.splitext(a.plot)[0] + "_sweep.png"
            fig.savefig(out, dpi=120)
            print(f"wrote {out}")
    if a.plot and results:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4.5))
        first = next(iter(results.values()))
        th, fh = hertz_curve(first["hertz_force_N"], first["hertz_duration_us"] * 1e-6)
        ax.plot(th * 1e6, fh, "k-", lw=2.5, label="Hertz")
        for m, r in results.items():
            ax.plot(np.array(r["time"]) * 1e6, r["normal_force"], lw=1, label=f"sphere2d_{m}")
        ax.set_xlabel("time [µs]")
        ax.set_ylabel("normal contact force [N]")
        ax.set_title("Two axisymmetric steel spheres, 0.1 m/s each (paper Fig. 8)")
        ax.legend()
        fig.tight_layout()
        fig.savefig(a.plot, dpi=120)
        print(f"\nplot: {a.plot}")
    if a.json:
        for r in results.values():
            r.pop("time", None)
            r.pop("normal_force", None)
        summary["models"] = results
        json.dump(summary, open(a.json, "w"), indent=1)


if __name__ == "__main__":
    sys.exit(main())
