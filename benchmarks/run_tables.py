#!/usr/bin/python3
"""Reproduces the preprocessing columns of the paper's Tables 1 and 2 with igaprep.

Runs `igaprep BODY.yaml -o OUT.sid.h5` on the paper's body files (configs/bodies/sphere2d_*.yaml,
sphere3d_*.yaml; the hierarchical models come with the THB spaces of issue 3) and, with
--extra, on the speed-check bodies in benchmarks/bodies/. For each run it reads the SID file
(root attributes ndof, nq, n_interface_control_points, nlvl) and measures the wall time and the
peak resident memory of the igaprep process (os.wait4), then prints a table with the paper's
values next to ours, and the same data as JSON (--json FILE).

Paper values (Tables 1 and 2: ndof, nq = modes + dim x interface points, preprocessing time in
MATLAB) are keyed by the body file name: sphere2d_h<N> / sphere3d_h<N> are the hierarchical
models with N levels, sphere2d_ref<N> / sphere3d_ref<N> (or *_global<N>) their globally refined
references.

usage: benchmarks/run_tables.py [--igaprep build/bin/igaprep] [--extra] [--json out.json]
                                [--threads N] [BODY.yaml ...]
"""
import argparse
import glob
import json
import os
import re
import subprocess
import sys
import tempfile
import time

import h5py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# (dim, kind, nlvl) -> (ndof, normal modes, interface points, time in s)
PAPER = {
    (2, "h", 3): (3856, 10, 41, 13), (2, "h", 4): (2884, 10, 40, 8),
    (2, "h", 5): (2728, 10, 42, 11), (2, "h", 6): (1708, 10, 41, 4),
    (2, "ref", 3): (9216, 10, 41, 44), (2, "ref", 4): (7440, 10, 40, 29),
    (2, "ref", 5): (6726, 10, 40, 24), (2, "ref", 6): (5368, 10, 39, 16),
    (3, "h", 3): (18891, 50, 273, 273), (3, "h", 4): (14940, 50, 297, 262),
    (3, "h", 5): (12711, 50, 321, 246),
    (3, "ref", 3): (139431, 50, 441, 100 * 60), (3, "ref", 4): (117267, 50, 441, 162 * 60),
    (3, "ref", 5): (92823, 50, 441, 128 * 60),
}
TARGET_S = {(2, "h"): 2, (2, "ref"): 2, (3, "h"): 30, (3, "ref"): 600}


def paper_key(path):
    name = os.path.basename(path)
    m = re.match(r"sphere([23])d_(h|g|ref|global)(\d)", name)
    if not m:
        return None
    kind = "h" if m.group(2) == "h" else "ref"
    return (int(m.group(1)), kind, int(m.group(3)))


def run(igaprep, body, out, threads):
    cmd = [igaprep, "-q", body, "-o", out]
    if threads:
        cmd += ["--threads", str(threads)]
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.monotonic() - start
    err = proc.stderr.read().decode()
    proc.stdout.close()
    proc.stderr.close()
    code = os.waitstatus_to_exitcode(status)
    return code, wall, usage.ru_maxrss / 1024.0, usage.ru_utime + usage.ru_stime, err.strip()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("bodies", nargs="*")
    ap.add_argument("--igaprep", default=os.path.join(ROOT, "build", "bin", "igaprep"))
    ap.add_argument("--extra", action="store_true", help="also run benchmarks/bodies/*.yaml")
    ap.add_argument("--json", help="write the results as JSON to this file")
    ap.add_argument("--threads", type=int, default=0)
    args = ap.parse_args()
    bodies = args.bodies or sorted(glob.glob(os.path.join(ROOT, "configs/bodies/sphere2d_*.yaml"))
                                   + glob.glob(os.path.join(ROOT, "configs/bodies/sphere3d_*.yaml")))
    if args.extra:
        bodies += sorted(glob.glob(os.path.join(ROOT, "benchmarks/bodies/*.yaml")))
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for body in bodies:
            out = os.path.join(tmp, os.path.basename(body) + ".sid.h5")
            code, wall, mem, cpu, err = run(args.igaprep, body, out, args.threads)
            row = {"body": os.path.relpath(body, ROOT), "exit": code, "wall_s": wall,
                   "cpu_s": cpu, "peak_mib": mem}
            if code == 0:
                with h5py.File(out, "r") as f:
                    a = f.attrs
                    row.update(ndof=int(a["ndof"]), nq=int(a["nq"]), nlvl=int(a["nlvl"]),
                               normal_modes=int(a["normal_modes"]),
                               constraint_modes=int(a["constraint_modes"]),
                               rigid_dropped=int(a["rigid_modes_dropped"]),
                               interface=int(a["n_interface_control_points"]),
                               dim=int(a["space_dim"]),
                               f_min_hz=float(f["sid/frequencies_hz"][0]),
                               f_max_hz=float(f["sid/frequencies_hz"][-1]))
            else:
                row["error"] = err
            key = paper_key(body)
            if key in PAPER:
                p = PAPER[key]
                row["paper"] = {"ndof": p[0], "nq": f"{p[1]}+{key[0]}x{p[2]}", "time_s": p[3]}
                row["target_s"] = TARGET_S[key[:2]]
            rows.append(row)
            print(f"  ran {row['body']}: exit {code}, {wall:.2f} s", file=sys.stderr)

    hdr = (f"{'body':<44} {'ndof':>7} {'nq (modes+dim x intf)':>24} {'intf':>5} {'wall s':>8} {'cpu s':>8} "
           f"{'peak MiB':>9} | {'paper ndof':>10} {'paper nq':>12} {'paper s':>8} {'target s':>8}")
    print(hdr)
    print("-" * len(hdr))
    for r in rows:
        if r["exit"] != 0:
            print(f"{r['body']:<44} FAILED (exit {r['exit']}): {r.get('error', '')[:80]}")
            continue
        nq = (f"{r['nq']} = {r['normal_modes']}+{r['dim']}x{r['interface']}"
              f"{'' if r['constraint_modes'] == r['dim'] * r['interface'] else '*'}"
              f"-{r['rigid_dropped']}")
        p = r.get("paper")
        ptxt = (f"{p['ndof']:>10} {p['nq']:>12} {p['time_s']:>8} {r['target_s']:>8}" if p
                else f"{'-':>10} {'-':>12} {'-':>8} {'-':>8}")
        print(f"{r['body']:<44} {r['ndof']:>7} {nq:>24} {r['interface']:>5} {r['wall_s']:>8.2f} {r['cpu_s']:>8.2f} "
              f"{r['peak_mib']:>9.1f} | {ptxt}")
    print("\n* constraint modes != dim x interface points: axis points (u_r = 0) have one DOF.")
    print("nq = normal + constraint modes - rigid directions dropped (paper: normal + dim x interface).")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=2)
    return 0 if all(r["exit"] == 0 for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
